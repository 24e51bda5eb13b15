// Avenues — a 2D DXF floor plan as a Plan, read with dxflib.
//
// What is read (dxflib's DL_CreationAdapter callbacks): LINE, LWPOLYLINE and old-style
// POLYLINE/VERTEX (bulges become arcs), ARC, CIRCLE, ELLIPSE, SPLINE (evaluated from its
// control points and knots, de Boor; rational weights are ignored, so a NURBS circle is
// drawn as its non-rational B-spline), INSERT of BLOCKs (nested, arrays, scale, rotation;
// entities on layer 0 take the INSERT's layer), TEXT and MTEXT (formatting codes
// stripped), HATCH boundaries (lines, arcs, polylines; elliptic and spline edges are
// skipped, as dxflib passes them without their shape), and $INSUNITS. dxflib does not
// read DIMENSION geometry, 3D solids or proxy objects; none of them is a wall.
//
// What is understood:
//  * layers: walls (A-WALL, ISO 13567 / AIA names, "Walls", "Existing Structure",
//    partitions, Wand/Wände/Mauer), doors (A-DOOR, Doors, Tür/Tuer), windows (A-GLAZ,
//    Windows, Fenster, Glazing), by the words in their names; `layers` overrides;
//  * walls: the exact arrangement (plans/formats/wall_arrangement.h) of every curve on the
//    wall layers and of the straight lines on the door layers (frames, jambs, the caps of
//    a wall's ends in a door block, partitions drawn with their doors; swings are never
//    walls), with the gaps left at wall lines' ends closed (plans/formats/wall_line_ends.h:
//    a line stopping short of another carried on to it, a wall's open end capped);
//    its narrow or hatched faces are wall, the rest are spaces; every edge between a space
//    and anything else, or between a wall face and the outside, becomes a wall of no
//    thickness (Jones's sheet), so that any wall shape the drawing has is kept; the wall
//    faces are solid (Plan::unnamed_spaces_solid) and the outside is free, up to the far
//    box, so that a door out of the building leads out and a window looks out;
//  * doors: each swing (an arc of 60–120° and 0.4–1.6 m radius, drawn on a door layer or
//    inside a door block) closes its gap with a line from its hinge to the arc's closed
//    end (the end its leaf is not drawn to; else the end nearer the walls), which must
//    be at a wall line or at another swing's closed end (a double door); the pieces
//    of that line between two spaces, or between a space and a wall face or the outside
//    when 0.25 m or wider (a door out of the building), are its door opening;
//  * doors without a swing (sliding, pocket, bi-fold, leaves drawn as lines; door blocks
//    whose name says door, Tür, porte, sliding, pocket or bi-fold): their straight lines
//    away from any swing, lying along one axis, close the wall gap they lie in from end
//    to end with a door (plans/formats/swingless_doors.h); their panels are no walls;
//  * windows: each cluster of window-layer lines closes its gap with its longest line,
//    the same way: a window (sill 0.9 m, head 2.1 m) between two rooms or in an outer
//    wall, where it opens onto the outside;
//  * rooms: each space is a room, named by the TEXT/MTEXT inside it (or by a layer
//    "Room - NAME" polyline around it), else "space N";
//  * units from $INSUNITS, `unit` overriding; a drawing without units is taken as
//    millimetres when it is over 1000 units across, else metres, with a warning.
// A drawing with no wall layer, or whose wall lines close no room, is a PlanError listing
// its layers and how to name them. Known limits: a swing whose hinge or closed end is over
// 0.15 m from every wall line is not placed (a warning); arcs are arranged as their
// straight pieces (16 per half turn at least, and within Plan::arc_tolerance of the arc
// once the unit is known from $INSUNITS or `unit`), not as exact circular arcs; door-sized lines on
// a door layer in no wall gap (a wardrobe's sliding front) are not placed (a warning).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "plans/plan.h"

namespace avenues {

struct DxfPlanOptions {
  std::string layers;          ///< "walls=A,B;doors=C;windows=D" (names case-insensitive)
  std::string unit;            ///< "m", "cm", "mm", "in", "ft", or "" ($INSUNITS)
  double storey_height = 2.7;  ///< [m] > 0
};

struct DxfPlan {
  Plan plan;
  /// What was understood, a line each: the layers taken for walls, doors and windows,
  /// the unit, and the counts of walls, doors, windows and rooms.
  std::vector<std::string> summary;
  /// [m] every line of the drawing (blocks placed, curves as their straight pieces), in
  /// the plan's axes: what the plan was understood from, to draw under it.
  std::vector<std::pair<Vec2, Vec2>> drawing;
  /// > 0: the file is a 3D model, not a floor plan: this many 3D faces (3DFACE entities,
  /// polygon and polyface mesh POLYLINEs) and no line on a wall layer (and no `layers`
  /// given). `plan` is then empty: read the file as a mesh scene (Assimp reads DXF's
  /// 3D faces).
  int model_faces = 0;
  double metres_per_unit = 0;  ///< a 3D model's unit from $INSUNITS; 0 when it says none
};

/// True when the text starts like an ASCII DXF file (group code 0, SECTION).
bool looks_like_dxf(const std::string& head);

/// Reads a DXF drawing as a one-storey plan, or tells it is a 3D model (model_faces).
/// Throws PlanError naming the file.
DxfPlan read_dxf_plan(const std::string& path, const DxfPlanOptions& options = {});

}  // namespace avenues
