// Avenues — shadow outlines on a surface (see shadow_outline.h).
#include "render/shadow_outline.h"

#include <algorithm>
#include <cmath>

namespace avenues {

namespace {

/// Coordinates in the surface's plane.
struct PlaneFrame {
  Vec3 origin, u, v;
  Vec2 in(Vec3 p) const { return {dot(p - origin, u), dot(p - origin, v)}; }
  Vec3 out(Vec2 p) const { return origin + p.x * u + p.y * v; }
};

using Poly2 = std::vector<Vec2>;

bool inside(const Poly2& poly, Vec2 p) {
  const double orient = signed_area(poly) >= 0 ? 1 : -1;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    if (orient * cross(b - a, p - a) < 0) return false;
  }
  return true;
}

/// Parameter t along a→b where it crosses c→d, if it does (strictly inside both).
bool crossing(Vec2 a, Vec2 b, Vec2 c, Vec2 d, double& t) {
  const Vec2 r = b - a, s = d - c;
  const double den = cross(r, s);
  if (den == 0) return false;
  t = cross(c - a, s) / den;
  const double w = cross(c - a, r) / den;
  return t > 0 && t < 1 && w >= 0 && w <= 1;
}

}  // namespace

std::vector<std::array<Vec3, 2>> shadow_outline(const std::vector<Vec3>& surface, const SurfaceLight& light) {
  std::vector<std::array<Vec3, 2>> out;
  if (surface.size() < 3 || (light.whole && light.shadow.empty())) return out;
  Vec3 n{0, 0, 0};
  for (size_t i = 0; i < surface.size(); ++i) n = n + cross(surface[i], surface[(i + 1) % surface.size()]);
  const double nl = length(n);
  Vec3 u = surface[1] - surface[0];
  if (!(nl > 0) || !(length(u) > 0)) return out;
  n = (1 / nl) * n;
  u = (1 / length(u)) * u;
  const PlaneFrame f{surface[0], u, cross(n, u)};
  auto flat = [&](const std::vector<Vec3>& p) {
    Poly2 q;
    for (Vec3 x : p) q.push_back(f.in(x));
    return q;
  };
  const Poly2 s = flat(surface);
  std::vector<Poly2> lit, shadow;
  if (!light.whole)
    for (const auto& p : light.lit) lit.push_back(flat(p));
  for (const auto& p : light.shadow) shadow.push_back(flat(p));
  double size = 0;
  for (Vec2 p : s) size = std::max(size, length(p - s[0]));
  const double delta = 1e-6 * size;
  auto in_light = [&](Vec2 p) {
    const bool reached = light.whole || std::any_of(lit.begin(), lit.end(), [&](const Poly2& q) { return inside(q, p); });
    return reached && std::none_of(shadow.begin(), shadow.end(), [&](const Poly2& q) { return inside(q, p); });
  };
  std::vector<const Poly2*> all{&s};
  for (const Poly2& q : lit) all.push_back(&q);
  for (const Poly2& q : shadow) all.push_back(&q);
  std::vector<std::array<Vec2, 2>> kept;
  std::vector<double> ts;
  for (size_t k = 1; k < all.size(); ++k) {
    const Poly2& poly = *all[k];
    for (size_t i = 0; i < poly.size(); ++i) {
      const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
      const double len = length(b - a);
      if (!(len > delta)) continue;
      const Vec2 perp = (delta / len) * Vec2{a.y - b.y, b.x - a.x};
      ts.assign({0.0, 1.0});
      for (const Poly2* other : all)
        for (size_t j = 0; j < other->size(); ++j) {
          double t;
          if (crossing(a, b, (*other)[j], (*other)[(j + 1) % other->size()], t)) ts.push_back(t);
        }
      std::sort(ts.begin(), ts.end());
      for (size_t j = 0; j + 1 < ts.size(); ++j) {
        if (!((ts[j + 1] - ts[j]) * len > delta)) continue;
        const Vec2 m = a + (0.5 * (ts[j] + ts[j + 1])) * (b - a);
        const Vec2 left = m + perp, right = m - perp;
        if (!inside(s, left) || !inside(s, right)) continue;  // along the surface's own edge
        if (in_light(left) == in_light(right)) continue;
        const Vec2 p = a + ts[j] * (b - a), q = a + ts[j + 1] * (b - a);
        // Once: an edge lying on an edge kept already (a lit piece's edge on a shadow's) is not kept again.
        const bool seen = std::any_of(kept.begin(), kept.end(), [&](const std::array<Vec2, 2>& e) {
          const Vec2 d = e[1] - e[0];
          const double l = length(d);
          auto on = [&](Vec2 x) {
            const double t = dot(x - e[0], d) / (l * l);
            return std::fabs(cross(d, x - e[0])) <= delta * l && t >= -delta / l && t <= 1 + delta / l;
          };
          return l > 0 && on(p) && on(q);
        });
        if (!seen) kept.push_back({p, q});
      }
    }
  }
  for (const auto& e : kept) out.push_back({f.out(e[0]), f.out(e[1])});
  return out;
}

}  // namespace avenues
