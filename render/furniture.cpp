// Avenues — furniture (see furniture.h).
#include "render/furniture.h"
#include "core/angles.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace avenues {

namespace {

constexpr double kBehind = 1e-9;  ///< [m] a point hides only if this far behind a polygon's plane (not on it)

Vec3 unit(Vec3 v) {
  const double l = length(v);
  return l > 0 ? (1.0 / l) * v : v;
}

/// Normals and edges of a placed mesh.
void find_edges(FurniturePiece& p) {
  const Mesh& m = p.mesh;
  const size_t polygons = m.polygon_of.empty() ? 0 : size_t(*std::max_element(m.polygon_of.begin(), m.polygon_of.end())) + 1;
  std::vector<Vec3> sum(polygons, Vec3{0, 0, 0});
  p.polygon_point.assign(polygons, Vec3{0, 0, 0});
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const Vec3 a = m.vertices[size_t(tri[0])], b = m.vertices[size_t(tri[1])], c = m.vertices[size_t(tri[2])];
    sum[size_t(m.polygon_of[t])] = sum[size_t(m.polygon_of[t])] + cross(b - a, c - a);
    p.polygon_point[size_t(m.polygon_of[t])] = a;
  }
  p.polygon_normal.clear();
  for (Vec3 s : sum) p.polygon_normal.push_back(unit(s));
  // Every triangle side, keyed by its vertex pair; sides of one polygon only are diagonals.
  struct Side {
    int32_t lo, hi, polygon;
  };
  std::vector<Side> sides;
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int32_t u = m.triangles[t][size_t(k)], v = m.triangles[t][size_t((k + 1) % 3)];
      sides.push_back({std::min(u, v), std::max(u, v), int32_t(m.polygon_of[t])});
    }
  std::sort(sides.begin(), sides.end(), [](const Side& a, const Side& b) {
    return a.lo != b.lo ? a.lo < b.lo : a.hi != b.hi ? a.hi < b.hi : a.polygon < b.polygon;
  });
  for (size_t i = 0; i < sides.size();) {
    size_t j = i;
    while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi) ++j;
    // A side only of polygons of no area (a needle, the walls of a box of no height) is
    // no edge of anything seen: it would be drawn as a line of its own.
    bool flat_only = true;
    for (size_t k = i; k < j && flat_only; ++k) flat_only = length(p.polygon_normal[size_t(sides[k].polygon)]) == 0;
    if (flat_only) {
      i = j;
      continue;
    }
    FurnitureEdge e;
    e.v[0] = sides[i].lo;
    e.v[1] = sides[i].hi;
    e.polygon[0] = sides[i].polygon;
    for (size_t k = i + 1; k < j && e.polygon[1] < 0; ++k)
      if (sides[k].polygon != e.polygon[0]) e.polygon[1] = sides[k].polygon;
    const bool boundary = j - i == 1;
    if (boundary || e.polygon[1] >= 0) {  // not a diagonal inside one polygon
      if (e.polygon[1] >= 0) {
        const double c = dot(p.polygon_normal[size_t(e.polygon[0])], p.polygon_normal[size_t(e.polygon[1])]);
        e.dihedral_deg = deg_from_rad(std::acos(std::clamp(c, -1.0, 1.0)));
      }
      p.edges.push_back(e);
    }
    i = j;
  }
}

}  // namespace

Furniture place_furniture(const CellComplex& c) {
  Furniture f;
  std::map<std::string, Mesh> loaded;
  for (const Object& o : c.objects) {
    auto it = loaded.find(mesh_key(o));
    if (it == loaded.end()) it = loaded.emplace(mesh_key(o), load_object_mesh(o)).first;
    const double floor_z = o.storey >= 0 && size_t(o.storey) < c.storeys.size() ? c.storeys[size_t(o.storey)].elevation : 0;
    FurniturePiece p;
    p.name = o.name;
    p.mesh = place(it->second, o, floor_z);
    find_edges(p);
    Box3 box;
    for (Vec3 v : p.mesh.vertices) box.add(v);
    if (o.cell >= 0 && size_t(o.cell) < c.cells.size()) {  // cut to that cell already
      p.cells.push_back(o.cell);
      f.pieces.push_back(std::move(p));
      continue;
    }
    for (CellId id = 0; id < CellId(c.cells.size()); ++id) {
      const Box3 b = c.cells[size_t(id)].bounds();
      if (b.lo.x <= box.hi.x && box.lo.x <= b.hi.x && b.lo.y <= box.hi.y && box.lo.y <= b.hi.y &&
          b.lo.z <= box.hi.z && box.lo.z <= b.hi.z)
        p.cells.push_back(id);
    }
    f.pieces.push_back(std::move(p));
  }
  return f;
}

std::vector<uint8_t> polygons_facing(const FurniturePiece& p, Vec3 eye) {
  std::vector<uint8_t> facing(p.polygon_normal.size());
  for (size_t k = 0; k < facing.size(); ++k) facing[k] = dot(p.polygon_normal[k], eye - p.polygon_point[k]) > 0;
  return facing;
}

bool edge_is_seen(const FurnitureEdge& e, const std::vector<uint8_t>& facing, double crease_deg, Weight& weight) {
  if (e.polygon[1] < 0) {  // the boundary of an open mesh, seen from either side
    weight = Weight::Outline;
    return true;
  }
  const bool f0 = facing[size_t(e.polygon[0])], f1 = facing[size_t(e.polygon[1])];
  if (f0 != f1) {  // Crow: one polygon faces the eye, the other away — a silhouette
    weight = Weight::Outline;
    return true;
  }
  weight = Weight::Crease;
  return f0 && e.dihedral_deg > crease_deg;  // both away: hidden by the closed mesh itself
}

void add_occluders(const FurniturePiece& p, const std::vector<uint8_t>& facing, const Camera& cam,
                   std::vector<Occluder>& out) {
  const Mesh& m = p.mesh;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    if (m.closed && !facing[size_t(m.polygon_of[t])]) continue;
    Vec3 P[3];
    for (int k = 0; k < 3; ++k) P[k] = cam.camera_from_world(m.vertices[size_t(m.triangles[t][size_t(k)])]);
    if (P[0].z <= 0 && P[1].z <= 0 && P[2].z <= 0) continue;  // wholly behind the eye: hides nothing drawn
    Occluder o;
    o.n = unit(cross(P[1] - P[0], P[2] - P[0]));
    o.d = -dot(o.n, P[0]);
    if (o.d < 0) o.n = -1.0 * o.n, o.d = -o.d;  // the eye (the origin) on the positive side
    if (!(o.d > kBehind)) continue;             // seen edge-on: hides nothing
    for (int k = 0; k < 3; ++k) {
      o.side[k] = cross(P[k], P[(k + 1) % 3]);
      if (dot(o.side[k], P[(k + 2) % 3]) < 0) o.side[k] = -1.0 * o.side[k];
    }
    const double inf = std::numeric_limits<double>::infinity();
    o.lo = {inf, inf};
    o.hi = {-inf, -inf};
    if (P[0].z > 0 && P[1].z > 0 && P[2].z > 0) {
      for (const Vec3& q : P) {
        const Vec2 xy{q.x / q.z, q.y / q.z};
        o.lo = {std::min(o.lo.x, xy.x), std::min(o.lo.y, xy.y)};
        o.hi = {std::max(o.hi.x, xy.x), std::max(o.hi.y, xy.y)};
      }
    } else {
      o.lo = {-inf, -inf};
      o.hi = {inf, inf};
    }
    out.push_back(o);
  }
}

void hide_behind(const std::vector<Occluder>& occluders, Vec3 p0, Vec3 p1, std::vector<detail::Interval>& intervals) {
  if (intervals.empty()) return;
  const double first = intervals.front().t0, last = intervals.back().t1;
  const Vec3 d = p1 - p0;
  const Vec3 a = p0 + first * d, b = p0 + last * d;  // Z > 0 on the intervals
  const Vec2 lo{std::min(a.x / a.z, b.x / b.z), std::min(a.y / a.z, b.y / b.z)};
  const Vec2 hi{std::max(a.x / a.z, b.x / b.z), std::max(a.y / a.z, b.y / b.z)};
  for (const Occluder& o : occluders) {
    if (o.hi.x < lo.x || hi.x < o.lo.x || o.hi.y < lo.y || hi.y < o.lo.y) continue;
    detail::Interval h{first, last};
    bool alive = detail::clip_interval(h, -(dot(o.n, p0) + o.d) - kBehind, -(dot(o.n, p1) + o.d) - kBehind);
    for (int k = 0; k < 3 && alive; ++k) alive = detail::clip_interval(h, dot(o.side[k], p0), dot(o.side[k], p1));
    if (alive) detail::subtract_interval(intervals, h);
    if (intervals.empty()) return;
  }
}

}  // namespace avenues
