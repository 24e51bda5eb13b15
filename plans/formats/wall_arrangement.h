// Avenues — the arrangement of a drawing's wall curves, and which of its faces are walls.
//
// The one CGAL boundary of plans/formats: arrange_walls() builds the exact planar
// arrangement (CGAL Arrangement_2, Epeck) of the wall lines of a 2D drawing together with
// the lines that close its door and window gaps, and tells each bounded face
//  * a wall face: hatched, or narrow (twice its area over its perimeter, the width of a
//    strip, at most `max_wall_width`, as between two near-parallel wall lines);
//  * a gap face: narrow, convex, and bounded for at least `gap_share` of its perimeter by
//    the closing lines of one door or window (the glass between a window's lines);
//  * or a space.
// It returns the edges that separate a space or a gap face from anything else, or a wall
// face from the outside, as plain segments ("sheets", walls of no thickness), with the
// closing line they lie on (not on a wall face's edges), each space with a point inside
// it, and the gap faces. A face's width counts each edge bounding it once: lines standing
// free in a room (a door leaf, an arrow) have the room on both sides and are not its
// boundary. Plain structs in, plain structs out.
#pragma once

#include <vector>

#include "core/geometry.h"

namespace avenues {

/// A straight piece of the drawing [m]. `closes` >= 0: the line closing door or window
/// gap number `closes` (the caller's numbering); -1: a wall line.
struct ArrangedSegment {
  Vec2 a, b;
  int closes = -1;
};

struct WallArrangementInput {
  std::vector<ArrangedSegment> segments;
  /// Hatches of the wall layers, each a set of rings (even-odd: a point is inside the
  /// hatch when it is inside an odd number of its rings).
  std::vector<std::vector<std::vector<Vec2>>> hatches;
  std::vector<Vec2> probes;      ///< points to locate (room names' texts)
  double max_wall_width = 0.45;  ///< [m] a narrower face is a wall
  double gap_share = 0.4;        ///< of a narrow face's perimeter on one gap's lines: a gap face
};

struct Sheet {
  Vec2 a, b;         ///< [m]
  int closes = -1;   ///< the gap whose closing line it lies on, or -1 (a wall's face)
  bool between_spaces = false;  ///< a space on both sides (else a space and a wall face or the
                                ///< outside, or a wall face and the outside)
  bool beside_gap_face = false; ///< a GapFace on one side: the opening, however short the piece
};

/// A narrow face lying in a door or window gap: between the lines of one window (its
/// glass and frame lines), or between a door's closing line and a threshold. It is free
/// over the opening's height, not wall: the sheets around it carry the opening, but
/// those it shares with a wall face (its jambs). Convex, counter-clockwise, in metres.
struct GapFace {
  std::vector<Vec2> poly;
  int closes = -1;   ///< the gap it lies in
};

struct Space {
  Vec2 inside;       ///< [m] a point strictly inside the face
  double area = 0;   ///< [m²]
};

struct WallArrangement {
  std::vector<Sheet> sheets;
  std::vector<Space> spaces;       ///< the bounded faces that are not walls
  std::vector<GapFace> gap_faces;  ///< narrow faces in a door or window gap
  std::vector<int> probe_space;    ///< per probe: index into spaces, -1 in a wall face or on a line, -2 outside
  int faces = 0, wall_faces = 0;   ///< bounded faces, and of them walls
  int hatched_faces = 0;
};

/// Builds the arrangement and classifies it (see above).
WallArrangement arrange_walls(const WallArrangementInput& input);

}  // namespace avenues
