// Avenues — furniture (see furniture.h).
#include "render/furniture.h"
#include "core/angles.h"
#include "render/scene_objects.h"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <limits>

namespace avenues {

namespace {

constexpr double kBehind = 1e-9;  ///< [m] a point hides only if this far behind a polygon's plane (not on it)

Vec3 unit(Vec3 v) {
  const double l = length(v);
  return l > 0 ? (1.0 / l) * v : v;
}

/// [deg] in [0, 180]: the angle between two unit normals.
double dihedral_deg(Vec3 a, Vec3 b) { return deg_from_rad(std::acos(std::clamp(dot(a, b), -1.0, 1.0))); }

/// Normals and edges of a placed mesh.
void find_edges(FurniturePiece& p) {
  const Mesh& m = p.mesh;
  const size_t polygons = m.polygon_of.empty() ? 0 : size_t(*std::max_element(m.polygon_of.begin(), m.polygon_of.end())) + 1;
  std::vector<Vec3> sum(polygons, Vec3{0, 0, 0});
  std::vector<double> span2(polygons, 0);  // per polygon: its longest side, squared
  p.polygon_point.assign(polygons, Vec3{0, 0, 0});
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const Vec3 a = m.vertices[size_t(tri[0])], b = m.vertices[size_t(tri[1])], c = m.vertices[size_t(tri[2])];
    const size_t k = size_t(m.polygon_of[t]);
    sum[k] = sum[k] + cross(b - a, c - a);
    span2[k] = std::max({span2[k], dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
    p.polygon_point[k] = a;
  }
  // A polygon whose area is rounding beside its size (a needle whose corners were on one
  // line until placing it rounded them off it) has no normal: it is no surface.
  p.polygon_normal.clear();
  for (size_t k = 0; k < polygons; ++k)
    p.polygon_normal.push_back(length(sum[k]) <= 1e-12 * span2[k] ? Vec3{0, 0, 0} : unit(sum[k]));
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
        e.dihedral_deg = dihedral_deg(p.polygon_normal[size_t(e.polygon[0])], p.polygon_normal[size_t(e.polygon[1])]);
      }
      p.edges.push_back(e);
    }
    i = j;
  }
}

}  // namespace

namespace {

/// A detail polygon is cut to the cells it crosses, and a cell's detail is gathered into
/// clusters (cells/soup_detail.h), so the sides of a cluster's mesh that one triangle alone
/// uses are not all the input's open edges: some are edges between two input polygons in
/// two clusters, and some are cuts along the cell's faces. Drawn as an open mesh's
/// boundary, they crossed a curved solid's drawing with lines it does not have. Here each
/// such side that another cluster has too (corner for corner) becomes an edge between the
/// two polygons (the other's kept as a polygon of no triangles, for facing and the
/// dihedral), and one lying on a face of its cell is dropped.
void join_detail_edges(Furniture& f, const CellComplex& complex) {
  if (f.pieces.size() != complex.objects.size()) return;
  // Two pieces of one input edge are cut to a cell's face by two triangles, each in double:
  // their cut corners agree to a rounding, not always to the bit.
  const double tol = 1e-9 * complex.far_box.magnitude(), bucket = 1e3 * tol;
  struct Open {
    size_t piece, edge;
    Vec3 a, b;
    bool done = false;
  };
  std::vector<Open> open;
  std::map<std::array<int64_t, 3>, std::vector<size_t>> near;  // by the edge's middle
  auto square = [&](Vec3 p) {
    return std::array<int64_t, 3>{int64_t(std::floor(p.x / bucket)), int64_t(std::floor(p.y / bucket)),
                                  int64_t(std::floor(p.z / bucket))};
  };
  for (size_t i = 0; i < f.pieces.size(); ++i) {
    if (complex.objects[i].cell < 0) continue;
    const FurniturePiece& p = f.pieces[i];
    for (size_t e = 0; e < p.edges.size(); ++e) {
      if (p.edges[e].polygon[1] >= 0) continue;
      const Vec3 a = p.mesh.vertices[size_t(p.edges[e].v[0])], b = p.mesh.vertices[size_t(p.edges[e].v[1])];
      near[square(0.5 * (a + b))].push_back(open.size());
      open.push_back({i, e, a, b});
    }
  }
  auto same = [&](Vec3 u, Vec3 v) {
    return std::fabs(u.x - v.x) <= tol && std::fabs(u.y - v.y) <= tol && std::fabs(u.z - v.z) <= tol;
  };
  std::vector<std::vector<uint8_t>> drop(f.pieces.size());
  for (size_t i = 0; i < f.pieces.size(); ++i) drop[i].assign(f.pieces[i].edges.size(), 0);
  for (size_t k = 0; k < open.size(); ++k) {
    Open& o = open[k];
    if (o.done) continue;
    o.done = true;
    // The other piece of the same edge, if any: an edge between two polygons.
    const std::array<int64_t, 3> at = square(0.5 * (o.a + o.b));
    Open* twin = nullptr;
    for (int64_t dx = -1; dx <= 1 && !twin; ++dx)
      for (int64_t dy = -1; dy <= 1 && !twin; ++dy)
        for (int64_t dz = -1; dz <= 1 && !twin; ++dz) {
          const auto it = near.find({at[0] + dx, at[1] + dy, at[2] + dz});
          if (it == near.end()) continue;
          for (size_t j : it->second) {
            Open& t = open[j];
            if (t.done || (t.piece == o.piece && t.edge == o.edge)) continue;
            if ((same(o.a, t.a) && same(o.b, t.b)) || (same(o.a, t.b) && same(o.b, t.a))) {
              twin = &t;
              break;
            }
          }
        }
    if (twin) {
      twin->done = true;
      FurniturePiece& keep = f.pieces[o.piece];
      const FurniturePiece& other = f.pieces[twin->piece];
      const size_t poly = size_t(other.edges[twin->edge].polygon[0]);
      FurnitureEdge& e = keep.edges[o.edge];
      if (twin->piece == o.piece) {
        e.polygon[1] = int32_t(poly);
      } else {
        e.polygon[1] = int32_t(keep.polygon_normal.size());
        keep.polygon_normal.push_back(other.polygon_normal[poly]);
        keep.polygon_point.push_back(other.polygon_point[poly]);
      }
      e.dihedral_deg = dihedral_deg(keep.polygon_normal[size_t(e.polygon[0])], keep.polygon_normal[size_t(e.polygon[1])]);
      drop[twin->piece][twin->edge] = 1;
      continue;
    }
    // None: the input's own open edge, or a cut along a face of the piece's cell.
    const Cell& cell = complex.cells[size_t(complex.objects[o.piece].cell)];
    for (const Face& face : cell.faces)
      if (std::fabs(face.plane.eval(o.a)) <= tol && std::fabs(face.plane.eval(o.b)) <= tol) {
        drop[o.piece][o.edge] = 1;
        break;
      }
  }
  for (size_t i = 0; i < f.pieces.size(); ++i) {
    std::vector<FurnitureEdge>& edges = f.pieces[i].edges;
    size_t kept = 0;
    for (size_t e = 0; e < edges.size(); ++e)
      if (!drop[i][e]) edges[kept++] = edges[e];
    edges.resize(kept);
  }
}

}  // namespace

Furniture furniture_of(const CellComplex& complex, const std::vector<PlacedObject>& placed) {
  Furniture f;
  for (const PlacedObject& o : placed) {
    FurniturePiece p;
    p.name = o.name;
    p.mesh = o.mesh;
    find_edges(p);
    for (const ObjectCell& in : o.cells) p.cells.push_back(in.cell);
    f.pieces.push_back(std::move(p));
  }
  join_detail_edges(f, complex);
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

std::vector<uint8_t> polygons_facing(const FurniturePiece& p, const Camera& cam) {
  if (!cam.is_parallel()) return polygons_facing(p, cam.eye);
  std::vector<uint8_t> facing(p.polygon_normal.size());
  for (size_t k = 0; k < facing.size(); ++k) facing[k] = dot(p.polygon_normal[k], cam.forward) < 0;
  return facing;
}

namespace {

/// A point of camera space as the sides of an occluder's cone take it: itself (a cone from
/// the eye at the origin), or in a parallel projection its place on the picture plane, (x, y, 1)
/// (a prism along z).
Vec3 for_sides(Vec3 p, bool parallel) { return parallel ? Vec3{p.x, p.y, 1} : p; }

/// The occluder of a camera-space triangle, or false when it hides nothing.
bool occluder_of(const Vec3 (&P)[3], bool parallel, Occluder& o) {
  if (!parallel && P[0].z <= 0 && P[1].z <= 0 && P[2].z <= 0) return false;  // wholly behind the eye: hides nothing drawn
  o.n = unit(cross(P[1] - P[0], P[2] - P[0]));
  o.d = -dot(o.n, P[0]);
  if (parallel) {
    if (o.n.z > 0) o.n = -1.0 * o.n, o.d = -o.d;  // the viewer (far along -z) on the positive side
    if (!(-o.n.z > 1e-9)) return false;            // seen edge-on: hides nothing
  } else {
    if (o.d < 0) o.n = -1.0 * o.n, o.d = -o.d;  // the eye (the origin) on the positive side
    if (!(o.d > kBehind)) return false;         // seen edge-on: hides nothing
  }
  // The cone's sides, each turned to hold the third corner. A sliver (a corner less than
  // 1e-9 radians off the plane through the eye and the other two) hides nothing that
  // could be drawn, and its sides' rounding could turn its cone to hold points nowhere
  // near it: it is no occluder.
  const Vec3 Q[3] = {for_sides(P[0], parallel), for_sides(P[1], parallel), for_sides(P[2], parallel)};
  for (int k = 0; k < 3; ++k) {
    o.side[k] = cross(Q[k], Q[(k + 1) % 3]);
    const Vec3 third = Q[(k + 2) % 3];
    const double s = dot(o.side[k], third);
    if (!(std::fabs(s) > 1e-9 * length(o.side[k]) * length(third))) return false;
    if (s < 0) o.side[k] = -1.0 * o.side[k];
  }
  const double inf = std::numeric_limits<double>::infinity();
  o.lo = {inf, inf};
  o.hi = {-inf, -inf};
  if (Q[0].z > 0 && Q[1].z > 0 && Q[2].z > 0) {
    for (const Vec3& q : Q) {
      const Vec2 xy{q.x / q.z, q.y / q.z};
      o.lo = {std::min(o.lo.x, xy.x), std::min(o.lo.y, xy.y)};
      o.hi = {std::max(o.hi.x, xy.x), std::max(o.hi.y, xy.y)};
    }
    // Less than 1e-7 across on the picture plane (a ten-thousandth of a pixel at any
    // size a picture is drawn): it hides nothing that could be drawn, and its sides,
    // found from corners a rounding apart, may point anywhere.
    if (!(o.hi.x - o.lo.x > 1e-7 || o.hi.y - o.lo.y > 1e-7)) return false;
  } else {
    o.lo = {-inf, -inf};
    o.hi = {inf, inf};
  }
  return true;
}

}  // namespace

void add_occluders(const FurniturePiece& p, const std::vector<uint8_t>& facing, const Camera& cam,
                   std::vector<Occluder>& out, const Plane* beyond) {
  const Mesh& m = p.mesh;
  const bool parallel = cam.is_parallel();
  if (!parallel) beyond = nullptr;
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    if (m.closed && !facing[size_t(m.polygon_of[t])]) continue;
    // The triangle, or what lies of it beyond the plane the rays start from (at most four
    // corners, a fan of two triangles).
    Vec3 W[4];
    int n = 0;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = m.vertices[size_t(m.triangles[t][size_t(k)])];
      if (!beyond) {
        W[n++] = a;
        continue;
      }
      const Vec3 b = m.vertices[size_t(m.triangles[t][size_t((k + 1) % 3)])];
      const double ea = beyond->eval(a), eb = beyond->eval(b);
      if (ea >= 0) W[n++] = a;
      if ((ea < 0 && eb > 0) || (ea > 0 && eb < 0)) W[n++] = a + (ea / (ea - eb)) * (b - a);
    }
    for (int k = 1; k + 1 < n; ++k) {
      const Vec3 P[3] = {cam.camera_from_world(W[0]), cam.camera_from_world(W[k]), cam.camera_from_world(W[k + 1])};
      Occluder o;
      if (occluder_of(P, parallel, o)) out.push_back(o);
    }
  }
}

namespace {

/// The ends on the picture plane of the stretch of the segment where `intervals` lie
/// (from the first's start to the last's end), and their box [lo, hi].
struct PictureStretch {
  Vec2 a, b, lo, hi;
};
PictureStretch picture_stretch(Vec3 p0, Vec3 p1, const std::vector<detail::Interval>& intervals) {
  const Vec3 d = p1 - p0;
  const Vec3 a = p0 + intervals.front().t0 * d, b = p0 + intervals.back().t1 * d;  // Z > 0 on the intervals
  PictureStretch s{{a.x / a.z, a.y / a.z}, {b.x / b.z, b.y / b.z}, {}, {}};
  s.lo = {std::min(s.a.x, s.b.x), std::min(s.a.y, s.b.y)};
  s.hi = {std::max(s.a.x, s.b.x), std::max(s.a.y, s.b.y)};
  return s;
}

/// Subtracts what occluder o hides of the intervals (a set difference: in any order of
/// occluders, the same intervals), which lay within [first, last] and
/// within the box [lo, hi] at the start; false once nothing is left.
bool hide_behind_one(const Occluder& o, Vec3 p0, Vec3 p1, Vec3 q0, Vec3 q1, double first, double last, Vec2 lo,
                     Vec2 hi, std::vector<detail::Interval>& intervals) {
  if (o.hi.x < lo.x || hi.x < o.lo.x || o.hi.y < lo.y || hi.y < o.lo.y) return true;
  detail::Interval h{first, last};
  bool alive = detail::clip_interval(h, -(dot(o.n, p0) + o.d) - kBehind, -(dot(o.n, p1) + o.d) - kBehind);
  for (int k = 0; k < 3 && alive; ++k) alive = detail::clip_interval(h, dot(o.side[k], q0), dot(o.side[k], q1));
  if (alive) detail::subtract_interval(intervals, h);
  return !intervals.empty();
}

}  // namespace

void hide_behind(const std::vector<Occluder>& occluders, Vec3 p0, Vec3 p1, std::vector<detail::Interval>& intervals,
                 bool parallel) {
  if (intervals.empty()) return;
  const double first = intervals.front().t0, last = intervals.back().t1;
  const Vec3 q0 = for_sides(p0, parallel), q1 = for_sides(p1, parallel);
  const PictureStretch s = picture_stretch(q0, q1, intervals);
  for (const Occluder& o : occluders)
    if (!hide_behind_one(o, p0, p1, q0, q1, first, last, s.lo, s.hi, intervals)) return;
}

OccluderGrid::OccluderGrid(std::vector<Occluder> occluders, bool parallel)
    : occluders_(std::move(occluders)), parallel_(parallel) {
  // An occluder reaching behind the eye has no box on the picture plane.
  auto bounded = [](const Occluder& o) {
    return std::isfinite(o.lo.x) && std::isfinite(o.hi.x) && std::isfinite(o.lo.y) && std::isfinite(o.hi.y);
  };
  Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (const Occluder& o : occluders_)
    if (bounded(o))
      lo = {std::min(lo.x, o.lo.x), std::min(lo.y, o.lo.y)}, hi = {std::max(hi.x, o.hi.x), std::max(hi.y, o.hi.y)};
  n_ = std::clamp(int(std::sqrt(double(occluders_.size()) / 4)), 1, 256);
  lo_ = lo;
  size_ = {std::max((hi.x - lo.x) / n_, 1e-12), std::max((hi.y - lo.y) / n_, 1e-12)};
  auto bin = [&](double v, double v0, double s) { return std::clamp(int((v - v0) / s), 0, n_ - 1); };
  std::vector<int32_t> count(size_t(n_) * size_t(n_) + 1, 0);
  std::vector<std::array<int, 4>> range(occluders_.size());
  for (size_t i = 0; i < occluders_.size(); ++i) {
    const Occluder& o = occluders_[i];
    auto& r = range[i];
    if (!(lo.x <= hi.x) || !bounded(o)) {
      r = {1, 0, 1, 0};  // none: met everywhere
    } else {
      r = {bin(o.lo.x, lo_.x, size_.x), bin(o.hi.x, lo_.x, size_.x), bin(o.lo.y, lo_.y, size_.y), bin(o.hi.y, lo_.y, size_.y)};
      if (4 * (r[1] - r[0] + 1) * (r[3] - r[2] + 1) > n_ * n_ && n_ > 1) r = {1, 0, 1, 0};
    }
    if (r[0] > r[1]) {
      everywhere_.push_back(int32_t(i));
      continue;
    }
    for (int y = r[2]; y <= r[3]; ++y)
      for (int x = r[0]; x <= r[1]; ++x) count[size_t(y) * size_t(n_) + size_t(x) + 1]++;
  }
  for (size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
  start_ = count;
  items_.resize(size_t(count.back()));
  for (size_t i = 0; i < occluders_.size(); ++i) {
    const auto& r = range[i];
    for (int y = r[2]; y <= r[3]; ++y)
      for (int x = r[0]; x <= r[1]; ++x) items_[size_t(count[size_t(y) * size_t(n_) + size_t(x)]++)] = int32_t(i);
  }
}

void OccluderGrid::near(Vec2 a, Vec2 b, std::vector<int32_t>& out) const {
  out.assign(everywhere_.begin(), everywhere_.end());
  if (items_.empty()) return;
  // Each occluder once, without sorting: a mark per occluder, this call's own number.
  thread_local std::vector<uint64_t> mark;
  thread_local uint64_t call = 0;
  if (mark.size() < occluders_.size()) mark.resize(occluders_.size(), 0);
  ++call;
  auto bin = [&](double v, double v0, double s) {
    return int(std::clamp(std::floor((v - v0) / s), -1.0, double(n_)));  // -1 and n_: off the grid
  };
  if (a.y > b.y) std::swap(a, b);
  const int y0 = std::max(bin(a.y, lo_.y, size_.y), 0), y1 = std::min(bin(b.y, lo_.y, size_.y), n_ - 1);
  for (int y = y0; y <= y1; ++y) {
    // The stretch of x where the segment crosses this row of bins.
    double xa = a.x, xb = b.x;
    if (b.y - a.y > 0) {
      const double r0 = lo_.y + y * size_.y, r1 = r0 + size_.y;
      const double t0 = std::clamp((r0 - a.y) / (b.y - a.y), 0.0, 1.0), t1 = std::clamp((r1 - a.y) / (b.y - a.y), 0.0, 1.0);
      xa = a.x + t0 * (b.x - a.x), xb = a.x + t1 * (b.x - a.x);
    }
    if (xa > xb) std::swap(xa, xb);
    const int x0 = std::max(bin(xa, lo_.x, size_.x) - 1, 0), x1 = std::min(bin(xb, lo_.x, size_.x) + 1, n_ - 1);
    for (int x = x0; x <= x1; ++x) {
      const size_t k = size_t(y) * size_t(n_) + size_t(x);
      for (int32_t at = start_[k]; at < start_[k + 1]; ++at) {
        const int32_t i = items_[size_t(at)];
        if (mark[size_t(i)] != call) mark[size_t(i)] = call, out.push_back(i);
      }
    }
  }
}

void hide_behind(const OccluderGrid& occluders, Vec3 p0, Vec3 p1, std::vector<detail::Interval>& intervals) {
  if (intervals.empty()) return;
  const double first = intervals.front().t0, last = intervals.back().t1;
  const Vec3 q0 = for_sides(p0, occluders.parallel()), q1 = for_sides(p1, occluders.parallel());
  const PictureStretch s = picture_stretch(q0, q1, intervals);
  thread_local std::vector<int32_t> candidates;
  occluders.near(s.a, s.b, candidates);
  for (const int32_t i : candidates)
    if (!hide_behind_one(occluders.all()[size_t(i)], p0, p1, q0, q1, first, last, s.lo, s.hi, intervals)) return;
}

}  // namespace avenues
