// Avenues — boxes, spheres, cylinders and cones as triangles (see primitive_shapes.h).
#include "plans/primitive_shapes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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

}  // namespace avenues
