// Avenues — line weights: which real lines are outlines from this eye.
//
// A draughtsman draws outlines heavier than creases. A line is an outline where the eye
// sees past it: on one side of it the picture shows a surface meeting the line, on the
// other what lies beyond. Let Π be the plane through the eye and the line. Every opaque
// surface meeting the line leaves it in some direction w (in the surface, perpendicular to
// the line). Rays grazing the line on one side of Π meet the surfaces leaving on that side
// right at the line; so if every surface leaves on the same side of Π, the rays on the other
// side pass the line by and it is an outline; if surfaces leave on both sides, the line is a
// crease. This one test decides, from the eye alone:
//  - a Convex real line (an outer corner, a reveal) is an outline exactly when its two faces
//    are one front- and one back-facing (both then lie on one side of Π: its silhouette);
//    with both faces turned to the eye they lie on either side, and it is a crease;
//  - a line bounding an opening, seen against what lies beyond, is an outline: the frame of a
//    door in a sheet (Jones's walls of no thickness) has wall on one side only; the arris of a
//    door in a thick wall is an outline while its jamb is turned away, a crease while the jamb
//    is in view (the far arris then outlines the opening);
//  - the free end of a sheet and the top of a low wall are outlines;
//  - a Concave crease (wall–floor, an inner corner) and a T-junction of sheets have surfaces on
//    both sides of Π whenever the line can be seen at all: creases.
// Surfaces seen exactly edge-on (w in Π) count on neither side.
#pragma once

#include <cstdint>
#include <vector>

#include "cells/cell_complex.h"
#include "render/drawing.h"

namespace avenues {

/// The opaque surfaces meeting each real line, computed once per cell complex.
struct LineFaces {
  std::vector<int32_t> start;  ///< per RealLine, offsets into dirs; complex.lines.size() + 1 entries
  std::vector<Vec3> dirs;      ///< unit, perpendicular to the line, pointing into an opaque face that meets it
  /// Per cell, offsets into `shows`; complex.cells.size() + 1 entries.
  std::vector<int32_t> cell_start;
  /// Per cell, per entry of its `lines`: 0 where the cell sees no line at all, 1 otherwise.
  /// A wall of no thickness is one plane for the cells on both its sides, so a line meeting it
  /// on one side (a T-junction of sheets) lies on the boundary of the cell on the other side
  /// too, where that cell sees only the flat sheet: one face of the cell holds the line, with
  /// opaque wall on both sides of it.
  std::vector<uint8_t> shows;
};

/// Collects, for every real line, the directions of the opaque faces of the cells around it,
/// probed at the middle of each cell's part of the line; and whether each cell shows it.
LineFaces line_faces(const CellComplex& complex);

/// Outline or crease, for the line `id` seen from `eye` (see above).
Weight line_weight(const CellComplex& complex, const LineFaces& faces, LineId id, Vec3 eye);
/// The same for parallel rays along `direction`: Π contains the line and the direction.
Weight line_weight_along(const CellComplex& complex, const LineFaces& faces, LineId id, Vec3 direction);

}  // namespace avenues
