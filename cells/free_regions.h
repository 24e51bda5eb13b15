// Avenues — a complex's free space in regions: cells joined by portals. Two regions meet
// only across opaque surfaces, so nothing is seen and nobody walks from one into another
// (the inside of a closed box, a room with its door shut, the outside).
#pragma once

#include <vector>

#include "cells/cell_complex.h"

namespace avenues {

struct FreeRegions {
  std::vector<size_t> of;       ///< per cell: its region, named by one of its cells (the root)
  std::vector<size_t> largest;  ///< per root: its largest cell by volume; the cell count elsewhere
  std::vector<double> volume;   ///< [m³] per root: its cells' volumes summed; 0 elsewhere
  size_t outside = 0;           ///< the root of the region holding the far box's corner; the cell count if none
};

/// The regions of the complex's cells (union-find over its portals).
FreeRegions free_regions(const CellComplex& complex);

}  // namespace avenues
