// Avenues — nearly coplanar neighbours of a soup cut space by one plane (see shared_planes.h).
#include "cells/shared_planes.h"

#include "core/float_rounding.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>

namespace avenues {

namespace {

/// The largest coordinate, in magnitude, of three points (a triangle's, a plane's).
double largest_coordinate(const std::array<Vec3, 3>& p) {
  double m = 0;
  for (const Vec3& q : p) m = std::max({m, std::fabs(q.x), std::fabs(q.y), std::fabs(q.z)});
  return m;
}

/// True when every coordinate is a float's: the soup was stored in single precision (glTF,
/// FBX, 3DS and every format Assimp reads), so a planar polygon's corners lie off its plane
/// by up to a float's rounding of the coordinates, not a double's.
bool stored_in_floats(const std::vector<SoupTriangle>& soup) {
  for (const SoupTriangle& t : soup)
    for (const Vec3& p : t.p)
      for (double x : {p.x, p.y, p.z})
        if (!is_float(x)) return false;
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

/// A plane triangles may take: its corners, and its unit normal, offset from the soup's
/// middle and the rounding of its corners, in doubles.
struct Candidate {
  SharedPlane plane;
  Vec3 n;
  double offset = 0;
  double rounding = 0;
};

/// The soup's triangles as the grouping sees them.
struct Grouping {
  const std::vector<SoupTriangle>& soup;
  const SharedPlaneParams& params;
  Vec3 mid;
  double unit = 0;              ///< the rounding of a stored coordinate, relative to its size
  std::vector<Vec3> normal;     ///< unit, per triangle
  std::vector<double> area;     ///< twice the area, per triangle
  std::vector<double> tolerance;
  std::vector<uint32_t> order;  ///< triangles of some area, largest first

  Candidate candidate(const SharedPlane& plane) const {
    Candidate c{plane, {}, 0, 0};
    const Vec3 x = cross(plane.p[1] - plane.p[0], plane.p[2] - plane.p[0]);
    c.n = (1.0 / length(x)) * x;
    c.offset = dot(c.n, plane.p[0] - mid);
    c.rounding = unit * largest_coordinate(plane.p);
    return c;
  }

  /// Each triangle of some area on the first of `planes` it lies on, or on a new plane of
  /// its own, appended to `planes` (taken largest first, so a later triangle may take it).
  /// Returns, per triangle, its plane's index, or −1 for none.
  std::vector<int> group(std::vector<Candidate>& planes) const {
    std::unordered_map<NormalKey, std::multimap<double, uint32_t>, NormalHash> by_normal;
    double largest_rounding = 0;
    for (size_t c = 0; c < planes.size(); ++c) {
      by_normal[key_of(planes[c].n)].emplace(planes[c].offset, uint32_t(c));
      largest_rounding = std::max(largest_rounding, planes[c].rounding);
    }
    const double min_cos = std::cos(params.normal_turn);
    std::vector<int> plane_of(soup.size(), -1);
    for (uint32_t u : order) {
      const auto& p = soup[u].p;
      // How far the offset of a plane u lies on can differ from u's own: its tolerance and
      // the plane's rounding, and a normal turned by up to the cell's reach, times u's
      // distance from the middle.
      double reach = 0;
      for (const Vec3& q : p) reach = std::max(reach, length(q - mid));
      const double window = tolerance[u] + largest_rounding + 4 / kNormalCells * reach;
      const double offset = dot(normal[u], p[0] - mid);
      int found = -1;
      for (double sign : {1.0, -1.0}) {
        const NormalKey k = key_of(sign * normal[u]);
        const double d = sign * offset;
        for (int dx = -1; dx <= 1; ++dx)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dz = -1; dz <= 1; ++dz) {
              const auto it = by_normal.find({k.x + dx, k.y + dy, k.z + dz});
              if (it == by_normal.end()) continue;
              for (auto c = it->second.lower_bound(d - window); c != it->second.end() && c->first <= d + window; ++c) {
                if (found >= 0 && uint32_t(found) < c->second) continue;
                const Candidate& h = planes[c->second];
                if (std::fabs(dot(h.n, normal[u])) < min_cos) continue;
                const double tol = tolerance[u] + h.rounding;
                bool on = true;
                for (const Vec3& q : p) on = on && std::fabs(dot(h.n, q - h.plane.p[0])) <= tol;
                if (on) found = int(c->second);
              }
            }
      }
      if (found < 0) {
        found = int(planes.size());
        planes.push_back(candidate({{p[0], p[1], p[2]}}));
        by_normal[key_of(planes.back().n)].emplace(planes.back().offset, uint32_t(found));
        largest_rounding = std::max(largest_rounding, planes.back().rounding);
      }
      plane_of[u] = found;
    }
    return plane_of;
  }

  /// Each group's plane made again through three of its corners spread across it: the two
  /// farthest apart (nearly: the farthest from its largest triangle's first corner, and
  /// the farthest from that), and the one farthest from the line through them, in the
  /// order that keeps the plane's orientation. A group of one triangle keeps its plane.
  /// The planes come out largest group first, by area. Returns false when none changed.
  bool spread(const std::vector<int>& plane_of, std::vector<Candidate>& planes) const {
    std::vector<std::vector<uint32_t>> members(planes.size());
    for (uint32_t u : order) members[size_t(plane_of[u])].push_back(u);
    std::vector<std::pair<double, Candidate>> next;
    bool changed = false;
    for (size_t c = 0; c < planes.size(); ++c) {
      if (members[c].empty()) {
        changed = true;  // a plane no triangle took
        continue;
      }
      const Candidate& h = planes[c];
      SharedPlane made = h.plane;
      if (members[c].size() > 1) {
        auto farthest = [&](auto&& measure) {
          Vec3 best = soup[members[c][0]].p[0];
          double m = -1;
          for (uint32_t u : members[c])
            for (const Vec3& q : soup[u].p)
              if (const double d = measure(q); d > m) m = d, best = q;
          return best;
        };
        const Vec3 a = farthest([&](Vec3 q) { return length(q - soup[members[c][0]].p[0]); });
        const Vec3 b = farthest([&](Vec3 q) { return length(q - a); });
        const Vec3 e = farthest([&](Vec3 q) { return length(cross(b - a, q - a)); });
        const Vec3 x = cross(b - a, e - a);
        if (length(x) > 1e-12 * dot(b - a, b - a) && std::fabs(dot(x, h.n)) > 0.5 * length(x))
          made = dot(x, h.n) > 0 ? SharedPlane{{a, b, e}} : SharedPlane{{a, e, b}};
      }
      changed = changed || made.p != h.plane.p;
      double weight = 0;
      for (uint32_t u : members[c]) weight += area[u];
      next.emplace_back(weight, candidate(made));
    }
    if (!changed) return false;
    std::stable_sort(next.begin(), next.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    planes.clear();
    for (auto& [weight, c] : next) planes.push_back(std::move(c));
    return true;
  }
};

}  // namespace

SharedPlanes shared_planes(const std::vector<SoupTriangle>& soup, const SharedPlaneParams& params) {
  const size_t n = soup.size();
  SharedPlanes out;
  out.plane_of.assign(n, -1);
  out.own.assign(n, true);
  if (n == 0) return out;

  // Distances from the middle of the soup, so that an offset's rounding stays small.
  Vec3 lo = soup[0].p[0], hi = lo;
  for (const SoupTriangle& t : soup)
    for (const Vec3& p : t.p)
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)},
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  Grouping g{soup, params, 0.5 * (lo + hi), 0, {}, {}, {}, {}};
  // The rounding of one stored coordinate, relative to its size (a half unit in the last
  // place, twice over for a plane's corners and the member's).
  g.unit = stored_in_floats(soup) ? std::ldexp(1.0, -23) : 16 * DBL_EPSILON;

  // Each triangle's unit normal, area and tolerance; a triangle of no area in doubles
  // takes part in no group.
  g.normal.resize(n), g.area.assign(n, 0), g.tolerance.assign(n, 0);
  for (size_t i = 0; i < n; ++i) {
    const auto& p = soup[i].p;
    const Vec3 c = cross(p[1] - p[0], p[2] - p[0]);
    const double l = std::max({length(p[1] - p[0]), length(p[2] - p[1]), length(p[0] - p[2])});
    g.area[i] = length(c);
    // Far from collinear as doubles go (collinear corners' rounding leaves ~1e-16 l²).
    if (!(g.area[i] > 1e-12 * l * l)) continue;
    g.normal[i] = (1.0 / g.area[i]) * c;
    g.tolerance[i] = params.angle * l + g.unit * largest_coordinate(p);
    g.order.push_back(uint32_t(i));
  }
  std::stable_sort(g.order.begin(), g.order.end(), [&](uint32_t a, uint32_t b) { return g.area[a] > g.area[b]; });

  // Group, spread each group's plane, and group again while planes change (a few rounds:
  // each widens a face's plane to the triangles the last one reached).
  std::vector<Candidate> planes;
  std::vector<int> plane_of = g.group(planes);
  for (int round = 0; round < 3 && g.spread(plane_of, planes); ++round) plane_of = g.group(planes);

  // The planes some triangle took, in order; triangles of no area keep their own.
  std::vector<int> index(planes.size(), -1);
  for (size_t i = 0; i < n; ++i) {
    const auto& p = soup[i].p;
    if (plane_of[i] < 0) {
      out.plane_of[i] = int(out.planes.size());
      out.planes.push_back({{p[0], p[1], p[2]}});
      continue;
    }
    int& k = index[size_t(plane_of[i])];
    if (k < 0) k = int(out.planes.size()), out.planes.push_back(planes[size_t(plane_of[i])].plane);
    out.plane_of[i] = k;
    out.own[i] = out.planes[size_t(k)].p == p;
  }
  return out;
}

}  // namespace avenues
