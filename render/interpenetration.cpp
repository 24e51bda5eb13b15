// Avenues — crossing polygons, found once per scene (see interpenetration.h).
#include "render/interpenetration.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>

namespace avenues {

namespace {

/// A triangle of the scene with what it belongs to.
struct Tri {
  std::array<Vec3, 3> v;
  std::array<int, 3> index{-1, -1, -1};  ///< its mesh's vertex indices (-1: a face of a cell)
  int owner = -1;                        ///< object or mesh; -1: a face of a cell
  Vec3 lo, hi;                           ///< bounding box
};

Tri make_tri(const std::array<Vec3, 3>& v, std::array<int, 3> index, int owner) {
  Tri t{v, index, owner, v[0], v[0]};
  for (const Vec3& p : v) {
    t.lo = {std::min(t.lo.x, p.x), std::min(t.lo.y, p.y), std::min(t.lo.z, p.z)};
    t.hi = {std::max(t.hi.x, p.x), std::max(t.hi.y, p.y), std::max(t.hi.z, p.z)};
  }
  return t;
}

void add_mesh(const Mesh& m, int owner, std::vector<Tri>& out) {
  for (const auto& t : m.triangles)
    out.push_back(make_tri({m.vertices[size_t(t[0])], m.vertices[size_t(t[1])], m.vertices[size_t(t[2])]},
                           {t[0], t[1], t[2]}, owner));
}

bool neighbours(const Tri& a, const Tri& b) {
  if (a.owner != b.owner || a.owner < 0) return false;
  for (int i : a.index)
    for (int j : b.index)
      if (i == j) return true;
  return false;
}

/// [m] tolerance for a pair: a billionth of their size, at least 1e-9 m.
double tolerance_of(const Tri& a, const Tri& b) {
  double m = 1;
  for (const Tri* t : {&a, &b})
    for (const Vec3& p : {t->lo, t->hi}) m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  return 1e-9 * m;
}

/// Sweeps the triangles' boxes along x; calls name(a, b) for the first crossing pair.
template <class Name>
bool sweep(std::vector<Tri>& tris, Interpenetration& out, Name name) {
  std::sort(tris.begin(), tris.end(), [](const Tri& a, const Tri& b) { return a.lo.x < b.lo.x; });
  for (size_t i = 0; i < tris.size(); ++i) {
    const Tri& a = tris[i];
    for (size_t j = i + 1; j < tris.size() && tris[j].lo.x <= a.hi.x; ++j) {
      const Tri& b = tris[j];
      if ((a.owner < 0 && b.owner < 0) || neighbours(a, b)) continue;  // faces of a convex cell never cross
      if (b.lo.y > a.hi.y || a.lo.y > b.hi.y || b.lo.z > a.hi.z || a.lo.z > b.hi.z) continue;
      ++out.pairs_tested;
      if (!triangles_cross(a.v, b.v, tolerance_of(a, b))) continue;
      out.found = true;
      out.what = name(a.owner, b.owner);
      return true;
    }
  }
  return false;
}

/// Signed distances of t's corners from o's plane; false when o has no plane.
bool distances(const std::array<Vec3, 3>& t, const std::array<Vec3, 3>& o, Vec3& n, std::array<double, 3>& d) {
  n = cross(o[1] - o[0], o[2] - o[0]);
  const double l = length(n);
  if (!(l > 0)) return false;
  n = (1 / l) * n;
  for (size_t k = 0; k < 3; ++k) d[k] = dot(n, t[k] - o[0]);
  return true;
}

bool straddles(const std::array<double, 3>& d, double tol) {
  return std::max({d[0], d[1], d[2]}) > tol && std::min({d[0], d[1], d[2]}) < -tol;
}

/// The extent along `dir` of where triangle t meets the other plane (t's distances d).
void interval(const std::array<Vec3, 3>& t, const std::array<double, 3>& d, Vec3 dir, double tol, double& lo,
              double& hi) {
  lo = HUGE_VAL;
  hi = -HUGE_VAL;
  auto at = [&](Vec3 p) {
    const double s = dot(dir, p);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  };
  for (size_t k = 0; k < 3; ++k) {
    const size_t m = (k + 1) % 3;
    if (std::fabs(d[k]) <= tol) at(t[k]);
    if ((d[k] > tol && d[m] < -tol) || (d[k] < -tol && d[m] > tol)) at(t[k] + (d[k] / (d[k] - d[m])) * (t[m] - t[k]));
  }
}

}  // namespace

bool triangles_cross(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, double tol) {
  Vec3 na, nb;
  std::array<double, 3> da{}, db{};
  // Each must have corners strictly on both sides of the other's plane (Möller's early outs).
  if (!distances(a, b, nb, da) || !straddles(da, tol)) return false;
  if (!distances(b, a, na, db) || !straddles(db, tol)) return false;
  Vec3 dir = cross(na, nb);
  const double l = length(dir);
  if (!(l > 0)) return false;
  dir = (1 / l) * dir;
  double lo_a, hi_a, lo_b, hi_b;
  interval(a, da, dir, tol, lo_a, hi_a);
  interval(b, db, dir, tol, lo_b, hi_b);
  return std::min(hi_a, hi_b) - std::max(lo_a, lo_b) > tol;
}

Interpenetration find_interpenetration(const CellComplex& complex, const std::vector<PlacedObject>& objects) {
  Interpenetration out;
  const ObjectsByCell by_cell = objects_by_cell(complex.cells.size(), objects);
  std::vector<Tri> tris;
  for (size_t c = 0; c < complex.cells.size(); ++c) {
    const std::span<const uint32_t> in_cell = by_cell.of(CellId(c));
    if (in_cell.empty()) continue;
    tris.clear();
    for (const uint32_t entry : in_cell) {
      const uint32_t o = entry & ~ObjectsByCell::kCut;
      add_mesh(objects[o].mesh, int(o), tris);
    }
    for (const Face& f : complex.cells[c].faces)
      for (size_t k = 1; k + 1 < f.poly.size(); ++k) tris.push_back(make_tri({f.poly[0], f.poly[k], f.poly[k + 1]}, {-1, -1, -1}, -1));
    auto name = [&](int a, int b) {
      if (a < 0 || (b >= 0 && b < a)) std::swap(a, b);  // the object first, the earlier object first
      const std::string first = "object '" + objects[size_t(a)].name + "'";
      if (b < 0) return first + " and a face of its cell cross";
      if (a == b) return first + " passes through itself";
      return first + " and object '" + objects[size_t(b)].name + "' cross";
    };
    if (sweep(tris, out, name)) return out;
  }
  return out;
}

Interpenetration find_interpenetration(const std::vector<Mesh>& meshes) {
  Interpenetration out;
  std::vector<Tri> tris;
  for (size_t m = 0; m < meshes.size(); ++m) add_mesh(meshes[m], int(m), tris);
  auto label = [&](int m) {
    const std::string file = std::filesystem::path(meshes[size_t(m)].path).filename().string();
    return "mesh " + std::to_string(m + 1) + (file.empty() ? "" : " (" + file + ")");
  };
  sweep(tris, out, [&](int a, int b) {
    if (b < a) std::swap(a, b);
    return a == b ? label(a) + " passes through itself" : label(a) + " and " + label(b) + " cross";
  });
  return out;
}

}  // namespace avenues
