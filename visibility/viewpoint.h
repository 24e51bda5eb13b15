// Avenues — where to stand when nobody says: the plan's own viewpoint, or a sensible
// eye in the first room, at eye height, looking through its first door.
#pragma once

#include "cells/cell_complex.h"

namespace avenues {

constexpr double kEyeHeight = 1.6;  ///< [m] above the floor

/// The plan's viewpoint if it names one; otherwise the centre of the largest cell of
/// the first named room, 1.6 m above its floor, looking at the middle of that cell's
/// first door (or window, or hatch) or, where it has none, along the level heading of
/// sixteen that sees the most cells, with a 60° field of view.
Viewpoint default_viewpoint(const CellComplex& complex);

}  // namespace avenues
