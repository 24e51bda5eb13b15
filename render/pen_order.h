// Avenues — the order a pen plotter draws strokes in.
//
// A pen plotter spends much of its time in the air, carrying the lifted pen from the end
// of one stroke to the start of the next. Strokes are drawn pen by pen (one pen per
// weight); within a pen, greedily, the stroke with an end nearest the pen goes next, drawn
// from that end. A stroke starting exactly where the pen is continues the same pen-down
// path, so strokes that touch are chained into one polyline. Nearest ends are found in a
// uniform grid over the strokes' ends, searched in growing square rings (the search stops
// once a ring's nearest possible end is farther than the best found). Greedy is a heuristic
// and can lose to an order that was good already; the plan then keeps the given order, so
// the travel never grows.
#pragma once

#include <array>
#include <vector>

#include "core/geometry.h"

namespace avenues {

/// One pen-down path: the pen goes down at points[0] and draws through the rest.
struct PenPath {
  int pen = 1;              ///< >= 1
  std::vector<Vec2> points; ///< at least two
};

struct PenPlan {
  std::vector<PenPath> paths;  ///< in plotting order: pens ascending, then nearest-end-first (or as given)
  double travel_before = 0;    ///< pen-up travel drawing the segments as given, pen by pen [input units]
  double travel_after = 0;     ///< pen-up travel along `paths` [input units], <= travel_before
};

/// Plans the plot of `segments` (in any unit; plotter units for HPGL), `pens[i]` the pen of
/// segments[i]. The pen starts at `start`; travel is counted from there, not back home.
PenPlan plan_pen_paths(const std::vector<std::array<Vec2, 2>>& segments, const std::vector<int>& pens, Vec2 start);

}  // namespace avenues
