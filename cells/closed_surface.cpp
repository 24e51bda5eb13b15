// Avenues — a closed surface: what lies inside it, and where a segment first enters it
// (closed_surface.h).
#include "cells/closed_surface.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace avenues {

namespace {

constexpr int32_t kLeaf = 8;  // triangles a leaf holds at most

double along(Vec3 p, int axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; }

/// The parameter range [t0, t1] of the line a + t·d inside the box, clipped to [0, t_max];
/// false when that is empty.
bool line_meets(const Box3& b, Vec3 a, Vec3 d, double t_max) {
  double t0 = 0, t1 = t_max;
  for (int axis = 0; axis < 3; ++axis) {
    const double o = along(a, axis), v = along(d, axis), lo = along(b.lo, axis), hi = along(b.hi, axis);
    if (v == 0) {
      if (o < lo || o > hi) return false;
      continue;
    }
    double n = (lo - o) / v, f = (hi - o) / v;
    if (n > f) std::swap(n, f);
    t0 = std::max(t0, n), t1 = std::min(t1, f);
    if (t0 > t1) return false;
  }
  return true;
}


}  // namespace

bool line_plane_hit(const Triangle3& tri, Vec3 a, Vec3 d, double* t, double* u, double* v) {
  const Vec3 e1 = tri[1] - tri[0], e2 = tri[2] - tri[0];
  const Vec3 q = cross(d, e2);
  const double det = dot(e1, q);
  if (det == 0 || !std::isfinite(det)) return false;
  const double inv = 1 / det;
  const Vec3 s = a - tri[0];
  *u = dot(s, q) * inv;
  const Vec3 r = cross(s, e1);
  *v = dot(d, r) * inv;
  *t = dot(e2, r) * inv;
  return true;
}

double winding_number(const std::vector<Triangle3>& triangles, Vec3 p) {
  double sum = 0;
  for (const Triangle3& t : triangles) {
    const Vec3 a = t[0] - p, b = t[1] - p, c = t[2] - p;
    const double la = length(a), lb = length(b), lc = length(c);
    const double num = dot(a, cross(b, c));
    const double den = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
    sum += 2 * std::atan2(num, den);
  }
  return sum / (4 * std::numbers::pi);
}

ClosedSurface::ClosedSurface(std::string name, std::vector<Triangle3> triangles)
    : name_(std::move(name)), triangles_(std::move(triangles)) {
  for (const Triangle3& t : triangles_)
    for (Vec3 p : t) box_.add(p);
  if (triangles_.empty()) return;
  std::vector<Vec3> centres;
  centres.reserve(triangles_.size());
  for (const Triangle3& t : triangles_) centres.push_back((1.0 / 3) * (t[0] + t[1] + t[2]));
  std::vector<int32_t> order(triangles_.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = int32_t(i);
  nodes_.reserve(2 * (triangles_.size() / size_t(kLeaf) + 1) * 2);
  nodes_.emplace_back();
  build(0, 0, int32_t(triangles_.size()), order, centres);
  std::vector<Triangle3> in_order;
  in_order.reserve(triangles_.size());
  for (int32_t i : order) in_order.push_back(triangles_[size_t(i)]);
  triangles_ = std::move(in_order);
}

void ClosedSurface::build(int32_t node, int32_t first, int32_t count, std::vector<int32_t>& order,
                          const std::vector<Vec3>& centres) {
  Box3 b, c;
  for (int32_t k = first; k < first + count; ++k) {
    for (Vec3 p : triangles_[size_t(order[size_t(k)])]) b.add(p);
    c.add(centres[size_t(order[size_t(k)])]);
  }
  nodes_[size_t(node)].box = b;
  if (count <= kLeaf) {
    nodes_[size_t(node)].first = first;
    nodes_[size_t(node)].count = count;
    return;
  }
  const Vec3 e = c.hi - c.lo;
  const int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
  const int32_t mid = first + count / 2;
  std::nth_element(order.begin() + first, order.begin() + mid, order.begin() + first + count,
                   [&](int32_t i, int32_t j) {
                     const double a = along(centres[size_t(i)], axis), b2 = along(centres[size_t(j)], axis);
                     return a < b2 || (a == b2 && i < j);
                   });
  const int32_t child = int32_t(nodes_.size());
  nodes_.emplace_back();
  nodes_.emplace_back();
  nodes_[size_t(node)].first = child;
  nodes_[size_t(node)].count = 0;
  build(child, first, mid - first, order, centres);
  build(child + 1, mid, first + count - mid, order, centres);
}

template <class F>
bool ClosedSurface::for_each_near(Vec3 a, Vec3 d, const double* t_max, F&& f) const {
  if (nodes_.empty()) return true;
  int32_t stack[64];  // median splits keep the tree under 40 deep; the stack holds a node a level
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0) {
    const Node& n = nodes_[size_t(stack[--depth])];
    if (!line_meets(n.box, a, d, *t_max)) continue;
    if (n.count == 0) {
      stack[depth++] = n.first, stack[depth++] = n.first + 1;
      continue;
    }
    for (int32_t k = n.first; k < n.first + n.count; ++k)
      if (!f(triangles_[size_t(k)])) return false;
  }
  return true;
}

SurfaceEntry ClosedSurface::entry(Vec3 a, Vec3 b) const {
  SurfaceEntry best;
  const Vec3 d = b - a;
  for_each_near(a, d, &best.t, [&](const Triangle3& tri) {
    const Vec3 normal = cross(tri[1] - tri[0], tri[2] - tri[0]);
    if (!(dot(normal, d) < 0)) return true;  // leaving, or along it: not stopped
    double t, u, v;
    if (!line_plane_hit(tri, a, d, &t, &u, &v)) return true;
    // Edges and corners count (a segment through a seam between two facets is stopped).
    if (!(t >= 0 && t <= best.t && u >= 0 && v >= 0 && u + v <= 1)) return true;
    best.t = t;
    best.hit = true;
    best.normal = (1 / length(normal)) * normal;
    return true;
  });
  return best;
}

bool ClosedSurface::crossings(Vec3 p, Vec3 d, int* sum) const {
  constexpr double kNear = 1e-9;  // a barycentric coordinate this close to 0: on an edge
  const double unbounded = HUGE_VAL;
  return for_each_near(p, d, &unbounded, [&](const Triangle3& tri) {
    const Vec3 normal = cross(tri[1] - tri[0], tri[2] - tri[0]);
    double t, u, v;
    if (!line_plane_hit(tri, p, d, &t, &u, &v)) {
      // Parallel: a ray in the triangle's plane may graze it; too near to tell.
      const double l = length(normal);
      return !(l > 0 && std::fabs(dot(p - tri[0], normal)) <= kNear * l * (1 + length(tri[1] - tri[0])));
    }
    const double w = 1 - u - v;
    if (u < -kNear || v < -kNear || w < -kNear || t < -kNear) return true;  // clearly missed
    if (u <= kNear || v <= kNear || w <= kNear || t <= kNear) return false;  // on an edge, or p on it
    *sum += dot(normal, d) > 0 ? 1 : -1;
    return true;
  });
}

bool ClosedSurface::holds(Vec3 p) const {
  if (nodes_.empty() || !box_.contains(p)) return false;
  // Crossings counted along a ray: leaving minus entering is 1 inside a closed, outward
  // surface and 0 outside. Directions along no axis and no simple diagonal, so that a ray
  // rarely meets a modelled edge; where one does, the next direction, and at last the
  // winding number itself (exact for any closed surface, and slower).
  static const Vec3 kRays[3] = {{0.8017837257372732, 0.5345224838248488, 0.2672612419124244},
                                {-0.3015113445777636, 0.9045340337332909, -0.3015113445777636},
                                {0.2182178902359924, -0.4364357804719848, -0.8728715609439696}};
  for (Vec3 d : kRays) {
    int sum = 0;
    if (crossings(p, d, &sum)) return sum >= 1;
  }
  return winding_number(triangles_, p) > 0.5;
}

}  // namespace avenues
