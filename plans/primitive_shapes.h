// Avenues — the solids scene formats name instead of giving their faces: a box, a sphere, a
// cylinder and a cone (Irrlicht's cube and sphere nodes, VRML's Box, Sphere, Cylinder and
// Cone), as triangles about the origin with y as their axis, each with (b − a) × (c − a)
// pointing out of the solid; and a cross-section swept along a spine (VRML's Extrusion).
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

/// A cross-section swept along a spine, as VRML97 defines its Extrusion (ISO/IEC 14772-1,
/// 6.18): at each spine point the cross-section (x, z pairs) is scaled by that point's
/// `scale`, turned by its `orientation` (axis x, y, z and angle [rad]) and set in the
/// spine-aligned cross-section plane there (y along the spine, z across its bend, the bend
/// of a straight spine being the turn of +y onto it); a spine whose first and last points
/// coincide is closed. `scale` and `orientation` hold one value for every spine point, or
/// one for all (a shorter list repeats its last; empty: 1 × 1 and no turn). Caps (the
/// cross-section at the first and the last spine point, convex or not) as asked, unless
/// the spine is closed. Triangles of no area are left out. Where the surface is closed (a
/// closed cross-section, capped or swept round a closed spine), (b − a) × (c − a) points out
/// of it; otherwise the sides turn as the cross-section does.
struct Extrusion {
  std::vector<Vec2> cross_section{{1, 1}, {1, -1}, {-1, -1}, {-1, 1}, {1, 1}};
  std::vector<Vec3> spine{{0, 0, 0}, {0, 1, 0}};
  std::vector<Vec2> scale{{1, 1}};
  std::vector<std::array<double, 4>> orientation{{0, 0, 1, 0}};
  bool begin_cap = true, end_cap = true;
};
void extrusion_shape(const Extrusion& e, ShapeTriangles out);

}  // namespace avenues
