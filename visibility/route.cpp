// Avenues — routes on the portal graph (see route.h).
#include "visibility/route.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <stdexcept>

namespace avenues {

namespace {

Vec3 centre(const std::vector<Vec3>& poly) {
  Vec3 m{0, 0, 0};
  for (Vec3 v : poly) m = m + v;
  return (1.0 / double(poly.size())) * m;
}

/// Can a person pass through this portal from cell `from`?
bool walkable(const CellComplex& c, const Portal& p, CellId from, const RouteOptions& o) {
  if (std::fabs(p.plane.n.z) > 0.5) return false;  // horizontal: stairwells need stairs
  if (p.kind == PortalKind::Window || p.kind == PortalKind::Hatch) return false;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (Vec3 v : p.poly) lo = std::min(lo, v.z), hi = std::max(hi, v.z);
  const double floor = std::max(c.cells[size_t(from)].z0, c.cells[size_t(p.other(from))].z0);
  return lo - floor <= o.max_step && hi - lo >= o.min_height;
}

Vec3 at_eye(const CellComplex& c, CellId id, Vec2 p, const RouteOptions& o) {
  return {p.x, p.y, c.cells[size_t(id)].z0 + o.eye_height};
}

}  // namespace

std::vector<Vec3> route_through(const CellComplex& c, const std::vector<std::string>& names, const RouteOptions& o) {
  std::vector<RoomId> rooms;
  for (const std::string& name : names) {
    RoomId found = -1;
    for (size_t r = 0; r < c.rooms.size() && found < 0; ++r)
      if (c.rooms[r].name == name) found = RoomId(r);
    if (found < 0) {
      std::string known;
      for (const RoomInfo& r : c.rooms) known += (known.empty() ? "'" : ", '") + r.name + "'";
      throw std::runtime_error("the plan has no room '" + name + "' (its rooms: " + known + ")");
    }
    rooms.push_back(found);
  }
  if (rooms.empty()) throw std::runtime_error("a route needs at least one room");
  CellId here = c.largest_cell_of(rooms[0]);
  if (here == kNoCell) throw std::runtime_error("room '" + names[0] + "' has no cell to stand in");
  std::vector<Vec3> points{at_eye(c, here, centroid(c.cells[size_t(here)].footprint), o)};

  for (size_t k = 1; k < rooms.size(); ++k) {
    // Dijkstra from the current point over cells; a step into a cell costs the distance
    // from the last point to the centre of the portal crossed.
    const size_t n = c.cells.size();
    std::vector<double> dist(n, HUGE_VAL);
    std::vector<PortalId> via(n, -1);
    std::vector<Vec3> point(n);
    using Item = std::pair<double, CellId>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    dist[size_t(here)] = 0;
    point[size_t(here)] = points.back();
    queue.push({0, here});
    CellId reached = kNoCell;
    while (!queue.empty()) {
      auto [d, cell] = queue.top();
      queue.pop();
      if (d > dist[size_t(cell)]) continue;
      if (c.cells[size_t(cell)].kind == CellKind::Room && c.cells[size_t(cell)].room == rooms[k]) {
        reached = cell;
        break;
      }
      for (PortalId pi : c.cells[size_t(cell)].portals) {
        const Portal& p = c.portals[size_t(pi)];
        if (!walkable(c, p, cell, o)) continue;
        const CellId next = p.other(cell);
        Vec3 m = centre(p.poly);
        m.z = std::min(c.cells[size_t(cell)].z0, c.cells[size_t(next)].z0) + o.eye_height;
        const double nd = d + length(m - point[size_t(cell)]);
        if (nd < dist[size_t(next)]) {
          dist[size_t(next)] = nd;
          via[size_t(next)] = pi;
          point[size_t(next)] = m;
          queue.push({nd, next});
        }
      }
    }
    if (reached == kNoCell)
      throw std::runtime_error("room '" + names[k] + "' cannot be reached on foot from room '" + names[k - 1] + "'");
    std::vector<Vec3> leg;
    for (CellId cell = reached; cell != here; cell = c.portals[size_t(via[size_t(cell)])].other(cell))
      leg.push_back(point[size_t(cell)]);
    std::reverse(leg.begin(), leg.end());
    points.insert(points.end(), leg.begin(), leg.end());
    // On to the centre of the room's cell the walk came into (a convex cell: the straight
    // step from the portal to its centre stays inside).
    here = reached;
    points.push_back(at_eye(c, here, centroid(c.cells[size_t(here)].footprint), o));
  }
  return points;
}

std::vector<Vec3> smooth_path(const CellComplex& c, const std::vector<Vec3>& w, double step) {
  if (!(step > 0)) throw std::runtime_error("the step along a path must be a positive length");
  std::vector<Vec3> out;
  if (w.empty()) return out;
  out.push_back(w[0]);
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    // Catmull–Rom between w[i] and w[i+1], with the neighbours as tangent guides.
    const Vec3 p0 = i > 0 ? w[i - 1] : w[i], p1 = w[i], p2 = w[i + 1], p3 = i + 2 < w.size() ? w[i + 2] : w[i + 1];
    const int64_t n = stretch_points(p1, p2, step);
    std::vector<Vec3> seg;
    bool free = true;
    CellId hint = kNoCell;
    for (int64_t s = 1; s <= n && free; ++s) {
      const double t = double(s) / double(n), t2 = t * t, t3 = t2 * t;
      const Vec3 q = 0.5 * ((2 * t2 - t3 - t) * 1.0 * p0 + (3 * t3 - 5 * t2 + 2) * 1.0 * p1 +
                            (4 * t2 - 3 * t3 + t) * 1.0 * p2 + (t3 - t2) * 1.0 * p3);
      const Location at = c.locate(q, hint);
      free = at.what == Location::What::Cell;
      hint = at.cell;
      seg.push_back(q);
    }
    if (!free) {  // the curve would cut a jamb: walk this stretch straight
      seg.clear();
      for (int64_t s = 1; s <= n; ++s) seg.push_back(p1 + (double(s) / double(n)) * (p2 - p1));
    }
    out.insert(out.end(), seg.begin(), seg.end());
  }
  return out;
}

int64_t stretch_points(Vec3 a, Vec3 b, double step) {
  const double n = std::ceil(length(b - a) / step);
  // Beyond 2^62 (or NaN) the count is "too many" anyway: keep it representable.
  if (!(n < 4.6e18)) return int64_t(1) << 62;
  return std::max<int64_t>(1, int64_t(n));
}

int64_t path_points(const std::vector<Vec3>& w, double step) {
  if (w.empty()) return 0;
  int64_t n = 1;
  for (size_t i = 0; i + 1 < w.size(); ++i) n = std::min(n + stretch_points(w[i], w[i + 1], step), int64_t(1) << 62);
  return n;
}

}  // namespace avenues
