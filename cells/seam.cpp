// Avenues — seams between opaque pieces closed (see CellComplex::close_seams).
//
// Pieces of one plane cut by the decomposition meet along shared lines, but not always at
// shared corners: a sky cell's top may run 5 m along an edge where its neighbours' tops
// run 1 m each (a T-junction). Exact, the two sides of such a line are one line; rounded,
// each piece's edge is the line through its own rounded corners, and a sample centre on the
// seam may fall outside both — the search resolved by depth (the hull search) then shows
// what lies behind, a sparkle along the seam. So every corner of a piece that lies inside
// an edge of another (within the rounding of the corners) is put into that edge: the seam
// is then made of the same segments on both sides, rounded alike on any raster, as
// mesh_of_polygons does for a mesh's own T-junctions.
//
// Candidates are found in a uniform grid of cubes about as wide as the median edge: each
// corner is filed in every cube its tolerance box meets, and each edge looks in the cubes
// of its pieces no longer than a cube (at most 2 × 2 × 2 each).
#include "cells/cell_complex.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace avenues {

namespace {

struct Filed {
  uint64_t cube;
  uint32_t corner;
  bool operator<(const Filed& o) const { return cube < o.cube || (cube == o.cube && corner < o.corner); }
};

/// 21 bits per axis: enough for the grid's cubes along each side and the tolerance's overlap.
uint64_t cube_key(int64_t x, int64_t y, int64_t z) {
  constexpr int64_t mask = (int64_t(1) << 21) - 1;
  return (uint64_t(x & mask) << 42) | (uint64_t(y & mask) << 21) | uint64_t(z & mask);
}

}  // namespace

size_t CellComplex::close_seams() {
  // Every corner once (corners rounded from one exact point are bit for bit the same).
  std::vector<Vec3> corners;
  std::vector<double> edge_lengths;
  Box3 bounds;
  for (const Cell& cell : cells)
    for (const Face& face : cell.faces)
      for (const OpaquePoly& piece : face.opaque)
        for (size_t i = 0; i < piece.poly.size(); ++i) {
          const Vec3 p = piece.poly[i];
          if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return 0;
          corners.push_back(p);
          edge_lengths.push_back(length(piece.poly[(i + 1) % piece.poly.size()] - p));
          bounds.add(p);
        }
  if (corners.empty()) return 0;
  auto before = [](Vec3 a, Vec3 b) { return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z))); };
  std::sort(corners.begin(), corners.end(), before);
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());

  // How far off an edge a corner may lie to be in it: the rounding of coordinates this far
  // from the origin, many times over. How near an end it may lie and not be that end: a
  // thousand times more, so that the edge's two parts keep its direction (a corner
  // beside an end would make a side of no direction of its own).
  const double scale = bounds.magnitude();
  const double tol = 1e-12 * scale;  // [m]
  const double end = 1e-9 * scale;   // [m]
  const size_t middle = edge_lengths.size() / 2;
  std::nth_element(edge_lengths.begin(), edge_lengths.begin() + std::ptrdiff_t(middle), edge_lengths.end());
  const Vec3 extent = bounds.hi - bounds.lo;
  const double widest = std::max({extent.x, extent.y, extent.z});
  // No more than 4,096 cubes along an axis: a complex whose median edge is a sliver's
  // (a tessellated solid cut by the soup BSP) still has edges across the far box, each
  // looked along cube by cube.
  const double size = std::max({edge_lengths[middle], widest / 4096, 64 * tol});
  auto cube_of = [&](double v, double lo) { return int64_t(std::floor((v - lo) / size)); };

  std::vector<Filed> filed;
  filed.reserve(corners.size());
  for (size_t k = 0; k < corners.size(); ++k) {
    const Vec3 p = corners[k];
    const int64_t x0 = cube_of(p.x - tol, bounds.lo.x), x1 = cube_of(p.x + tol, bounds.lo.x);
    const int64_t y0 = cube_of(p.y - tol, bounds.lo.y), y1 = cube_of(p.y + tol, bounds.lo.y);
    const int64_t z0 = cube_of(p.z - tol, bounds.lo.z), z1 = cube_of(p.z + tol, bounds.lo.z);
    for (int64_t x = x0; x <= x1; ++x)
      for (int64_t y = y0; y <= y1; ++y)
        for (int64_t z = z0; z <= z1; ++z) filed.push_back({cube_key(x, y, z), uint32_t(k)});
  }
  std::sort(filed.begin(), filed.end());
  // Each cube's run of corners in `filed`.
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> run;
  run.reserve(filed.size());
  for (uint32_t k = 0; k < uint32_t(filed.size());) {
    uint32_t e = k;
    while (e < filed.size() && filed[e].cube == filed[k].cube) ++e;
    run.emplace(filed[k].cube, std::pair{k, e});
    k = e;
  }

  // Each piece changes only itself, and reads only the corners as they were: cells in
  // parallel, the same result on any number of threads.
  std::atomic<size_t> added{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, cells.size(), 64), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<uint32_t> near;
    std::vector<std::pair<double, Vec3>> inside;
    std::vector<Vec3> out;
    size_t here = 0;
    for (size_t c = range.begin(); c != range.end(); ++c)
      for (Face& face : cells[c].faces)
        for (OpaquePoly& piece : face.opaque) {
          const size_t m = piece.poly.size();
          if (m < 3) continue;
          out.clear();
          for (size_t i = 0; i < m; ++i) {
            const Vec3 a = piece.poly[i], b = piece.poly[(i + 1) % m];
            out.push_back(a);
            const Vec3 d = b - a;
            const double len = length(d);
            if (!(len > 2 * end)) continue;
            // The cubes of the edge, piece by piece no longer than a cube.
            near.clear();
            const size_t steps = size_t(std::ceil(len / size));
            for (size_t s = 0; s < steps; ++s) {
              const Vec3 p = a + (double(s) / double(steps)) * d, q = a + (double(s + 1) / double(steps)) * d;
              const int64_t x0 = cube_of(std::min(p.x, q.x), bounds.lo.x), x1 = cube_of(std::max(p.x, q.x), bounds.lo.x);
              const int64_t y0 = cube_of(std::min(p.y, q.y), bounds.lo.y), y1 = cube_of(std::max(p.y, q.y), bounds.lo.y);
              const int64_t z0 = cube_of(std::min(p.z, q.z), bounds.lo.z), z1 = cube_of(std::max(p.z, q.z), bounds.lo.z);
              for (int64_t x = x0; x <= x1; ++x)
                for (int64_t y = y0; y <= y1; ++y)
                  for (int64_t z = z0; z <= z1; ++z) {
                    const auto it = run.find(cube_key(x, y, z));
                    if (it == run.end()) continue;
                    for (uint32_t k = it->second.first; k < it->second.second; ++k) near.push_back(filed[k].corner);
                  }
            }
            if (near.empty()) continue;
            std::sort(near.begin(), near.end());
            near.erase(std::unique(near.begin(), near.end()), near.end());
            inside.clear();
            for (const uint32_t k : near) {
              const Vec3 v = corners[k];
              const double t = dot(v - a, d) / (len * len);
              if (!(t * len > end && (1 - t) * len > end)) continue;  // an end, or beyond one
              if (!(length(v - (a + t * d)) <= tol)) continue;
              inside.emplace_back(t, v);
            }
            std::sort(inside.begin(), inside.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
            // Two corners a rounding apart are one corner: the side between them would have
            // no direction of its own.
            for (const auto& [t, v] : inside)
              if (length(v - out.back()) > end) out.push_back(v), ++here;
          }
          if (out.size() != m) piece.poly = out;
        }
    added += here;
  });
  return added;
}

}  // namespace avenues
