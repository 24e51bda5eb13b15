// Avenues — the mask: Jones's convex outline on the picture plane through which a cell
// is still seen.
//
// Robust by design. A mask is kept as a counter-clockwise cycle of half-planes
// a·x + b·y + c >= 0 on the picture plane, never as a list of constructed points. Each
// half-plane is the trace of a plane through the eye and two *original* portal vertices
// (or a side of the view window): its coefficients are one cross product of input
// differences, rotated into camera space. A vertex of the mask is computed afresh,
// each time it is needed, as the meeting point of its two neighbouring half-planes —
// so no constructed value is ever fed back into another construction, and the error
// of a mask after 200 portals is the error of one line intersection, not of 200.
// Every test ("is this vertex inside that half-plane") is then a predicate of degree 3
// in input coordinates, evaluated in the kernel's number type T: float or double (fast,
// a bounded relative error), or exact rationals (slow, no error at all).
//
// Why no near plane: a portal straddling the eye's near plane, or the very doorway the
// eye stands in, is a window in space, not a drawn object. The rays through it are the
// intersection of its edge planes' half-spaces, whatever its depth; clipping it at a
// near plane would close a doorway the eye stands in. The near plane is applied only
// where lines and faces are drawn.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

namespace avenues {

/// Half-plane a·x + b·y + c >= 0 on the picture plane.
template <class T>
struct HalfPlane {
  T a, b, c;
};

template <class T>
struct Point2T {
  T x, y;
};

template <class T>
class Mask {
 public:
  Mask() = default;
  /// The view window [x0, x1] × [y0, y1] on the picture plane.
  static Mask window(T x0, T x1, T y0, T y1) {
    Mask m;
    m.h_ = {{T(0), T(1), -y0}, {T(-1), T(0), x1}, {T(0), T(-1), y1}, {T(1), T(0), -x0}};
    return m;
  }
  bool empty() const { return h_.size() < 3; }
  const std::vector<HalfPlane<T>>& half_planes() const { return h_; }

  /// Vertex k: where half-plane k-1 meets half-plane k (computed from the two, afresh).
  Point2T<T> vertex(size_t k) const {
    const HalfPlane<T>& p = h_[(k + h_.size() - 1) % h_.size()];
    const HalfPlane<T>& q = h_[k];
    T det = p.a * q.b - q.a * p.b;
    return {(p.b * q.c - q.b * p.c) / det, (p.c * q.a - q.c * p.a) / det};
  }
  std::vector<Point2T<T>> polygon() const {
    std::vector<Point2T<T>> v;
    for (size_t k = 0; k < h_.size(); ++k) v.push_back(vertex(k));
    return v;
  }

  /// Intersects the mask with half-plane l. Returns false when nothing of area is left
  /// (the mask is then empty). A half-plane containing the whole mask changes nothing.
  bool clip(const HalfPlane<T>& l) {
    const size_t n = h_.size();
    if (n < 3) return false;
    // Sign of l at each vertex (scratch buffers per thread: a mask is copied at every
    // portal, and carrying its scratch along would allocate three times per copy).
    thread_local std::vector<int> side_;
    thread_local std::vector<HalfPlane<T>> next_;
    side_.resize(n);
    bool any_out = false, any_in = false;
    for (size_t k = 0; k < n; ++k) {
      Point2T<T> v = vertex(k);
      T s = l.a * v.x + l.b * v.y + l.c;
      if constexpr (std::is_floating_point_v<T>) {
        // Floating point: a sign smaller than the evaluation's rounding error is taken as
        // zero ("on the line"), so a half-plane that only touches the mask — the same
        // portal edge met again from the next cell — is never added twice, which would
        // leave two parallel neighbours and no vertex between them. Exact number types
        // need no such bound.
        const T bound = kSignBound * (std::fabs(l.a * v.x) + std::fabs(l.b * v.y) + std::fabs(l.c));
        if (!(std::fabs(s) > bound)) s = T(0);
      }
      side_[k] = s > T(0) ? 1 : (s < T(0) ? -1 : 0);
      any_out |= side_[k] < 0;
      any_in |= side_[k] > 0;
    }
    if (!any_out) return true;  // l contains the mask
    if (!any_in) {              // nothing of area left
      h_.clear();
      return false;
    }
    // Edge k runs from vertex k to vertex k+1 along half-plane k. Keep the edges that
    // have a part strictly inside l; l follows the edge on which the boundary leaves l's
    // inside: the one ending outside, or ending on l when the next edge does not go back in
    // (a mask merely touching l at a vertex is left as it is).
    next_.clear();
    auto keep = [&](size_t k) { return side_[k % n] > 0 || side_[(k + 1) % n] > 0; };
    for (size_t k = 0; k < n; ++k) {
      if (!keep(k)) continue;
      next_.push_back(h_[k]);
      const int end = side_[(k + 1) % n];
      if (end < 0 || (end == 0 && !keep(k + 1))) next_.push_back(l);
    }
    h_.assign(next_.begin(), next_.end());
    if (h_.size() < 3) {
      h_.clear();
      return false;
    }
    return true;
  }

  /// True only when this mask certainly lies inside `outer` (closed): every vertex inside
  /// every half-plane of `outer` (convex in convex). Exact number types decide it exactly. In
  /// floating point a vertex must lie inside by more than the evaluation's rounding bound,
  /// so a mask touching `outer`'s boundary from inside, or equal to it, is not taken as
  /// inside: the answer errs only towards "not inside".
  bool inside(const Mask& outer) const {
    if (empty() || outer.empty()) return false;
    for (size_t k = 0; k < h_.size(); ++k) {
      const Point2T<T> v = vertex(k);
      for (const HalfPlane<T>& l : outer.h_) {
        const T s = l.a * v.x + l.b * v.y + l.c;
        if constexpr (std::is_floating_point_v<T>) {
          const T bound = kSignBound * (std::fabs(l.a * v.x) + std::fabs(l.b * v.y) + std::fabs(l.c));
          if (!(s > bound)) return false;
        } else {
          if (s < T(0)) return false;
        }
      }
    }
    return true;
  }

  /// The same cycle of half-planes, coefficient for coefficient (from the same index on):
  /// the same region, exactly, in any number type.
  bool same_as(const Mask& o) const {
    const size_t n = h_.size();
    if (n < 3 || o.h_.size() != n) return false;
    for (size_t shift = 0; shift < n; ++shift) {
      bool all = true;
      for (size_t k = 0; k < n && all; ++k) {
        const HalfPlane<T>& p = h_[k];
        const HalfPlane<T>& q = o.h_[(k + shift) % n];
        all = p.a == q.a && p.b == q.b && p.c == q.c;
      }
      if (all) return true;
    }
    return false;
  }

  /// Twice the signed area (positive for a proper counter-clockwise mask).
  T area2() const {
    T a(0);
    auto v = polygon();
    for (size_t k = 0; k < v.size(); ++k) {
      const auto& p = v[k];
      const auto& q = v[(k + 1) % v.size()];
      a += p.x * q.y - q.x * p.y;
    }
    return a;
  }

 private:
  /// Relative error bound of a sign evaluation in floating point: vertices are two
  /// divisions of degree-2 terms, then one more degree-1 evaluation; 2^7 ulps covers it.
  static constexpr double kSignBound = std::is_floating_point_v<T> ? 128 * double(std::numeric_limits<T>::epsilon()) : 0;
  std::vector<HalfPlane<T>> h_;
};

}  // namespace avenues
