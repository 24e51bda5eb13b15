// Avenues — find_visible in float and double; the exact kernel is in traverse_exact.cpp.
#include "visibility/traverse.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace avenues {

namespace detail {
template <>
double to_double_of<float>(const float& x) { return double(x); }
template <>
double to_double_of<double>(const double& x) { return x; }
}  // namespace detail

const char* to_string(Kernel k) {
  switch (k) {
    case Kernel::Float: return "float";
    case Kernel::Double: return "double";
    case Kernel::Filtered: return "filtered";
    case Kernel::Exact: return "exact";
  }
  return "?";
}

bool parse_kernel(const std::string& s, Kernel& out) {
  if (s == "float") out = Kernel::Float;
  else if (s == "double") out = Kernel::Double;
  else if (s == "filtered") out = Kernel::Filtered;
  else if (s == "exact") out = Kernel::Exact;
  else return false;
  return true;
}

std::vector<PortalId> VisibleSet::path(int avenue) const {
  std::vector<PortalId> p;
  for (int a = avenue; a >= 0 && avenues[size_t(a)].portal >= 0; a = avenues[size_t(a)].parent)
    p.push_back(avenues[size_t(a)].portal);
  std::reverse(p.begin(), p.end());
  return p;
}

void VisibleSet::collect_cells() {
  cells.clear();
  max_depth = 0;
  for (const Avenue& a : avenues) {
    cells.push_back(a.cell);
    max_depth = std::max(max_depth, a.depth);
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
}

namespace {
VisibleSet traverse(const CellComplex& complex, const Camera& camera, CellId eye_cell, const TraverseParams& params,
                    const Plane* cut) {
  const bool prune = params.prune_covered;
  const detail::Join join = params.hull_pieces    ? detail::Join::Hull
                            : params.merge_pieces ? detail::Join::Convex
                                                  : detail::Join::None;
  const TraverseParams::Strip* strip = params.strip && !camera.is_parallel() ? &*params.strip : nullptr;
  // The hull search's pictures resolve depth among every face found: the same bytes
  // without what no sample sees. The merged search's masks decide which cell a sample
  // shows, and other pieces merge into other masks.
  const int per_side = params.hull_pieces ? params.samples_per_side : 0;
  VisibleSet vs;
  switch (params.kernel) {
    case Kernel::Float:
      vs = detail::traverse_with<float>(complex, camera, eye_cell, prune, cut, join, strip, per_side);
      break;
    case Kernel::Double:
      vs = detail::traverse_with<double>(complex, camera, eye_cell, prune, cut, join, strip, per_side);
      break;
    case Kernel::Filtered: vs = detail::traverse_filtered(complex, camera, eye_cell, prune, cut, join, strip); break;
    case Kernel::Exact: vs = detail::traverse_exact(complex, camera, eye_cell, prune, cut, join, strip); break;
  }
  if (camera.is_parallel()) vs.cut = cut ? *cut : camera.picture_plane();
  return vs;
}
}  // namespace

VisibleSet find_visible(const CellComplex& complex, const Camera& camera, CellId eye_cell, const TraverseParams& params) {
  return traverse(complex, camera, eye_cell, params, nullptr);
}

bool cut_plane_usable(const Camera& camera, const Plane& cut) {
  const double n = length(cut.n);
  return n > 0 && std::isfinite(n) && std::isfinite(cut.d) && std::fabs(dot(cut.n, camera.forward)) > 1e-6 * n;
}

VisibleSet find_visible_from_cut(const CellComplex& complex, const Camera& camera, const Plane& cut, Kernel kernel) {
  TraverseParams params;
  params.kernel = kernel;
  return find_visible_from_cut(complex, camera, cut, params);
}

VisibleSet find_visible_from_cut(const CellComplex& complex, const Camera& camera, const Plane& cut,
                                 const TraverseParams& params) {
  if (!camera.is_parallel()) throw std::invalid_argument("find_visible_from_cut needs a parallel projection");
  if (!cut_plane_usable(camera, cut)) throw std::invalid_argument("the cut plane is parallel to the direction of view");
  return traverse(complex, camera, kNoCell, params, &cut);
}

VisibleSet find_visible(const CellComplex& complex, const Camera& camera, CellId eye_cell, Kernel kernel) {
  TraverseParams params;
  params.kernel = kernel;
  return find_visible(complex, camera, eye_cell, params);
}

std::vector<CellId> frustum_cells(const CellComplex& complex, const Camera& cam) {
  // The four side planes of the view pyramid, as inward normals through the eye.
  const double hw = cam.half_width(), hh = cam.half_height();
  const Vec3 corners[4] = {
      (cam.shift_x - hw) * cam.right + (cam.shift_y - hh) * cam.up + cam.forward,
      (cam.shift_x + hw) * cam.right + (cam.shift_y - hh) * cam.up + cam.forward,
      (cam.shift_x + hw) * cam.right + (cam.shift_y + hh) * cam.up + cam.forward,
      (cam.shift_x - hw) * cam.right + (cam.shift_y + hh) * cam.up + cam.forward};
  Vec3 n[4];
  for (int k = 0; k < 4; ++k) n[k] = cross(corners[k], corners[(k + 1) % 4]);
  std::vector<CellId> out;
  for (CellId id = 0; id < CellId(complex.cells.size()); ++id) {
    Box3 b = complex.cells[size_t(id)].bounds();
    bool inside = true;
    for (int k = 0; k < 4 && inside; ++k) {
      // The box meets the half-space if its corner farthest along n does.
      Vec3 far{n[k].x >= 0 ? b.hi.x : b.lo.x, n[k].y >= 0 ? b.hi.y : b.lo.y, n[k].z >= 0 ? b.hi.z : b.lo.z};
      inside = dot(n[k], far - cam.eye) >= 0;
    }
    if (inside) out.push_back(id);
  }
  return out;
}

}  // namespace avenues
