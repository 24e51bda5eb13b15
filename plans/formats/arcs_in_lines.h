// Avenues — arcs drawn as chains of short straight lines.
//
// Programs that write arcs as polylines or lines (conversions from PDF, SketchUp, Rhino)
// draw a door's swing as a dozen short lines. arcs_in_lines() finds such chains among
// lines: three or more, end to end (ends agreeing to a billionth of the drawing's extent,
// exactly two lines meeting at each inner corner), turning the same way by at most 36
// degrees at each corner (ten lines to a circle at the coarsest), their corners within 2 %
// of the radius of one circle. A closed chain is an outline, not an arc.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "core/geometry.h"

namespace avenues {

struct ArcOfLines {
  std::vector<size_t> lines;  ///< indices into the lines given, along the arc
  Vec2 centre, from, to;      ///< the arc runs counter-clockwise from `from` to `to`
  double r = 0;
  double sweep_deg = 0;
};

std::vector<ArcOfLines> arcs_in_lines(const std::vector<std::pair<Vec2, Vec2>>& lines);

}  // namespace avenues
