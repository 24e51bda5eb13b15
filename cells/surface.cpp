// Avenues — the surfaces of a cell complex: its opaque pieces grouped by plane and material
// (see Surface in cell_complex.h).
//
// Pieces of one surface were cut from one plane by the decomposition, each rounded once,
// so their planes agree to rounding but not bit for bit; a piece joins a surface when its
// unit normal is within kDirection of the surface's and its every vertex within kPlace of
// the surface's plane. Candidates are found without comparing every pair: surfaces are
// filed by their normal quantised to bins of kBin (a piece looks in its bin and the 26
// around it, so a normal near a bin's edge still meets its surface), and within a bin by
// their offset along the bin's own direction (the bin centre, the same for all): pieces
// of one plane differ in that offset by at most the bin's width times their distance
// apart, which the search window allows for.
#include "cells/cell_complex.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace avenues {
namespace {

constexpr double kDirection = 1e-6;  ///< [unit normal] the most two pieces' normals may differ
constexpr double kPlace = 1e-5;      ///< [m] the farthest a piece's vertex may lie off the plane
constexpr double kBin = 1e-4;        ///< [unit normal] the width of a normal bin

using BinKey = std::tuple<MaterialId, long, long, long>;

struct Filed {
  std::multimap<double, int32_t> by_offset;  ///< surface by its offset along `direction`
  Vec3 direction;                            ///< the bin's centre, made unit
};

}  // namespace

void CellComplex::index_surfaces() {
  surfaces.clear();
  // The window along a bin's direction: a bin's width over the far box's size, and kPlace.
  const Vec3 span = far_box.hi - far_box.lo;
  const double extent = std::isfinite(length(span)) ? length(span) : 0;
  const double window = 2 * kBin * extent + 2 * kPlace;
  std::map<BinKey, Filed> bins;
  struct Sum {
    Vec3 origin;           ///< the first piece's first vertex, on the plane: sums are kept relative to it
    Vec3 moment{0, 0, 0};  ///< Σ area · (centroid − origin)
    double area = 0;
  };
  std::vector<Sum> sums;
  for (Cell& cell : cells)
    for (Face& face : cell.faces)
      for (OpaquePoly& piece : face.opaque) {
        piece.surface = -1;
        if (piece.poly.size() < 3) continue;
        // Newell's normal (the piece faces into its cell) and its area and centroid, from
        // its first vertex (exact far from the origin).
        const Vec3 o = piece.poly[0];
        Vec3 n{0, 0, 0}, moment{0, 0, 0};
        double area = 0;
        for (size_t i = 1; i + 1 < piece.poly.size(); ++i) {
          const Vec3 a = piece.poly[i] - o, b = piece.poly[i + 1] - o;
          const Vec3 c = cross(a, b);
          n = n + c;
          const double t = 0.5 * length(c);
          area += t;
          moment = moment + (t / 3) * (a + b);
        }
        const double nl = length(n);
        if (!(nl > 0)) continue;
        n = (1 / nl) * n;
        const Vec3 centroid = o + (area > 0 ? (1 / area) * moment : Vec3{0, 0, 0});
        const long bx = std::lround(n.x / kBin), by = std::lround(n.y / kBin), bz = std::lround(n.z / kBin);
        auto fits = [&](int32_t s) {
          const Surface& sf = surfaces[size_t(s)];
          if (!(length(sf.normal - n) <= kDirection)) return false;
          for (Vec3 p : piece.poly)
            if (!(std::fabs(dot(sf.normal, p - sums[size_t(s)].origin)) <= kPlace)) return false;
          return true;
        };
        int32_t found = -1;
        for (long dx = -1; dx <= 1 && found < 0; ++dx)
          for (long dy = -1; dy <= 1 && found < 0; ++dy)
            for (long dz = -1; dz <= 1 && found < 0; ++dz) {
              const auto it = bins.find({piece.material, bx + dx, by + dy, bz + dz});
              if (it == bins.end()) continue;
              const double at = dot(it->second.direction, centroid);
              for (auto s = it->second.by_offset.lower_bound(at - window);
                   s != it->second.by_offset.end() && s->first <= at + window; ++s)
                if (fits(s->second)) {
                  found = s->second;
                  break;
                }
            }
        if (found < 0) {
          found = int32_t(surfaces.size());
          surfaces.push_back(Surface{n, centroid, 0, piece.material});
          sums.push_back(Sum{o, {0, 0, 0}, 0});
          Filed& bin = bins[{piece.material, bx, by, bz}];
          if (bin.by_offset.empty()) {
            const Vec3 centre{double(bx) * kBin, double(by) * kBin, double(bz) * kBin};
            const double cl = length(centre);
            bin.direction = cl > 0 ? (1 / cl) * centre : n;
          }
          bin.by_offset.emplace(dot(bin.direction, centroid), found);
        }
        piece.surface = found;
        Sum& sum = sums[size_t(found)];
        sum.moment = sum.moment + area * (centroid - sum.origin);
        sum.area += area;
      }
  for (size_t s = 0; s < surfaces.size(); ++s) {
    surfaces[s].area = sums[s].area;
    if (sums[s].area > 0) surfaces[s].centroid = sums[s].origin + (1 / sums[s].area) * sums[s].moment;
  }
}

}  // namespace avenues
