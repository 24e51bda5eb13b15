// Avenues — a plan drawing of the cell complex, for people to check at a glance.
//
// One SVG with every storey's plan (side by side, or stacked for wide buildings),
// each titled: the storey's cells filled with a pale colour per room, walls cut at
// sill height as thick lines, edges below the cut (low walls, sills) as thin lines,
// portals as dashed lines coloured by kind, floor openings hatched, room names at
// their largest cell, cell ids small, a legend and a scale bar. y points up, as in
// the plan; the viewBox is in metres and the page size in millimetres at a standard
// scale (1:50, 1:100, ...). A plan read from a drawing can have the drawing's own lines
// under it in light blue.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cells/cell_complex.h"

namespace avenues {

/// The lines of the drawing a plan was read from (a DXF's), [m] in the plan's axes: drawn
/// in a light colour under what was understood of them, for checking the one against the
/// other by eye. Empty for plans not read from a drawing.
using DrawingLines = std::vector<std::pair<Vec2, Vec2>>;

/// Writes the drawing to `path` (temporary file + rename: no partial file on failure).
/// Throws std::runtime_error naming the file if it cannot be written.
void write_plan_svg(const CellComplex& complex, const std::string& path, const DrawingLines& underlay = {});

/// The same drawing as SVG text.
std::string plan_svg(const CellComplex& complex, const DrawingLines& underlay = {});

}  // namespace avenues
