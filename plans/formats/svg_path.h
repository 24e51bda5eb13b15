// Avenues — an SVG path's outline as polygons (the `d` attribute's grammar, SVG 1.1 §8.3).
//
// Sweet Home 3D gives the shape a door or window cuts in its wall (cutOutShape: an arch,
// a circle) and the hole a staircase cuts in the floor above (staircaseCutOutShape) as
// SVG paths in the piece's unit square. Every command is read, absolute and relative:
// moveto, lineto (L H V), closepath, cubic and quadratic Béziers (C S Q T) and elliptical
// arcs (A, by the spec's endpoint-to-centre conversion, radii scaled up where too small).
// Curves are flattened into `pieces` straight pieces each.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "core/geometry.h"

namespace avenues {

/// The path's subpaths, each a polygon of its points in order (a subpath ends at the next
/// moveto or closepath; a closing point equal to the first is left out). nullopt when the
/// path does not follow the grammar (an unknown command, a number missing or not finite).
std::optional<std::vector<std::vector<Vec2>>> svg_path_polygons(std::string_view d, int pieces = 16);

/// The path's outline: its subpath enclosing the largest area (a cut-out is one hole);
/// empty when the path does not parse or no subpath encloses any area.
std::vector<Vec2> svg_path_outline(std::string_view d);

}  // namespace avenues
