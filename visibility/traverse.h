// Avenues — the traversal, generic over its number type T (internal to visibility/).
//
// Jones 1971: "On arriving at a node ... there will be a representation of the current
// mask ... the first opening of the cell is examined ... A new mask is formed from the
// intersection of the current mask and the boundary of the opening projected on to the
// picture plane. If the intersection is empty then this opening is not visible ...
// Otherwise ... the algorithm now descends a level." Like Godot's portal tracer we skip
// portals seen from behind first; unlike it there is no depth cap — a cell already on the
// current avenue is never entered again (a straight ray cannot revisit a convex cell),
// which bounds the search even where rounding errs.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>

#include "visibility/mask.h"
#include "visibility/visible_set.h"

namespace avenues::detail {

template <class T>
double to_double_of(const T& x);

template <class T>
struct Vec3T {
  T x, y, z;
};
template <class T>
Vec3T<T> sub(const Vec3T<T>& a, const Vec3T<T>& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
template <class T>
Vec3T<T> crossT(const Vec3T<T>& a, const Vec3T<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
T dotT(const Vec3T<T>& a, const Vec3T<T>& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

template <class T>
class Traversal {
 public:
  Traversal(const CellComplex& c, const Camera& cam, VisibleSet& out) : c_(c), out_(out) {
    eye_ = in(cam.eye);
    right_ = in(cam.right);
    up_ = in(cam.up);
    forward_ = in(cam.forward);
    const double hw = cam.half_width(), hh = cam.half_height();
    window_ = Mask<T>::window(T(cam.shift_x - hw), T(cam.shift_x + hw), T(cam.shift_y - hh), T(cam.shift_y + hh));
    on_path_.assign(c.cells.size(), 0);
  }

  void run(CellId start) {
    Mask<T> m = window_;
    visit(start, m, -1, -1, 0);
  }

 private:
  static Vec3T<T> in(Vec3 v) { return {T(v.x), T(v.y), T(v.z)}; }

  /// Picture-plane half-plane of the world plane through the eye with normal n:
  /// directions d = x·right + y·up + forward with n·d >= 0.
  HalfPlane<T> trace(const Vec3T<T>& n) const { return {dotT(n, right_), dotT(n, up_), dotT(n, forward_)}; }

  void visit(CellId cell, const Mask<T>& mask, int parent, PortalId via, int depth) {
    const int self = int(out_.avenues.size());
    Avenue a;
    a.cell = cell;
    a.parent = parent;
    a.portal = via;
    a.depth = depth;
    for (const auto& v : mask.polygon()) a.mask.push_back({to_double_of(v.x), to_double_of(v.y)});
    out_.avenues.push_back(std::move(a));
    out_.max_depth = std::max(out_.max_depth, depth);
    on_path_[size_t(cell)] = 1;
    for (PortalId pi : c_.cells[size_t(cell)].portals) {
      if (pi == via) continue;
      const Portal& p = c_.portals[size_t(pi)];
      const CellId other = p.other(cell);
      if (on_path_[size_t(other)]) continue;
      ++out_.portals_tested;
      // Which side of the portal's plane is the eye on? Exactly, from input vertices.
      const Vec3T<T> v0 = in(p.poly[0]), v1 = in(p.poly[1]), v2 = in(p.poly[2]);
      const Vec3T<T> N = crossT(sub(v1, v0), sub(v2, v0));  // points into p.cell[1]
      const T s = dotT(N, sub(eye_, v0));
      const bool from_first = cell == p.cell[0];
      Mask<T> m = mask;
      if (s == T(0)) {
        // The eye stands in the portal's plane: through it, if it stands in the portal,
        // lies the whole half-space on the far side; otherwise it is seen edge-on.
        if (!eye_in_polygon(p, N)) continue;
        const Vec3T<T> toward = from_first ? N : Vec3T<T>{-N.x, -N.y, -N.z};
        if (!m.clip(trace(toward))) continue;
      } else {
        if ((s < T(0)) != from_first) continue;  // seen from behind
        // Rays through the portal: inside every plane through the eye and an edge.
        // With the eye behind N (s < 0) the edge normals (a-e)×(b-e) point inwards.
        bool alive = true;
        const size_t n = p.poly.size();
        for (size_t k = 0; k < n && alive; ++k) {
          Vec3T<T> e = crossT(sub(in(p.poly[k]), eye_), sub(in(p.poly[(k + 1) % n]), eye_));
          if (s > T(0)) e = {-e.x, -e.y, -e.z};
          alive = m.clip(trace(e));
        }
        if (!alive) continue;
      }
      if (!(m.area2() > T(0))) continue;
      visit(other, m, self, pi, depth + 1);
    }
    on_path_[size_t(cell)] = 0;
  }

  /// Closed point-in-convex-polygon test of the eye, which lies in the polygon's plane.
  bool eye_in_polygon(const Portal& p, const Vec3T<T>& N) const {
    const size_t n = p.poly.size();
    for (size_t k = 0; k < n; ++k) {
      Vec3T<T> a = in(p.poly[k]), b = in(p.poly[(k + 1) % n]);
      if (dotT(crossT(sub(b, a), sub(eye_, a)), N) < T(0)) return false;
    }
    return true;
  }

  const CellComplex& c_;
  VisibleSet& out_;
  Vec3T<T> eye_, right_, up_, forward_;
  Mask<T> window_;
  std::vector<uint8_t> on_path_;
};

template <class T>
VisibleSet traverse_with(const CellComplex& c, const Camera& cam, CellId eye_cell) {
  VisibleSet out;
  out.eye_cell = eye_cell;
  auto t0 = std::chrono::steady_clock::now();
  Traversal<T>(c, cam, out).run(eye_cell);
  out.micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  for (const Avenue& a : out.avenues) out.cells.push_back(a.cell);
  std::sort(out.cells.begin(), out.cells.end());
  out.cells.erase(std::unique(out.cells.begin(), out.cells.end()), out.cells.end());
  return out;
}

VisibleSet traverse_exact(const CellComplex& c, const Camera& cam, CellId eye_cell);
VisibleSet traverse_filtered(const CellComplex& c, const Camera& cam, CellId eye_cell);

}  // namespace avenues::detail
