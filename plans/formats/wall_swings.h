// Avenues — door swings drawn where the walls are.
//
// A door layer's arcs are swings; a wall layer's are curved walls, except two kinds, which
// read as walls would close their gaps with a curved wall and make a half- or quarter-disc
// room:
//  - a double-acting door (a leaf swinging both ways: kitchens, corridors): a half circle
//    (150–210°) about the hinge, from the leaf open one way to the leaf open the other,
//    often with the leaf itself drawn open across the wall along the chord; both its ends
//    free of walls; the leaf shuts across the gap, from the hinge to the arc's middle;
//  - a swing among the walls (drawings that keep their doors with their walls): a 60–120°
//    arc, its open end free of walls but for the leaf drawn to it (when both ends are free,
//    the leaf drawn tells which is open); it shuts at its other end.
// Both stand at a wall's end: a wall line not along the leaf within 15 cm of the hinge. A
// curved wall (a niche, a bay, a rounded corner) ends on walls at both ends. The arc's
// pieces and the leaf's lines (along its axis, within the circle, long or out at its rim:
// not a wall end's short cap at the hinge) are no walls.
#pragma once

#include <vector>

#include "core/geometry.h"

namespace avenues {

struct WallSwingLine {
  Vec2 a, b;           ///< [m]
  bool curved = false; ///< a piece of an arc or curve
};

struct WallSwingArc {
  Vec2 c, p0, p1;      ///< [m] centre, and its ends counter-clockwise from p0 to p1
  double r = 0;        ///< [m]
  double sweep_deg = 0;
  bool both_ways = false;  ///< may be a double-acting door's half circle
  bool one_way = false;    ///< may be a swing among the walls
};

struct WallSwing {
  Vec2 hinge, shut;  ///< [m] the door's gap, from the hinge to where the leaf shuts
  size_t arc = 0;    ///< index into the arcs given
};

struct WallSwings {
  std::vector<WallSwing> swings;
  std::vector<bool> no_wall;  ///< per line given: a swing's arc or leaf
};

WallSwings find_wall_swings(const std::vector<WallSwingLine>& lines, const std::vector<WallSwingArc>& arcs);

}  // namespace avenues
