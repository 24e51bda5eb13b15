// Avenues — doors drawn over walls not cut for them.
//
// Sketches draw walls straight through and the door's swing on top. A swing whose hinge
// and one of its ends both lie on a wall line (within 2 cm) that runs on past both (by a
// centimetre) is a door in that wall: open_walls_under_swings() opens the wall there. That
// line, and the lines parallel to it (within 2 degrees) behind it over the span — the
// wall's other face: within 0.6 m, on the side of the nearest such line, or away from the
// swing when the wall is one line — lose the span between hinge and end. The ends so left
// are to be capped across the wall as any wall's open end is (wall_line_ends.h).
#pragma once

#include <utility>
#include <vector>

#include "core/geometry.h"

namespace avenues {

/// A door's swing [m]: its hinge (the arc's centre) and the arc's two ends.
struct SwingArc {
  Vec2 hinge, end0, end1;
};

struct OpenedWalls {
  std::vector<std::pair<Vec2, Vec2>> lines;  ///< the wall lines, those opened cut
  int doors = 0;                             ///< swings that opened a wall
};

OpenedWalls open_walls_under_swings(const std::vector<std::pair<Vec2, Vec2>>& walls, const std::vector<SwingArc>& swings);

}  // namespace avenues
