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

/// A person reads a few thousand masks and a tree of a thousand rows; a view of a finely cut
/// scene can hold hundreds of thousands of avenues (and once made a 363 MB file no browser
/// opens). So at most kOverlayMasks masks are outlined, the shallowest first (those nearest
/// the eye, which the deeper ones lie within), and the tree shows its first kOverlayTreeRows
/// avenues in search order; each panel's title says how many of how many it shows.
inline constexpr size_t kOverlayMasks = 3000, kOverlayTreeRows = 1000;

std::string overlay_svg(const CellComplex& complex, const Camera& camera, const VisibleSet& visible);
/// Writes overlay_svg() to `path` at once or not at all.
void write_overlay_svg(const CellComplex& complex, const Camera& camera, const VisibleSet& visible,
                       const std::string& path);

}  // namespace avenues
