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

#include <algorithm>
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

  /// The bounds of a mask's vertices (floating point; exact number types: none needed).
  struct Reach {
    T lo_x{}, hi_x{}, lo_y{}, hi_y{};
  };
  /// The vertices of one state of a mask, each computed once, with their bounds (floating
  /// point): for a mask narrowed by many portals in turn (every portal of a cell starts
  /// from the mask it was reached through), which would otherwise compute the same
  /// vertices again at each. They are the values vertex() gives, and only ever read, never
  /// fed into a construction.
  struct Corners {
    std::vector<Point2T<T>> at;  ///< at[k] == vertex(k)
    Reach reach;                 ///< their bounds, as reach() gives them
  };
  /// Fills `out` with this mask's vertices and their bounds (its storage reused).
  void corners(Corners& out) const {
    out.at.resize(h_.size());
    for (size_t k = 0; k < h_.size(); ++k) out.at[k] = vertex(k);
    out.reach = reach_of(out.at.size(), [&out](size_t k) { return out.at[k]; });
  }

  /// Intersects the mask with half-plane l. Returns false when nothing of area is left
  /// (the mask is then empty). A half-plane containing the whole mask changes nothing.
  /// `now`, where given and not null, points to the mask's corners as it stands, used
  /// instead of computing its vertices; it is set to null when the clip changes the mask.
  bool clip(const HalfPlane<T>& l, const Corners** now = nullptr) {
    const size_t n = h_.size();
    if (n < 3) return false;
    const Point2T<T>* known = now && *now ? (*now)->at.data() : nullptr;
    // Sign of l at each vertex (scratch buffers per thread: a mask is copied at every
    // portal, and carrying its scratch along would allocate three times per copy).
    thread_local std::vector<int> side_;
    thread_local std::vector<HalfPlane<T>> next_;
    side_.resize(n);
    bool any_out = false, any_in = false;
    for (size_t k = 0; k < n; ++k) {
      const Point2T<T> v = known ? known[k] : vertex(k);
      T s = l.a * v.x + l.b * v.y + l.c;
      if constexpr (std::is_floating_point_v<T>) {
        // Floating point: a sign smaller than the evaluation's rounding error is taken as
        // zero ("on the line"), so a half-plane that only touches the mask — the same
        // portal edge met again from the next cell — is never added twice, which would
        // leave two parallel neighbours and no vertex between them. Exact number types
        // need no such bound.
        if (!(std::fabs(s) > rounding_bound(l, v))) s = T(0);
      }
      side_[k] = s > T(0) ? 1 : (s < T(0) ? -1 : 0);
      any_out |= side_[k] < 0;
      any_in |= side_[k] > 0;
    }
    if (!any_out) return true;  // l contains the mask
    if (now) *now = nullptr;
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
          if (!(s > rounding_bound(l, v))) return false;
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

  /// Becomes the union of this mask and `o` when that union is convex and the two meet
  /// along a whole edge: one has a half-plane L and the other its opposite (the same line,
  /// as when two avenues into one cell were parted by the edge between two portals). With
  /// A' and B' the masks without L and without its opposite, A ∪ B = A' ∩ B' exactly when
  /// A ⊂ B' and B ⊂ A' (and A' ∩ B' never holds more than A ∪ B): so the test is every
  /// vertex of each inside the other's remaining half-planes, exact in exact number types;
  /// floating point admits a vertex outside by its rounding bound, which can only lose a
  /// sliver of that width, never add one. Returns false (and leaves the mask as it was)
  /// when they do not merge.
  bool absorb(const Mask& o) {
    const size_t n = h_.size(), m = o.h_.size();
    if (n < 3 || m < 3) return false;
    for (size_t k = 0; k < n; ++k)
      for (size_t j = 0; j < m; ++j) {
        if (!opposite(h_[k], o.h_[j])) continue;
        if (!vertices_inside(o, *this, k) || !vertices_inside(*this, o, j)) return false;
        thread_local std::vector<HalfPlane<T>> u;
        u.clear();
        for (size_t i = 1; i < n; ++i) u.push_back(h_[(k + i) % n]);
        const size_t first_of_o = u.size();
        for (size_t i = 1; i < m; ++i) u.push_back(o.h_[(j + i) % m]);
        // Where the cycles join, an edge of one may run straight on into an edge of the
        // other (the outline crossing L without a turn): one line, kept once. Both pass
        // through the end of the shared edge, so in floating point two lines within an
        // angle of kCollinear are taken as one (a wedge of that angle is all it can change),
        // rather than met at a point their rounding would put anywhere along them.
        auto same_direction = [](const HalfPlane<T>& p, const HalfPlane<T>& q) {
          const T cr = p.a * q.b - q.a * p.b;
          const T dt = p.a * q.a + p.b * q.b;
          if constexpr (std::is_floating_point_v<T>) {
            const T bound = T(kCollinear) * std::sqrt((p.a * p.a + p.b * p.b) * (q.a * q.a + q.b * q.b));
            return !(std::fabs(cr) > bound) && dt > T(0);
          } else {
            return cr == T(0) && dt > T(0);
          }
        };
        if (same_direction(u.back(), u.front())) u.pop_back();
        if (first_of_o < u.size() && same_direction(u[first_of_o - 1], u[first_of_o]))
          u.erase(u.begin() + long(first_of_o));
        if (u.size() < 3) return false;
        h_.assign(u.begin(), u.end());
        return true;
      }
    return false;
  }

  /// The convex hull of points (the vertices of several masks): the smallest convex mask
  /// holding them all, for the hull search (TraverseParams::hull_pieces), which trades a
  /// mask's exactness for one avenue per cell. Its sides are lines through two of the
  /// points, not traces of portal planes. Exact number types make the hull exactly; in
  /// floating point every side is moved outward by far more than the points' rounding
  /// (kHullGrowth of the points' extent), so the hull holds every point however the
  /// orientation tests round; with `grow_out` false they are not moved, for a mask remade
  /// from its own vertices (settle_within), whose corners then stay where those were. Empty
  /// when the points span no area.
  static Mask hull(std::vector<Point2T<T>>& points, bool grow_out = true) {
    Mask m;
    if (points.size() < 3) return m;
    std::sort(points.begin(), points.end(),
              [](const Point2T<T>& p, const Point2T<T>& q) { return p.x < q.x || (p.x == q.x && p.y < q.y); });
    auto turn = [](const Point2T<T>& o, const Point2T<T>& a, const Point2T<T>& b) {
      return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
    };
    // Andrew's monotone chain: the lower hull left to right, then the upper right to left.
    thread_local std::vector<Point2T<T>> chain;
    chain.clear();
    for (int pass = 0; pass < 2; ++pass) {
      const size_t floor = chain.size();
      for (size_t i = 0; i < points.size(); ++i) {
        const Point2T<T>& p = points[pass == 0 ? i : points.size() - 1 - i];
        while (chain.size() >= floor + 2 && !(turn(chain[chain.size() - 2], chain.back(), p) > T(0))) chain.pop_back();
        chain.push_back(p);
      }
      chain.pop_back();  // the last point of each pass starts the other
    }
    bool near_dropped = false;  // floating point, growing: a corner near a chord dropped (below)
    if constexpr (std::is_floating_point_v<T>) {
      // Two sides that nearly run on in one line meet at a vertex their rounding would put
      // anywhere along them: in floating point a corner turning by less than kCollinear
      // goes (it lies within kCollinear of the side that replaces it, far inside the growth
      // below). Taken out of the finished cycle, where its neighbours are its neighbours
      // along the outline (in the sweep, points of a nearly vertical side come in the order
      // of their x's rounding).
      // Growing, a corner within a quarter of the growth of the chord between its
      // neighbours goes too. Kept, it ends a side far shorter than the growth, and each of
      // the sides' moves shifts its vertices along nearly parallel neighbours: the side
      // between them then points anywhere (a Viking room view's hull had a side 3.5e-6
      // long, 3.5e-9 off the chord, turned by 9e-4, and the outline through the hull's
      // vertices passed 2.5e-5 inside a point it holds, 0.03 away). Dropped corners can
      // add up, so the sides are then moved out as far as every point needs.
      T slack(0);
      if (grow_out) {
        T extent(0);
        for (const Point2T<T>& p : chain) extent = std::max({extent, T(std::fabs(p.x)), T(std::fabs(p.y))});
        slack = T(kHullGrowth / 4) * (T(1) + extent);
      }
      for (bool again = true; again && chain.size() >= 3;) {
        again = false;
        for (size_t k = 0; k < chain.size() && chain.size() >= 3; ++k) {
          const Point2T<T>& o = chain[(k + chain.size() - 1) % chain.size()];
          const Point2T<T>& b = chain[(k + 1) % chain.size()];
          const T ax = chain[k].x - o.x, ay = chain[k].y - o.y, bx = b.x - o.x, by = b.y - o.y;
          const T cross = ax * by - ay * bx;
          if (cross > T(kCollinear) * std::sqrt((ax * ax + ay * ay) * (bx * bx + by * by))) {
            if (!(cross * cross <= slack * slack * (bx * bx + by * by))) continue;  // farther than slack
            near_dropped = true;
          }
          chain.erase(chain.begin() + long(k));
          again = true;
        }
      }
    }
    if (chain.size() < 3) return m;
    T grow(0);
    if constexpr (std::is_floating_point_v<T>) {
      T extent(0);
      for (const Point2T<T>& p : chain) extent = std::max({extent, T(std::fabs(p.x)), T(std::fabs(p.y))});
      if (grow_out) grow = T(kHullGrowth) * (T(1) + extent);
    }
    m.h_.reserve(chain.size());  // one allocation, not one per doubling
    for (size_t k = 0; k < chain.size(); ++k) {
      const Point2T<T>& p = chain[k];
      const Point2T<T>& q = chain[(k + 1) % chain.size()];
      // Inside: left of p → q, (q − p) × (x − p) >= 0.
      HalfPlane<T> l{p.y - q.y, q.x - p.x, T(0)};
      l.c = -(l.a * p.x + l.b * p.y);
      if constexpr (std::is_floating_point_v<T>) {
        l.c += grow * (std::fabs(l.a) + std::fabs(l.b));
        if (near_dropped) {  // every point inside, by a quarter of the growth
          T least(0);
          for (const Point2T<T>& x : points) least = std::min(least, l.a * x.x + l.b * x.y + l.c);
          if (least < T(0)) l.c += grow / T(4) * (std::fabs(l.a) + std::fabs(l.b)) - least;
        }
      }
      m.h_.push_back(l);
    }
    // Vertex k meets side k−1 and side k: the hull's sides are in order from chain[0].
    return m;
  }

  /// Whether this mask lies inside `outer` up to the hull's growth: every vertex held by
  /// `outer` as holds_up_to_growth() says (floating point: within twice kHullGrowth of its
  /// extent of every half-plane and of `outer`'s bounds; exact number types: closed,
  /// exactly). The hull search's test for pieces that add nothing to what a cell was
  /// searched through already.
  bool within(const Mask& outer) const {
    if (empty() || outer.empty()) return false;
    const Reach r = outer.reach();
    for (size_t k = 0; k < h_.size(); ++k)
      if (!outer.holds_up_to_growth(vertex(k), r)) return false;
    return true;
  }

  /// After this mask was clipped from `before`: in floating point, a vertex where two nearly
  /// parallel sides meet lands anywhere along them that their rounding puts it, even outside
  /// `before`, where no clip can reach (a soup's portal whose edges nearly run on in one
  /// line left a needle of no area with a corner 0.07 across the picture, and the cell
  /// beyond was drawn there). Such a vertex is settled, and the mask remade as the hull of
  /// its vertices so settled:
  /// - outside a half-plane of `before` by more than the hull's slack (as within()): dropped;
  /// - inside them but beyond the bounds of `before`'s vertices (it ran on past the tip of a
  ///   needle, along its sides, or past a corner where one of its sides nearly runs on in
  ///   the portal's edge) by more than the slack: moved onto those bounds. Such a vertex lies
  ///   on the line of a side of `before`; clamped to the bounds, it comes back to the end of
  ///   that side, not away from the mask (a triangle of 0.06 by 0.2 across a duplex view had
  ///   its corner 1e-7 past its parent's: dropping that corner lost the triangle).
  /// The mask is empty when the vertices kept span no area, or when the hull's own vertices
  /// stray again. Exact number types: nothing to settle. Returns whether the mask has area;
  /// `settled`, when given, is set when a vertex was dropped or moved.
  bool settle_within(const Mask& before, bool* settled = nullptr) {
    if constexpr (std::is_floating_point_v<T>) {
      if (empty() || before.empty()) return !empty();
      thread_local Corners own, theirs;
      corners(own);
      before.corners(theirs);
      return settle_within(before, theirs, own, settled);
    } else {
      return !empty();
    }
  }
  /// The same, given the corners of `before` and this mask's own (as corners() makes them).
  bool settle_within(const Mask& before, const Corners& before_corners, const Corners& own, bool* settled = nullptr) {
    if constexpr (std::is_floating_point_v<T>) {
      if (empty() || before.empty()) return !empty();
      const Reach& r = before_corners.reach;
      thread_local std::vector<Point2T<T>> kept;
      kept.clear();
      bool moved = false;
      for (size_t k = 0; k < h_.size(); ++k) {
        const Point2T<T> v = own.at[k];
        const T grow = growth_at(v);
        if (!before.in_half_planes_up_to(v, grow)) {
          moved = true;
          continue;
        }
        Point2T<T> c{std::clamp(v.x, r.lo_x, r.hi_x), std::clamp(v.y, r.lo_y, r.hi_y)};
        if (c.x != v.x && !(std::fabs(c.x - v.x) > grow)) c.x = v.x;  // within the slack: kept
        if (c.y != v.y && !(std::fabs(c.y - v.y) > grow)) c.y = v.y;
        moved = moved || c.x != v.x || c.y != v.y;
        kept.push_back(c);
      }
      if (!moved) return true;
      if (settled) *settled = true;
      *this = hull(kept, false);
      if (empty() || !(area2() > T(0))) {
        h_.clear();
        return false;
      }
      // The hull's sides meet where their rounding puts them, too: a needle's, anywhere.
      for (size_t k = 0; k < h_.size(); ++k)
        if (!before.holds_up_to_growth(vertex(k), r)) {
          h_.clear();
          return false;
        }
      return true;
    } else {
      return !empty();
    }
  }

  /// Twice the signed area (positive for a proper counter-clockwise mask).
  T area2() const {
    // The vertices as polygon() gives them, in the same order, without allocating: a mask's
    // area is asked at every portal it passes.
    return area2_of(h_.size(), [this](size_t k) { return vertex(k); });
  }
  /// The same from its corners (the same sum, in the same order).
  static T area2(const Corners& c) {
    return area2_of(c.at.size(), [&c](size_t k) { return c.at[k]; });
  }

 private:
  template <class V>
  static T area2_of(size_t n, V vertex_at) {
    T a(0);
    if (n == 0) return a;
    const Point2T<T> first = vertex_at(0);
    Point2T<T> p = first;
    for (size_t k = 0; k < n; ++k) {
      const Point2T<T> q = k + 1 < n ? vertex_at(k + 1) : first;
      a += p.x * q.y - q.x * p.y;
      p = q;
    }
    return a;
  }

  Reach reach() const {
    return reach_of(h_.size(), [this](size_t k) { return vertex(k); });
  }
  /// The bounds of n vertices, vertex_at(k) each (exact number types: none).
  template <class V>
  static Reach reach_of(size_t n, V vertex_at) {
    Reach r;
    if constexpr (std::is_floating_point_v<T>) {
      r.lo_x = r.lo_y = std::numeric_limits<T>::infinity(), r.hi_x = r.hi_y = -r.lo_x;
      for (size_t k = 0; k < n; ++k) {
        const Point2T<T> v = vertex_at(k);
        r.lo_x = std::min(r.lo_x, v.x), r.hi_x = std::max(r.hi_x, v.x);
        r.lo_y = std::min(r.lo_y, v.y), r.hi_y = std::max(r.hi_y, v.y);
      }
    }
    return r;
  }

  /// Whether point v lies in this mask up to the hull's growth: within()'s test, and
  /// settle_within()'s. Exact number types: inside every half-plane (closed), exactly.
  /// Floating point: inside every half-plane or outside it by at most twice kHullGrowth of
  /// v's extent, and inside the bounds of the mask's vertices (`r`, its reach()) grown as
  /// much. The bounds are what holds a needle: along a needle's two nearly parallel sides a
  /// point far beyond its tip lies outside each by less than the slack (a duplex view's
  /// piece reached 8.7e-4 past the tip of the needle it was clipped from, 1.3e-8 outside
  /// its sides).
  bool holds_up_to_growth(const Point2T<T>& v, const Reach& r) const {
    if constexpr (std::is_floating_point_v<T>) {
      const T grow = growth_at(v);
      if (v.x < r.lo_x - grow || v.x > r.hi_x + grow || v.y < r.lo_y - grow || v.y > r.hi_y + grow) return false;
      return in_half_planes_up_to(v, grow);
    } else {
      return in_half_planes_up_to(v, T(0));
    }
  }

  /// The hull's slack at v: twice kHullGrowth of v's extent (exact number types: none).
  static T growth_at(const Point2T<T>& v) {
    if constexpr (std::is_floating_point_v<T>) {
      return T(2 * kHullGrowth) * (T(1) + std::max(std::fabs(v.x), std::fabs(v.y)));
    } else {
      return T(0);
    }
  }

  /// Whether v lies inside every half-plane, or outside it by at most `grow` (closed).
  bool in_half_planes_up_to(const Point2T<T>& v, const T& grow) const {
    for (const HalfPlane<T>& l : h_) {
      if constexpr (std::is_floating_point_v<T>) {
        if (l.a * v.x + l.b * v.y + l.c < -grow * (std::fabs(l.a) + std::fabs(l.b))) return false;
      } else {
        if (l.a * v.x + l.b * v.y + l.c < T(0)) return false;
      }
    }
    return true;
  }

  /// Floating point: the rounding bound of l's sign at vertex v (a computed vertex, then one
  /// degree-1 evaluation); a sign no larger is taken as zero.
  static T rounding_bound(const HalfPlane<T>& l, const Point2T<T>& v) {
    return T(kSignBound * (std::fabs(l.a * v.x) + std::fabs(l.b * v.y) + std::fabs(l.c)));
  }

  /// Whether p and q are one line with opposite insides: exactly in exact number types,
  /// within rounding in floating point.
  static bool opposite(const HalfPlane<T>& p, const HalfPlane<T>& q) {
    if (!(p.a * q.a + p.b * q.b < T(0))) return false;
    const T ab = p.a * q.b - q.a * p.b, ac = p.a * q.c - q.a * p.c, bc = p.b * q.c - q.b * p.c;
    if constexpr (std::is_floating_point_v<T>) {
      auto small = [](T d, T x, T y) { return !(std::fabs(d) > kSignBound * (std::fabs(x) + std::fabs(y))); };
      return small(ab, p.a * q.b, q.a * p.b) && small(ac, p.a * q.c, q.a * p.c) && small(bc, p.b * q.c, q.b * p.c);
    } else {
      return ab == T(0) && ac == T(0) && bc == T(0);
    }
  }

  /// Every vertex of `v` inside every half-plane of `of` but its half-plane `skip` (closed;
  /// floating point admits the rounding bound).
  static bool vertices_inside(const Mask& v, const Mask& of, size_t skip) {
    for (size_t k = 0; k < v.h_.size(); ++k) {
      const Point2T<T> p = v.vertex(k);
      for (size_t i = 0; i < of.h_.size(); ++i) {
        if (i == skip) continue;
        const HalfPlane<T>& l = of.h_[i];
        const T s = l.a * p.x + l.b * p.y + l.c;
        if constexpr (std::is_floating_point_v<T>) {
          if (s < -rounding_bound(l, p)) return false;
        } else {
          if (s < T(0)) return false;
        }
      }
    }
    return true;
  }

  /// Relative error bound of a sign evaluation in floating point: vertices are two
  /// divisions of degree-2 terms, then one more degree-1 evaluation; 2^7 ulps covers it.
  /// [rad] Floating point: lines meeting at a smaller angle are one line where masks merge.
  static constexpr double kCollinear = std::is_same_v<T, float> ? 1e-4 : 1e-9;
  /// Floating point: how far each side of a hull is moved outward, relative to the points'
  /// extent (1 + their largest coordinate): above their rounding and the points a nearly
  /// straight turn drops (kCollinear), far below a sample in double.
  static constexpr double kHullGrowth = std::is_same_v<T, float> ? 1e-3 : 1e-8;
  static constexpr double kSignBound = std::is_floating_point_v<T> ? 128 * double(std::numeric_limits<T>::epsilon()) : 0;
  std::vector<HalfPlane<T>> h_;
};

}  // namespace avenues
