// Avenues — a complex's free space in regions (free_regions.h).
#include "cells/free_regions.h"

#include <numeric>

namespace avenues {

FreeRegions free_regions(const CellComplex& c) {
  const size_t n = c.cells.size();
  FreeRegions r;
  r.of.resize(n);
  std::iota(r.of.begin(), r.of.end(), size_t(0));
  auto find = [&](size_t i) {  // with path halving
    while (r.of[i] != i) i = r.of[i] = r.of[r.of[i]];
    return i;
  };
  for (const Portal& p : c.portals) r.of[find(size_t(p.cell[0]))] = find(size_t(p.cell[1]));
  for (size_t i = 0; i < n; ++i) r.of[i] = find(i);
  r.largest.assign(n, n);
  r.volume.assign(n, 0);
  std::vector<double> volume(n);
  for (size_t i = 0; i < n; ++i) {
    volume[i] = c.cells[i].volume();
    r.volume[r.of[i]] += volume[i];
    size_t& b = r.largest[r.of[i]];
    if (b == n || volume[i] > volume[b]) b = i;
  }
  const Box3& fb = c.far_box;
  const Vec3 corner = fb.lo + 1e-3 * (fb.hi - fb.lo);
  r.outside = n;
  for (size_t i = 0; i < n && r.outside == n; ++i)
    if (c.cells[i].contains(corner)) r.outside = r.of[i];
  return r;
}

}  // namespace avenues
