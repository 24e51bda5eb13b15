// Avenues — doors drawn without a swing: sliding, pocket, bi-fold, leaves drawn as lines.
//
// A swing door shows where its gap is by its arc (hinge to closed end). A sliding door,
// a pocket door slid into its wall, a bi-fold or a double leaf drawn as lines shows only
// its panels, lines lying along the gap. find_swingless_doors() takes the straight lines
// of the door layers and of door blocks (not those near a swing: leaves, frames and
// wall-end caps of swing doors), and:
//  1. clusters the lines that touch (within 2 cm) into pieces; a piece that is thin
//     across its main axis (at most `max_across`) and at most `max_width` long may be a
//     panel, a track or an arrow;
//  2. joins pieces lying along one axis (parallel within 10°, side by side within
//     `max_across`, less than 1 m apart along it): the two panels of a pocket door
//     drawn open, a panel and its arrow;
//  3. looks along that axis from the middle of the joined pieces, both ways, for the gap's
//     ends: the first wall line crossed (a wall's end cap) or the first wall line running
//     along the axis within `max_half_wall` of it (a wall's face, where the wall goes on
//     past the gap); a crossed cap counts only when the wall goes on past it.
// A door at least `min_width` long across a gap `min_width`..`max_width` wide, which its
// panels cover at least a third of, is a door: the gap's closing line from end to end.
// Lines that are door-sized (at least `min_width` long) but whose gap is not found are
// reported as not placed. Plain segments in, plain results out.
#pragma once

#include <utility>
#include <vector>

#include "core/geometry.h"

namespace avenues {

struct SwinglessDoorParams {
  double min_width = 0.5;      ///< [m] the narrowest door gap (and the shortest panels read as a door)
  double max_width = 3.0;      ///< [m] the widest
  double max_across = 0.35;    ///< [m] the thickest a door's drawing is across its gap
  double max_half_wall = 0.25; ///< [m] how far a wall's face may lie beside the gap's axis
  double near_swing = 0.1;     ///< [m] lines this near a swing's hinge or ends belong to the swing door
  double join_across = -1;     ///< [m] how far apart across pieces along one axis may lie to be one door (< 0: max_across)
};

struct SwinglessDoor {
  Vec2 a, b;                  ///< [m] the gap's closing line, end to end
  Vec2 where;                 ///< [m] the middle of its panels
  std::vector<int> lines;     ///< indices into `door_lines` of its panels, tracks, arrows
  bool placed = false;        ///< false: door-sized, but in no wall gap
};

/// `door_lines`: straight lines of door layers and door blocks, `door_line_is_wall` per
/// line whether it is a wall line too (door-layer lines are: frames, caps, partitions);
/// `wall_lines`: the other wall lines (wall layers, windows); `swing_points`: swings'
/// hinges and ends. A door's own lines are never its gap's ends.
std::vector<SwinglessDoor> find_swingless_doors(const std::vector<std::pair<Vec2, Vec2>>& door_lines,
                                                const std::vector<bool>& door_line_is_wall,
                                                const std::vector<std::pair<Vec2, Vec2>>& wall_lines,
                                                const std::vector<Vec2>& swing_points,
                                                const SwinglessDoorParams& params = {});

}  // namespace avenues
