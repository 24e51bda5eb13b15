// Avenues — boxes, spheres, cylinders and cones as triangles (see primitive_shapes.h).
#include "plans/primitive_shapes.h"

#include "core/affine.h"
#include "plans/polygon_triangulation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace avenues {

void box_shape(Vec3 size, ShapeTriangles out) {
  const int base = int(out.v.size());
  const Vec3 h = 0.5 * size;
  for (int c = 0; c < 8; ++c) out.v.push_back({c & 1 ? h.x : -h.x, c & 2 ? h.y : -h.y, c & 4 ? h.z : -h.z});
  // Each face's corners counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    out.tris.push_back({base + f[0], base + f[1], base + f[2]});
    out.tris.push_back({base + f[0], base + f[2], base + f[3]});
  }
}

void sphere_shape(double radius, int around, int bands, ShapeTriangles out) {
  around = std::clamp(around, 3, 256), bands = std::clamp(bands, 2, 256);
  const double pi = std::numbers::pi;
  const int top = int(out.v.size());
  out.v.push_back({0, radius, 0});
  for (int i = 1; i < bands; ++i) {
    const double a = pi * i / bands;
    for (int j = 0; j < around; ++j) {
      const double b = 2 * pi * j / around;
      out.v.push_back({radius * std::sin(a) * std::cos(b), radius * std::cos(a), radius * std::sin(a) * std::sin(b)});
    }
  }
  const int bottom = int(out.v.size());
  out.v.push_back({0, -radius, 0});
  auto at = [&](int ring, int j) { return top + 1 + (ring - 1) * around + (j % around); };
  // j runs clockwise seen from above (+y): b from +x towards +z.
  for (int j = 0; j < around; ++j) out.tris.push_back({top, at(1, j + 1), at(1, j)});
  for (int i = 1; i + 1 < bands; ++i)
    for (int j = 0; j < around; ++j) {
      out.tris.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      out.tris.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  for (int j = 0; j < around; ++j) out.tris.push_back({bottom, at(bands - 1, j), at(bands - 1, j + 1)});
}

void round_shape(double bottom_radius, double top_radius, double height, int around, bool side, bool top, bool bottom,
                 ShapeTriangles out) {
  around = std::clamp(around, 3, 256);
  const double pi = std::numbers::pi;
  const int base = int(out.v.size());
  for (int ring = 0; ring < 2; ++ring)  // the top ring, then the bottom one
    for (int j = 0; j < around; ++j) {
      const double b = 2 * pi * j / around, r = ring == 0 ? top_radius : bottom_radius;
      out.v.push_back({r * std::sin(b), ring == 0 ? height / 2 : -height / 2, r * std::cos(b)});
    }
  auto at = [&](int ring, int j) { return base + ring * around + (j % around); };
  // j runs anticlockwise seen from above (+y): b from +z towards +x.
  if (side)
    for (int j = 0; j < around; ++j) {
      out.tris.push_back({at(0, j), at(1, j), at(1, j + 1)});
      if (top_radius > 0) out.tris.push_back({at(0, j), at(1, j + 1), at(0, j + 1)});
    }
  const int centres = int(out.v.size());
  out.v.push_back({0, height / 2, 0});
  out.v.push_back({0, -height / 2, 0});
  for (int j = 0; j < around; ++j) {
    if (top && top_radius > 0) out.tris.push_back({centres, at(0, j), at(0, j + 1)});
    if (bottom && bottom_radius > 0) out.tris.push_back({centres + 1, at(1, j + 1), at(1, j)});
  }
}

void extrusion_shape(const Extrusion& e, ShapeTriangles out) {
  // Spine points that repeat the one before add nothing but a crease of no length.
  std::vector<size_t> at;  // the spine points kept, and what of scale and orientation they take
  for (size_t i = 0; i < e.spine.size(); ++i)
    if (at.empty() || !(e.spine[i] == e.spine[at.back()])) at.push_back(i);
  const bool closed_spine = at.size() > 2 && e.spine[at.front()] == e.spine[e.spine.size() - 1];
  if (closed_spine) at.pop_back();  // the last point is the first: wrapped round below
  std::vector<Vec2> cs = e.cross_section;
  const bool closed_section = cs.size() > 3 && cs.front() == cs.back();
  if (closed_section) cs.pop_back();
  const size_t n = at.size(), m = cs.size();
  if (n < 2 || m < 2) return;
  auto spine = [&](size_t k) { return e.spine[at[k % n]]; };
  auto unit = [](Vec3 v) -> std::optional<Vec3> {
    const double l = length(v);
    if (!(l > 1e-12) || !std::isfinite(l)) return std::nullopt;
    return (1 / l) * v;
  };
  // The spine-aligned cross-section planes: y along the spine, z across its bend.
  std::vector<Vec3> ys(n), zs(n);
  for (size_t k = 0; k < n; ++k) {
    const Vec3 before = closed_spine || k > 0 ? spine(k + n - 1) : spine(k);
    const Vec3 after = closed_spine || k + 1 < n ? spine(k + 1) : spine(k);
    ys[k] = unit(after - before).value_or(k > 0 ? ys[k - 1] : Vec3{0, 1, 0});
  }
  std::vector<std::optional<Vec3>> bend(n);
  for (size_t k = 0; k < n; ++k)
    if (closed_spine || (k > 0 && k + 1 < n)) bend[k] = unit(cross(spine(k + 1) - spine(k), spine(k + n - 1) - spine(k)));
  if (!closed_spine) bend[0] = n > 2 ? bend[1] : std::nullopt, bend[n - 1] = n > 2 ? bend[n - 2] : std::nullopt;
  const auto first_bend = std::find_if(bend.begin(), bend.end(), [](const auto& b) { return b.has_value(); });
  if (first_bend == bend.end()) {
    // A straight spine: the plane y = 0 turned as +y turns onto the spine.
    const Vec3 y = ys[0], up{0, 1, 0};
    const Vec3 axis = cross(up, y);
    const double angle = std::atan2(length(axis), dot(up, y));
    const Affine3 turn = length(axis) > 1e-12 ? Affine3::rotation(axis, angle)
                                              : (dot(up, y) < 0 ? Affine3::rotation({1, 0, 0}, std::numbers::pi) : Affine3{});
    const Vec3 z = turn.apply(Vec3{0, 0, 1}) - turn.apply(Vec3{0, 0, 0});
    for (size_t k = 0; k < n; ++k) zs[k] = z;
  } else {
    Vec3 last = **first_bend;
    for (size_t k = 0; k < n; ++k) {
      Vec3 z = bend[k].value_or(last);
      if (dot(z, last) < 0) z = -1.0 * z;  // the bend's sense kept from point to point
      zs[k] = last = z;
    }
  }
  // The rings of corners.
  const int base = int(out.v.size());
  for (size_t k = 0; k < n; ++k) {
    const size_t i = at[k];
    const Vec2 s = e.scale.empty() ? Vec2{1, 1} : e.scale[std::min(i, e.scale.size() - 1)];
    const std::array<double, 4> o = e.orientation.empty() ? std::array<double, 4>{0, 0, 1, 0}
                                                           : e.orientation[std::min(i, e.orientation.size() - 1)];
    const Affine3 turn = Affine3::rotation({o[0], o[1], o[2]}, o[3]);
    const Vec3 y = ys[k], z = zs[k], x = cross(y, z);
    for (const Vec2 c : cs) {
      const Vec3 local = turn.apply(Vec3{s.x * c.x, 0, s.y * c.y});
      out.v.push_back(spine(k) + local.x * x + local.y * y + local.z * z);
    }
  }
  const size_t first_tri = out.tris.size();
  auto corner = [&](size_t k, size_t j) { return base + int((k % n) * m + j % m); };
  auto add = [&](int a, int b, int c) {
    if (length(cross(out.v[size_t(b)] - out.v[size_t(a)], out.v[size_t(c)] - out.v[size_t(a)])) > 0) out.tris.push_back({a, b, c});
  };
  const size_t rings = closed_spine ? n : n - 1, sides = closed_section ? m : m - 1;
  for (size_t k = 0; k < rings; ++k)
    for (size_t j = 0; j < sides; ++j) {
      const int a = corner(k, j), b = corner(k, j + 1), c = corner(k + 1, j + 1), d = corner(k + 1, j);
      add(a, b, c), add(a, c, d);
    }
  // Caps: each edge of a ring is walked by the cap the other way from its side.
  const bool capped = !closed_spine && closed_section && m >= 3;
  for (const bool begin : {true, false}) {
    if (!capped || !(begin ? e.begin_cap : e.end_cap)) continue;
    std::vector<int> ring;
    for (size_t j = 0; j < m; ++j) ring.push_back(corner(begin ? 0 : n - 1, begin ? m - 1 - j : j));
    if (polygon_is_convex(out.v, ring)) {
      for (size_t j = 1; j + 1 < ring.size(); ++j) add(ring[0], ring[j], ring[j + 1]);
    } else {
      // Counter-clockwise about the ring's own normal: turned back where the ring turns the other way.
      Vec3 newell{0, 0, 0};
      for (size_t j = 0; j < ring.size(); ++j)
        newell = newell + cross(out.v[size_t(ring[j])], out.v[size_t(ring[(j + 1) % ring.size()])]);
      for (auto t : triangulate_polygon(out.v, ring)) {
        const Vec3 tn = cross(out.v[size_t(t[1])] - out.v[size_t(t[0])], out.v[size_t(t[2])] - out.v[size_t(t[0])]);
        if (dot(tn, newell) < 0) std::swap(t[1], t[2]);
        add(t[0], t[1], t[2]);
      }
    }
  }
  // A closed surface turned outward: by the sign of the volume it bounds.
  const bool closed = closed_section && (closed_spine || (capped && e.begin_cap && e.end_cap));
  if (closed) {
    double volume = 0;
    const Vec3 o = out.v[size_t(base)];
    for (size_t t = first_tri; t < out.tris.size(); ++t) {
      const auto& tri = out.tris[t];
      volume += dot(out.v[size_t(tri[0])] - o, cross(out.v[size_t(tri[1])] - o, out.v[size_t(tri[2])] - o));
    }
    if (volume < 0)
      for (size_t t = first_tri; t < out.tris.size(); ++t) std::swap(out.tris[t][1], out.tris[t][2]);
  }
}

}  // namespace avenues
