// Avenues — a circular arc through three points (see arc.h).
#include "plans/arc.h"

#include <algorithm>
#include <numbers>

namespace avenues {

std::optional<Arc> arc_through(Vec2 a, Vec2 m, Vec2 b) {
  const Vec2 u = m - a, v = b - a;
  const double c = cross(u, v);
  if (!(std::fabs(c) > 1e-9 * length(u) * length(v))) return std::nullopt;
  // Circumcentre relative to a (the standard formula, translated for precision).
  const double uu = dot(u, u), vv = dot(v, v);
  const Vec2 o{(v.y * uu - u.y * vv) / (2 * c), (u.x * vv - v.x * uu) / (2 * c)};
  Arc arc;
  arc.centre = a + o;
  arc.radius = length(o);
  // Points a, m, b in counter-clockwise order around the triangle are met in that
  // order going counter-clockwise round the circle, so the sweep's sign is c's.
  arc.start = std::atan2(a.y - arc.centre.y, a.x - arc.centre.x);
  double sweep = std::atan2(b.y - arc.centre.y, b.x - arc.centre.x) - arc.start;
  const double two_pi = 2 * std::numbers::pi;
  if (c > 0) {
    while (sweep <= 0) sweep += two_pi;
  } else {
    while (sweep >= 0) sweep -= two_pi;
  }
  arc.sweep = sweep;
  return arc;
}

double Arc::pieces_for(double tol) const {
  const double max_piece = tol >= radius ? std::numbers::pi : 2 * std::acos(1 - tol / radius);
  return std::max(2.0, std::ceil(std::fabs(sweep) / max_piece - 1e-9));
}

void Arc::append(long n, Vec2 b, std::vector<Vec2>& out) const {
  const double pieces = static_cast<double>(n);
  for (long i = 1; i < n; ++i) {
    const double t = start + sweep * static_cast<double>(i) / pieces;
    out.push_back({centre.x + radius * std::cos(t), centre.y + radius * std::sin(t)});
  }
  out.push_back(b);
}

}  // namespace avenues
