// Avenues — the outline of the shadows on a surface, for hidden-line drawings.
//
// A draughtsman draws a cast shadow by its outline. On one planar surface lit by one point
// light the lit region is the union of its lit pieces (all of it when whole) less the union
// of its shadow polygons (shadows.h); its outline is every part of those polygons' edges with
// light on one side and shadow on the other. Each candidate edge is cut where any other edge
// crosses it, and each piece is kept when a point just to its left and one just to its right
// differ in light. Parts along the surface's own edges are left out: those are lines of the
// architecture, drawn already.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"
#include "render/shadows.h"

namespace avenues {

/// The outline of `light`'s shadows on the convex planar polygon `surface`, as segments in
/// world coordinates, each once.
std::vector<std::array<Vec3, 2>> shadow_outline(const std::vector<Vec3>& surface, const SurfaceLight& light);

}  // namespace avenues
