// Avenues — why is something visible? The avenues of sight drawn for a person.
//
// One SVG in three panels: the picture plane with each avenue's mask outlined and
// labelled by cell and room (Jones's perspective view with its masks); the plan with
// the eye, its view and the cells seen (his Fig. 4, "avenues of sight"); and the avenue
// tree, one node per (cell, mask) reached, one arc per portal crossed (his Fig. 5).
#pragma once

#include <string>

#include "cells/cell_complex.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues {

std::string overlay_svg(const CellComplex& complex, const Camera& camera, const VisibleSet& visible);
/// Writes overlay_svg() to `path` at once or not at all.
void write_overlay_svg(const CellComplex& complex, const Camera& camera, const VisibleSet& visible,
                       const std::string& path);

}  // namespace avenues
