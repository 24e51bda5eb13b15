// Avenues — nearly coplanar neighbours of a soup cut space by one plane (see shared_planes.h).
#include "cells/shared_planes.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <unordered_map>

namespace avenues {

namespace {

double largest_coordinate(const SoupTriangle& t) {
  double m = 0;
  for (const Vec3& p : t.p) m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
  return m;
}

/// True when every coordinate is a float's: the soup was stored in single precision (glTF,
/// FBX, 3DS and every format Assimp reads), so a planar polygon's corners lie off its plane
/// by up to a float's rounding of the coordinates, not a double's.
bool stored_in_floats(const std::vector<SoupTriangle>& soup) {
  for (const SoupTriangle& t : soup)
    for (const Vec3& p : t.p)
      for (double x : {p.x, p.y, p.z})
        if (double(float(x)) != x) return false;
  return true;
}

/// A plane's normal direction in cells of 1/kNormalCells: nearly equal normals fall in the
/// same cell or a neighbouring one.
constexpr double kNormalCells = 1000;

struct NormalKey {
  int32_t x, y, z;
  friend bool operator==(const NormalKey&, const NormalKey&) = default;
};

struct NormalHash {
  size_t operator()(const NormalKey& k) const {
    return size_t((uint64_t(uint32_t(k.x)) * 0x9e3779b97f4a7c15ull) ^ (uint64_t(uint32_t(k.y)) * 0xc2b2ae3d27d4eb4full) ^
                  (uint64_t(uint32_t(k.z)) * 0x165667b19e3779f9ull));
  }
};

NormalKey key_of(Vec3 n) {
  return {int32_t(std::lround(n.x * kNormalCells)), int32_t(std::lround(n.y * kNormalCells)),
          int32_t(std::lround(n.z * kNormalCells))};
}

}  // namespace

std::vector<int> shared_planes(const std::vector<SoupTriangle>& soup, const SharedPlaneParams& params) {
  const size_t n = soup.size();
  std::vector<int> seed(n);
  std::iota(seed.begin(), seed.end(), 0);
  if (n == 0) return seed;

  // Distances from the middle of the soup, so that an offset's rounding stays small.
  Vec3 lo = soup[0].p[0], hi = lo;
  for (const SoupTriangle& t : soup)
    for (const Vec3& p : t.p)
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)},
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  const Vec3 mid = 0.5 * (lo + hi);
  // The rounding of one stored coordinate, relative to its size (a half unit in the last
  // place, twice over for the seed's corners and the member's).
  const double unit = stored_in_floats(soup) ? std::ldexp(1.0, -23) : 16 * DBL_EPSILON;

  // Each triangle's unit normal, area, tolerance and offset; a triangle of no area in
  // doubles takes part in no group.
  std::vector<Vec3> normal(n);
  std::vector<double> area(n, 0), tolerance(n, 0), offset(n, 0);
  std::vector<uint32_t> order;
  for (size_t i = 0; i < n; ++i) {
    const auto& p = soup[i].p;
    const Vec3 c = cross(p[1] - p[0], p[2] - p[0]);
    const double l = std::max({length(p[1] - p[0]), length(p[2] - p[1]), length(p[0] - p[2])});
    area[i] = length(c);
    // Far from collinear as doubles go (collinear corners' rounding leaves ~1e-16 l²).
    if (!(area[i] > 1e-12 * l * l)) continue;
    normal[i] = (1.0 / area[i]) * c;
    offset[i] = dot(normal[i], p[0] - mid);
    tolerance[i] = params.angle * l + unit * largest_coordinate(soup[i]);
    order.push_back(uint32_t(i));
  }
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return area[a] > area[b]; });

  // The planes so far (each its largest triangle's), by normal, then by offset.
  std::unordered_map<NormalKey, std::multimap<double, uint32_t>, NormalHash> planes;
  const double min_cos = std::cos(params.normal_turn);
  for (uint32_t u : order) {
    const auto& p = soup[u].p;
    // How far the offset of a plane u lies on can differ from u's own: its tolerance, and
    // a normal turned by up to the cell's reach, times u's distance from the middle.
    double reach = 0;
    for (const Vec3& q : p) reach = std::max(reach, length(q - mid));
    const double window = tolerance[u] + 4 / kNormalCells * reach;
    int found = -1;
    for (double sign : {1.0, -1.0}) {
      const NormalKey k = key_of(sign * normal[u]);
      for (int dx = -1; dx <= 1 && found < 0; ++dx)
        for (int dy = -1; dy <= 1 && found < 0; ++dy)
          for (int dz = -1; dz <= 1 && found < 0; ++dz) {
            const auto it = planes.find({k.x + dx, k.y + dy, k.z + dz});
            if (it == planes.end()) continue;
            const double d = sign * offset[u];
            for (auto c = it->second.lower_bound(d - window); c != it->second.end() && c->first <= d + window; ++c) {
              const uint32_t s = c->second;
              if (std::fabs(dot(normal[s], normal[u])) < min_cos) continue;
              const double tol = tolerance[u] + unit * largest_coordinate(soup[s]);
              bool on = true;
              for (const Vec3& q : p) on = on && std::fabs(dot(normal[s], q - soup[s].p[0])) <= tol;
              if (on) {
                found = int(s);
                break;
              }
            }
          }
      if (found >= 0) break;
    }
    if (found >= 0) {
      seed[u] = found;
    } else {
      planes[key_of(normal[u])].emplace(offset[u], u);
    }
  }
  return seed;
}

}  // namespace avenues
