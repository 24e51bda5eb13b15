// Avenues — closing the small gaps a drawing leaves at its wall lines' ends.
//
// Drawings are rarely closed exactly: a wall's two face lines stop at a door gap with no
// line across the wall's end, a partition stops a few millimetres short of the wall it
// meets, a corner is drawn with a gap. close_wall_line_ends() looks at every end of a
// wall line that touches no other line (a free end, within `touch`) and adds the short
// lines that close it, in three passes:
//  0. a near touch: an end that stops within `join` of another line (a partition drawn
//     a fraction of a millimetre short of a wall, a corner of two lines drawn onto a
//     line but a rounding beside it) is joined to it exactly: a line from the end across
//     that line, `join_overshoot` past it (or to its end, when that is the nearest point).
//     Ends where two lines meet count too: no carrying on past a shared corner closes it,
//     and snapping the drawing to a grid moves a corner drawn exactly onto a line off it;
//  1. an undershoot: the line carried on along its own direction meets another line
//     within `reach` (a partition drawn short of a wall): a line from the end to there;
//  2. a wall's end: the free ends left are joined in mutually nearest pairs at most
//     `cap` apart (a wall's end across its thickness, a corner drawn apart).
// Door gaps are wider than any wall, so they stay open for the doors to close.
// Plain segments in, the added segments out; a uniform grid keeps it near linear.
#pragma once

#include <utility>
#include <vector>

#include "core/geometry.h"

namespace avenues {

/// [m] How far the arrangement carries a wall line on past an end no other line ends at,
/// so that a line drawn onto another one crosses it.
constexpr double kWallLineCarriedOn = 0.001;

struct WallLineEndParams {
  double touch = 0.0005; ///< [m] an end nearer than this to another line is not free (the arrangement
                         ///< carries every line 1 mm on past its ends)
  double join = 0.002;   ///< [m] an end this near a line it does not run along is joined across it
  double join_overshoot = 0.0005;  ///< [m] how far past the line it is joined to the joining line reaches
  double reach = 0.05;   ///< [m] how far a free end is carried on along its line
  double cap = 0.45;     ///< [m] the widest wall end joined across
};

struct WallLineEnds {
  std::vector<std::pair<Vec2, Vec2>> added;  ///< [m] the lines that close the gaps
  int joined = 0;                            ///< lines added by pass 0 (joining ends to a line they nearly touch)
  int free_ends = 0;                         ///< free ends found before closing (those not joined)
  int extended = 0, capped = 0;              ///< lines added by pass 1 and by pass 2
};

WallLineEnds close_wall_line_ends(const std::vector<std::pair<Vec2, Vec2>>& lines,
                                  const WallLineEndParams& params = {});

/// Pass 0 alone, for lines added once the walls were closed (the lines across door and
/// window gaps, which run along the walls' faces): the joining lines for the ends that
/// nearly touch a line, of the pairs with at least one line at index >= first_new.
std::vector<std::pair<Vec2, Vec2>> join_wall_line_ends(const std::vector<std::pair<Vec2, Vec2>>& lines, size_t first_new,
                                                        const WallLineEndParams& params = {});

}  // namespace avenues
