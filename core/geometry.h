// Avenues — small value types shared by every module.
//
// Plain doubles in metres, +z up. Kept deliberately tiny (pbrt-v4 style: distinct
// point types, no hidden conversions); exact arithmetic lives behind cells/'s CGAL
// boundary, and nothing downstream of it sees a CGAL type.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace avenues {

struct Vec2 {
  double x = 0, y = 0;  ///< [m]
  friend Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  friend Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  friend Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
  friend bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
};
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double length(Vec2 a) { return std::hypot(a.x, a.y); }
/// Distance from p to the segment a–b (to a, when a and b coincide).
inline double distance_to_segment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double dd = dot(d, d);
  const double t = dd > 0 ? std::clamp(dot(p - a, d) / dd, 0.0, 1.0) : 0.0;
  return length(p - (a + t * d));
}

struct Vec3 {
  double x = 0, y = 0, z = 0;  ///< [m]
  friend Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
  friend bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
};
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }

/// Closed containment of q, lying in the plane of the convex polygon `poly` (either
/// orientation) whose normal is n: no edge has q farther than `tol` [m] on its outer side
/// while another has it farther than `tol` on its inner side.
inline bool in_convex_polygon(const std::vector<Vec3>& poly, Vec3 n, Vec3 q, double tol) {
  bool pos = false, neg = false;
  for (size_t k = 0; k < poly.size(); ++k) {
    const Vec3 a = poly[k], b = poly[(k + 1) % poly.size()];
    const double s = dot(cross(b - a, q - a), n) / length(b - a);  // signed distance of q from the edge
    pos |= s > tol;
    neg |= s < -tol;
  }
  return !(pos && neg);
}

/// Sutherland–Hodgman cut of a planar polygon to the half-space f(X) >= 0 (f affine).
template <class F>
std::vector<Vec3> cut_polygon(const std::vector<Vec3>& in, F f) {
  std::vector<Vec3> out;
  const size_t n = in.size();
  for (size_t i = 0; i < n; ++i) {
    const Vec3 a = in[i], b = in[(i + 1) % n];
    const double fa = f(a), fb = f(b);
    if (fa >= 0) out.push_back(a);
    if ((fa >= 0) != (fb >= 0)) out.push_back(a + (fa / (fa - fb)) * (b - a));
  }
  return out;
}

/// Normal of a planar polygon in space (convex, or simple and fanned from its first
/// vertex), turned by its corners' order (right hand), twice its area long.
inline Vec3 polygon_normal(const std::vector<Vec3>& p) {
  Vec3 n{0, 0, 0};
  for (size_t i = 0; i + 2 < p.size(); ++i) n = n + cross(p[i + 1] - p[0], p[i + 2] - p[0]);
  return n;
}

/// Area [m²] of a planar polygon in space (convex, or simple and fanned from its first vertex).
inline double polygon_area(const std::vector<Vec3>& p) { return 0.5 * length(polygon_normal(p)); }

/// Signed area [m²] of a simple polygon: positive when counter-clockwise. Taken about its
/// first corner, so that a plan placed in national grid coordinates (x 2,500,000 m) keeps
/// its square millimetres: about the origin each product would be 1e13 and lose them.
inline double signed_area(const std::vector<Vec2>& p) {
  if (p.empty()) return 0;
  double a = 0;
  for (size_t i = 1, n = p.size(); i + 1 < n; ++i) a += cross(p[i] - p[0], p[i + 1] - p[0]);
  return a / 2;
}

/// Whether p lies inside the polygon (even–odd: a ray to +x crosses its edges an odd number
/// of times); either orientation, any simple or self-touching polygon.
inline bool inside_polygon(const std::vector<Vec2>& poly, Vec2 p) {
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2 a = poly[i], b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)) in = !in;
  }
  return in;
}

/// The convex hull of points, counter-clockwise (Andrew's monotone chain); collinear
/// points dropped. Fewer than three distinct points come back as they are, sorted.
inline std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }), p.end());
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

/// Whether p is a convex polygon, counter-clockwise, with an area: at least three points,
/// no turn to the right (a straight one allowed), turning once around.
inline bool is_convex_ccw(const std::vector<Vec2>& p) {
  if (p.size() < 3 || !(signed_area(p) > 0)) return false;
  double turned = 0;
  for (size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 a = p[i], b = p[(i + 1) % n], c = p[(i + 2) % n];
    if (cross(b - a, c - b) < 0) return false;
    turned += std::atan2(cross(b - a, c - b), dot(b - a, c - b));
  }
  return turned < 2 * 3.14159265358979323846 + 1e-6;  // once around, not a star
}

/// Area centroid of a simple polygon (the vertex mean when it has no area), about its first
/// corner as signed_area is.
inline Vec2 centroid(const std::vector<Vec2>& p) {
  if (p.empty()) return {};
  const Vec2 o = p[0];
  double a = 0, cx = 0, cy = 0;
  for (size_t i = 0, n = p.size(); i < n; ++i) {
    const Vec2 u = p[i] - o, v = p[(i + 1) % n] - o;
    const double w = cross(u, v);
    a += w, cx += (u.x + v.x) * w, cy += (u.y + v.y) * w;
  }
  if (std::fabs(a) < 1e-12) {
    Vec2 s;
    for (Vec2 q : p) s = s + (q - o);
    return o + (1.0 / double(p.size())) * s;
  }
  return o + Vec2{cx / (3 * a), cy / (3 * a)};
}

/// Axis-aligned box; empty when lo > hi on any axis.
struct Box3 {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void add(Vec3 p) {
    lo = {std::fmin(lo.x, p.x), std::fmin(lo.y, p.y), std::fmin(lo.z, p.z)};
    hi = {std::fmax(hi.x, p.x), std::fmax(hi.y, p.y), std::fmax(hi.z, p.z)};
  }
  bool contains(Vec3 p, double tol = 0) const {
    return p.x >= lo.x - tol && p.x <= hi.x + tol && p.y >= lo.y - tol && p.y <= hi.y + tol &&
           p.z >= lo.z - tol && p.z <= hi.z + tol;
  }
  /// Whether this box and o grown by tol share a point (closed).
  bool meets(const Box3& o, double tol = 0) const {
    return lo.x <= o.hi.x + tol && o.lo.x - tol <= hi.x && lo.y <= o.hi.y + tol && o.lo.y - tol <= hi.y &&
           lo.z <= o.hi.z + tol && o.lo.z - tol <= hi.z;
  }
  Box3 grown(double tol) const { return {lo - Vec3{tol, tol, tol}, hi + Vec3{tol, tol, tol}}; }
  /// [m] The largest magnitude of a coordinate in the box, and at least 1: the scale of the
  /// rounding of the points in it (a tolerance is a relative one times this).
  double magnitude() const {
    return std::max({1.0, std::fabs(lo.x), std::fabs(hi.x), std::fabs(lo.y), std::fabs(hi.y), std::fabs(lo.z),
                     std::fabs(hi.z)});
  }
};

/// Plane n·p + d = 0. For a cell's face, n points out of the cell (unit length).
struct Plane {
  Vec3 n;
  double d = 0;
  double eval(Vec3 p) const { return dot(n, p) + d; }
};

}  // namespace avenues
