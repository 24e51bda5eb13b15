// Avenues — the solids scene formats name instead of giving their faces: a box, a sphere, a
// cylinder and a cone (Irrlicht's cube and sphere nodes, VRML's Box, Sphere, Cylinder and
// Cone), as triangles about the origin with y as their axis, each with (b − a) × (c − a)
// pointing out of the solid.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"

namespace avenues {

/// Triangles appended to `tris` over vertices appended to `v` (indices into all of `v`).
struct ShapeTriangles {
  std::vector<Vec3>& v;
  std::vector<std::array<int, 3>>& tris;
};

/// A box `size` across (x, y, z), centred on the origin.
void box_shape(Vec3 size, ShapeTriangles out);
/// A sphere of `radius`, `around` segments about y and `bands` from pole to pole (each at
/// least 3 and 2, at most 256).
void sphere_shape(double radius, int around, int bands, ShapeTriangles out);
/// A cylinder (`top_radius` == `bottom_radius`) or a cone (`top_radius` 0) about y, from
/// −height/2 to height/2, `around` segments; its side, top and bottom as asked.
void round_shape(double bottom_radius, double top_radius, double height, int around, bool side, bool top, bool bottom,
                 ShapeTriangles out);

}  // namespace avenues
