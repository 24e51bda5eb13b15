// Avenues — pass 5 of build_cells: convex footprints become prisms, portals and faces.
//
// Each piece of each band is a cell from the band's floor to its ceiling (a doorway
// piece: one cell per open height interval). Then, all by index on the triangulation:
//  - a side half-edge whose far triangle is free in the same band gives a portal over
//    the heights both cells share (cut by a wall of no thickness where it is solid);
//  - triangles stacked across a band boundary give horizontal portals where both are
//    free, and floors or ceilings where one is solid (merged into convex pieces);
//  - what no portal covers is opaque, as convex rectangles (sides) or polygons (floors).
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "cells/passes.h"

namespace avenues::detail {

namespace {

constexpr double kZTol = 1e-9;  ///< [m] heights are compared exactly up to this
constexpr double kMinArea = 1e-12;  ///< [m²] a footprint smaller than this is a sliver, not a cell
constexpr double kMinWidth = 1e-9;  ///< [m] a portal narrower than this is not a portal

/// Footprint of a piece: the boundary's vertices without collinear ones. side[k] is the
/// footprint side index of boundary half-edge k; the footprint starts at a kept vertex.
struct Outline2 {
  std::vector<Vec2> poly;
  std::vector<int32_t> half_edges;  ///< rotated so half_edges[0] starts side 0
  std::vector<int32_t> side;
};

Outline2 footprint_of(const Triangulation& T, const std::vector<int32_t>& boundary) {
  const size_t m = boundary.size();
  // Points that rounded to one (a wall top whose corners lie within rounding of each other),
  // or to points a rounding apart, count as one: the first of a run stands for it, and a
  // corner is judged against its nearest distinct neighbours (corners_of), as merging judged it.
  std::vector<Vec2> ring;
  std::vector<uint8_t> made;
  std::vector<Corner> corner;
  corners_of(ring, corner, ring_of(T, boundary, ring, made));
  std::vector<uint8_t> keep(m);
  for (size_t k = 0; k < m; ++k) keep[k] = corner[k] == Corner::Left || corner[k] == Corner::Right;
  size_t first = 0;
  while (first < m && !keep[first]) ++first;
  Outline2 o;
  if (first == m) return o;  // degenerate (all collinear): no footprint
  for (size_t j = 0; j < m; ++j) {
    size_t k = (first + j) % m;
    if (keep[k]) o.poly.push_back(ring[k]);
    o.half_edges.push_back(boundary[k]);
    o.side.push_back(int32_t(o.poly.size()) - 1);
  }
  return o;
}

Vec3 at(Vec2 p, double z) { return {p.x, p.y, z}; }

/// A height along a cell's side: level, or a sloped wall's top (then `z` is unused).
struct Level {
  double z = 0;
  const Slope* plane = nullptr;
  double operator()(Vec2 p) const { return plane ? (*plane)(p) : z; }
  /// The same level: one plane, or heights within kZTol.
  bool same(const Level& o) const {
    return plane || o.plane ? plane && o.plane && *plane == *o.plane : std::fabs(z - o.z) < kZTol;
  }
  /// The same level exactly: one plane, or one height.
  bool identical(const Level& o) const { return plane || o.plane ? plane && o.plane && *plane == *o.plane : z == o.z; }
};

/// The polygon p0 → p1 between heights lo and hi at each end, without the corners where
/// lo meets hi (a wedge's tip): {(p0, lo0), (p1, lo1), (p1, hi1), (p0, hi0)}.
std::vector<Vec3> band_polygon(Vec2 p0, Vec2 p1, double lo0, double lo1, double hi0, double hi1) {
  std::vector<Vec3> poly{at(p0, lo0), at(p1, lo1)};
  if (hi1 > lo1 + kZTol) poly.push_back(at(p1, hi1));
  if (hi0 > lo0 + kZTol) poly.push_back(at(p0, hi0));
  return poly;
}

/// The material of the side of `wall` that a cell's side from a to b faces (the cell on
/// its left, counter-clockwise): the wall's left side (Wall::material) when the cell lies
/// left of the centre line's nearest segment, else its right side (Wall::right_material,
/// where it has one). On a wall of no thickness the side runs along the centre line, and
/// its direction says which side of the wall the cell is on.
MaterialId wall_material(const Plan& plan, int wall, Vec2 a, Vec2 b) {
  if (wall < 0) return -1;
  const Wall& w = plan.walls[size_t(wall)];
  if (w.right_material < 0 || w.centre.size() < 2) return w.material;
  const Vec2 m = 0.5 * (a + b);
  size_t best = 0;
  double best_d = HUGE_VAL;
  for (size_t k = 0; k + 1 < w.centre.size(); ++k) {
    const double d = distance_to_segment(m, w.centre[k], w.centre[k + 1]);
    if (d < best_d) best_d = d, best = k;
  }
  const Vec2 s = w.centre[best + 1] - w.centre[best];
  double side = cross(s, m - w.centre[best]);
  if (std::fabs(side) <= 1e-9 * length(s)) side = dot(s, b - a);
  return side > 0 ? w.material : w.right_material;
}

}  // namespace

CellId Layout::cell_at(const CellComplex& c, size_t b, int t, double z) const {
  if (t < 0) return kNoCell;
  int32_t p = pieces[b].of[size_t(t)];
  if (p < 0) return kNoCell;
  for (CellId id : cells_of[b][size_t(p)])
    if (z > c.cells[size_t(id)].z0 && z < c.cells[size_t(id)].z1) return id;
  return kNoCell;
}

Layout extrude(const Plan& plan, const Outline& outline, const Triangulation& T, const Classes& C,
               CellComplex& out) {
  const int n = T.size();
  Layout L;
  // Per cell: its band and its boundary (half-edges with side indices).
  std::vector<size_t> band_of, band_last;  // per cell: the bands it spans, first and last
  std::vector<Outline2> shape;

  // --- 4. merge, per band; 5a. one cell per piece and open interval.
  for (size_t b = 0; b < C.bands.size(); ++b) {
    const Band& band = C.bands[b];
    L.pieces.push_back(merge_convex(T, C.of[b], band_barrier(outline, T, band, b)));
    const Pieces& P = L.pieces.back();
    L.cells_of.emplace_back(P.boundary.size());
    for (size_t p = 0; p < P.boundary.size(); ++p) {
      const SpaceClass& sc = C.classes[size_t(P.label[p])];
      // The outside piece right above an identical outside piece (the slab band around a
      // building has the storey band's outline) continues that cell upwards: one tall cell
      // instead of a stack of two joined by a horizontal portal, and so fewer avenues.
      if (sc.kind == CellKind::Outside && b > 0 && !P.boundary[p].empty()) {
        const int t = P.boundary[p][0] / 3;
        const int32_t q = L.pieces[b - 1].of[size_t(t)];
        if (q >= 0 && L.cells_of[b - 1][size_t(q)].size() == 1) {
          const CellId d = L.cells_of[b - 1][size_t(q)][0];
          Cell& below = out.cells[size_t(d)];
          auto sorted = [](std::vector<int32_t> v) { std::sort(v.begin(), v.end()); return v; };
          if (below.kind == CellKind::Outside && std::fabs(below.z1 - band.z0) < kZTol &&
              sorted(L.pieces[b - 1].boundary[size_t(q)]) == sorted(P.boundary[p])) {
            below.z1 = band.z1;
            band_last[size_t(d)] = b;
            L.cells_of[b][p].push_back(d);
            continue;
          }
        }
      }
      Outline2 o = footprint_of(T, P.boundary[p]);
      // A sliver left by nearly coincident input points (below any built size) stays solid.
      if (o.poly.size() < 3 || signed_area(o.poly) <= kMinArea) continue;
      Intervals iv{{band.z0, band.z1}};
      if (sc.top) {  // the sloped interval on its own: it may touch an opening's head
        iv = intersect(iv, Intervals(sc.open.begin(), sc.open.end() - 1));
        const auto [lo, hi] = sc.open.back();
        if (std::min(hi, band.z1) > std::max(lo, band.z0)) iv.push_back({std::max(lo, band.z0), std::min(hi, band.z1)});
      } else if (!sc.open.empty()) {
        iv = intersect(iv, sc.open);
      }
      for (auto [z0, z1] : iv) {
        // Over a sloped wall, the interval up to the ceiling has the wall's top for a floor.
        std::optional<Slope> floor;
        if (sc.top && z1 >= sc.open.back().second - kZTol) {
          floor = sc.top;
          z0 = HUGE_VAL;
          for (Vec2 v : o.poly) z0 = std::min(z0, std::clamp((*floor)(v), band.z0, z1));
          if (!(z1 > z0 + kZTol)) continue;
        }
        Cell c;
        c.kind = sc.kind;
        c.room = sc.room;
        c.opening = sc.opening;
        c.storey = band.kind == Band::Kind::Storey ? band.storey
                   : (band.kind == Band::Kind::Slab && sc.kind == CellKind::Stairwell) ? band.storey + 1
                                                                                        : -1;
        c.footprint = o.poly;
        c.z0 = z0;
        c.z1 = z1;
        c.prism = !floor;
        L.cells_of[b][p].push_back(CellId(out.cells.size()));
        L.floor_plane.push_back(floor);
        out.cells.push_back(std::move(c));
        band_of.push_back(b);
        band_last.push_back(b);
        shape.push_back(o);
      }
    }
  }

  // The floor of each cell along its sides: its z0, or a sloped wall's top (held within
  // the cell's heights: a wedge's tip meets its ceiling).
  auto floor_of = [&](CellId id) {
    const auto& f = L.floor_plane[size_t(id)];
    return f ? Level{0, &*f} : Level{out.cells[size_t(id)].z0, nullptr};
  };
  auto height = [&](CellId id, const Level& l, Vec2 p) {
    const Cell& c = out.cells[size_t(id)];
    return std::clamp(l(p), c.z0, c.z1);
  };

  // --- 5b. faces: sides, bottom, top (whole, before portals are cut out).
  for (CellId id = 0; id < CellId(out.cells.size()); ++id) {
    Cell& c = out.cells[size_t(id)];
    const Level floor = floor_of(id);
    const size_t m = c.footprint.size();
    for (size_t k = 0; k < m; ++k) {
      Vec2 a = c.footprint[k], b = c.footprint[(k + 1) % m];
      Vec2 d = b - a;
      double len = length(d);
      Face f;
      f.plane.n = {d.y / len, -d.x / len, 0};
      f.plane.d = -dot(f.plane.n, at(a, 0));
      // From the floor to the ceiling at each end; without a corner at a wedge's tip.
      const double za = height(id, floor, a), zb = height(id, floor, b);
      if (za < c.z1 - kZTol) f.poly.push_back(at(a, za));
      f.poly.push_back(at(a, c.z1));
      f.poly.push_back(at(b, c.z1));
      if (zb < c.z1 - kZTol) f.poly.push_back(at(b, zb));
      c.faces.push_back(std::move(f));
    }
    Face bottom, top;
    bottom.plane = {{0, 0, -1}, c.z0};
    if (floor.plane) {  // the wall's top, facing down and along the slope
      const Slope& s = *floor.plane;
      const Vec3 down = Vec3{s.grad.x, s.grad.y, -1};
      bottom.plane.n = (1.0 / length(down)) * down;
      bottom.plane.d = -dot(bottom.plane.n, at(s.at, s.z0));
    }
    top.plane = {{0, 0, 1}, -c.z1};
    for (Vec2 p : c.footprint) bottom.poly.push_back(at(p, height(id, floor, p)));
    for (size_t k = m; k-- > 0;) top.poly.push_back(at(c.footprint[k], c.z1));
    c.faces.push_back(std::move(bottom));
    c.faces.push_back(std::move(top));
  }

  auto add_portal = [&](CellId a, CellId b, std::vector<Vec3> poly, Vec3 normal, PortalKind kind, int opening) {
    Portal p;
    p.cell[0] = a;
    p.cell[1] = b;
    p.plane.n = normal;
    p.plane.d = -dot(normal, poly[0]);
    p.poly = std::move(poly);
    p.kind = kind;
    p.opening = opening;
    out.portals.push_back(std::move(p));
    return PortalId(out.portals.size() - 1);
  };
  // Which kind of portal joins cells a and b (vertically).
  auto kind_between = [&](const Cell& a, const Cell& b, int& opening) {
    for (const Cell* c : {&a, &b})
      if (c->kind == CellKind::Doorway) {
        opening = c->opening;
        for (const SpaceClass& sc : C.classes)
          if (sc.kind == CellKind::Doorway && sc.opening == c->opening) return sc.portal;
        return PortalKind::Gap;
      }
    opening = -1;
    if (a.kind == CellKind::Room && b.kind == CellKind::Room && a.room == b.room) return PortalKind::Transparent;
    return PortalKind::Open;
  };

  // --- 5c. side portals and opaque side pieces.
  // A portal's or an opaque piece's bottom and top along a side are Levels: flat, or along
  // a sloped wall's top (a cell over the wall, or the room beside it seeing over it).
  struct Rect { double s0, s1; Level lo, hi; MaterialId material = -1; };
  for (CellId ci = 0; ci < CellId(out.cells.size()); ++ci) {
    const Outline2& o = shape[size_t(ci)];
    Cell& c = out.cells[size_t(ci)];
    const Level own_floor = floor_of(ci);
    const size_t nsides = c.footprint.size();
    std::vector<std::vector<Rect>> open(nsides);       // portal pieces per side, in side coords
    // A side's material where nothing opaque lies behind a stretch of it: the one that
    // bounds most of its length (an outside cell's side runs past the corners of the walls
    // beside the one it faces).
    std::vector<std::map<MaterialId, double>> side_materials(nsides);
    // And which material lies behind each stretch of a side (s0, s1 along it): a side may
    // run past several walls (a bathroom's tiles, then the hall's plaster, in one line),
    // and each opaque piece takes the material behind it, the side's where none is.
    struct Span { double s0, s1, height; MaterialId material; };
    std::vector<std::vector<Span>> side_spans(nsides);
    // Runs of equal (neighbour, lo, hi) along consecutive pieces of one side.
    struct Run { CellId d; Level lo; double hi, s0, s1; int sheet_opening; int side; };
    std::vector<Run> active, next, done;
    // Runs end here; they become portals once every band the cell spans has been walked
    // (a tall outside cell meets a tall neighbour in one portal, not one per band).
    auto flush = [&](std::vector<Run>& runs, int side) {
      for (Run r : runs) {
        r.side = side;
        done.push_back(r);
      }
      runs.clear();
    };
    auto emit = [&]() {
      std::sort(done.begin(), done.end(), [](const Run& x, const Run& y) {
        return std::tie(x.side, x.d, x.s0, x.s1, x.sheet_opening, x.lo.z) < std::tie(y.side, y.d, y.s0, y.s1, y.sheet_opening, y.lo.z);
      });
      std::vector<Run> merged;
      for (const Run& r : done) {
        if (!merged.empty()) {
          Run& m = merged.back();
          if (m.side == r.side && m.d == r.d && m.sheet_opening == r.sheet_opening && std::fabs(m.s0 - r.s0) < 1e-9 &&
              std::fabs(m.s1 - r.s1) < 1e-9 && !r.lo.plane && std::fabs(m.hi - r.lo.z) < kZTol) {
            m.hi = r.hi;
            continue;
          }
        }
        merged.push_back(r);
      }
      for (const Run& r : merged) {
        const int side = r.side;
        if (r.s1 - r.s0 < kMinWidth) continue;
        Vec2 a = c.footprint[size_t(side)], e = c.footprint[(size_t(side) + 1) % nsides];
        Vec2 dir = (1.0 / length(e - a)) * (e - a);
        Vec2 p0 = a + r.s0 * dir, p1 = a + r.s1 * dir;
        const double lo0 = std::min(r.lo(p0), r.hi), lo1 = std::min(r.lo(p1), r.hi);
        if (!(r.hi > lo0 + kZTol) && !(r.hi > lo1 + kZTol)) continue;  // no height anywhere along it
        open[size_t(side)].push_back({r.s0, r.s1, r.lo, Level{r.hi, nullptr}});
        if (ci < r.d) {
          int opening = -1;
          PortalKind kind = kind_between(c, out.cells[size_t(r.d)], opening);
          if (r.sheet_opening >= 0) {  // an opening in a wall of no thickness
            const Region& reg = outline.regions[size_t(r.sheet_opening)];
            opening = opening_id(outline, reg.wall, reg.opening);
            OpeningKind ok = plan.walls[size_t(reg.wall)].openings[size_t(reg.opening)].kind;
            kind = ok == OpeningKind::Door ? PortalKind::Door : ok == OpeningKind::Window ? PortalKind::Window
                   : ok == OpeningKind::Hatch ? PortalKind::Hatch : PortalKind::Gap;
          }
          PortalId pid = add_portal(ci, r.d, band_polygon(p0, p1, lo0, lo1, r.hi, r.hi),
                                    c.faces[size_t(side)].plane.n, kind, opening);
          c.faces[size_t(side)].portals.push_back(pid);
          c.portals.push_back(pid);
          // The far cell's face: the side whose segment holds both ends of the portal.
          Cell& dc = out.cells[size_t(r.d)];
          size_t best = 0;
          double best_err = HUGE_VAL;
          for (size_t k = 0; k < dc.footprint.size(); ++k) {
            Vec2 fa = dc.footprint[k], fb = dc.footprint[(k + 1) % dc.footprint.size()];
            double err = std::max(distance_to_segment(p0, fa, fb), distance_to_segment(p1, fa, fb));
            if (err < best_err) best_err = err, best = k;
          }
          dc.faces[best].portals.push_back(pid);
          dc.portals.push_back(pid);
        }
      }
    };
    // The pieces of [s0, s1] along which one of the floors (levels) stays the highest.
    std::vector<double> breaks;
    for (size_t b = band_of[size_t(ci)]; b <= band_last[size_t(ci)]; ++b) {
    const Band& band = C.bands[b];
    const double zlo = std::max(c.z0, band.z0), zhi = std::min(c.z1, band.z1);
    int prev_side = -1;
    for (size_t k = 0; k < o.half_edges.size(); ++k) {
      const int32_t h = o.half_edges[k];
      const int side = o.side[k];
      if (side != prev_side && prev_side >= 0) flush(active, prev_side);
      prev_side = side;
      const Vec2 a = c.footprint[size_t(side)];
      const Vec2 e = c.footprint[(size_t(side) + 1) % nsides];
      const Vec2 dir = (1.0 / length(e - a)) * (e - a);
      const double s0 = dot(T.edge_from(h / 3, h % 3) - a, dir), s1 = dot(T.edge_to(h / 3, h % 3) - a, dir);
      const int u = T.nbr[size_t(h / 3)][size_t(h % 3)];
      // Heights at which the far side can be reached through this half-edge.
      Intervals reach{{zlo, zhi}};
      int sheet_wall = -1, sheet_opening = -1;
      if (band.kind == Band::Kind::Storey) {
        for_each_sheet_of_storey(outline, T, h, band.storey, [&](int32_t r) {
          reach = intersect(reach, outline.regions[size_t(r)].open);
          sheet_wall = outline.regions[size_t(r)].wall;
          if (outline.regions[size_t(r)].opening >= 0) sheet_opening = r;
        });
      }
      const std::vector<CellId> none;
      const std::vector<CellId>& far =
          u >= 0 && L.pieces[b].of[size_t(u)] >= 0 ? L.cells_of[b][size_t(L.pieces[b].of[size_t(u)])] : none;
      // Where a sloped floor, this cell's or a neighbour's, overtakes another floor or a
      // bound of the reach along the half-edge, the shared heights change how they are
      // bounded: the half-edge is walked in pieces between such points.
      breaks.assign({s0, s1});
      {
        std::vector<Level> floors{own_floor, {c.z1, nullptr}};
        for (CellId d : far) floors.push_back(floor_of(d)), floors.push_back({out.cells[size_t(d)].z1, nullptr});
        for (auto [lo, hi] : reach) floors.push_back({lo, nullptr}), floors.push_back({hi, nullptr});
        const Vec2 pa = a + s0 * dir, pb = a + s1 * dir;
        for (size_t x = 0; x < floors.size(); ++x)
          for (size_t y = x + 1; y < floors.size(); ++y) {
            if (!floors[x].plane && !floors[y].plane) continue;
            const double fa = floors[x](pa) - floors[y](pa), fb = floors[x](pb) - floors[y](pb);
            if ((fa > kZTol && fb < -kZTol) || (fa < -kZTol && fb > kZTol)) breaks.push_back(s0 + (s1 - s0) * fa / (fa - fb));
          }
        std::sort(breaks.begin(), breaks.end());
      }
      for (size_t piece = 0; piece + 1 < breaks.size(); ++piece) {
        const double t0 = breaks[piece], t1 = breaks[piece + 1];
        if (t1 - t0 <= 1e-12 && breaks.size() > 2) continue;
        const Vec2 mid = a + (0.5 * (t0 + t1)) * dir;
        next.clear();
        for (CellId d : far) {
          const Cell& dc = out.cells[size_t(d)];
          const Level dfloor = floor_of(d);
          for (auto [lo, hi] : intersect(reach, {{dc.z0, dc.z1}})) {
            // The floor here: the highest of the interval's bound and the sloped floors.
            Level floor{lo, nullptr};
            for (const Level& f : {own_floor, dfloor})
              if (f.plane && f(mid) > floor(mid)) floor = f;
            if (!(hi > floor(mid) + kZTol)) continue;
            auto same = std::find_if(active.begin(), active.end(), [&](const Run& r) {
              return r.d == d && r.lo.same(floor) && std::fabs(r.hi - hi) < kZTol && std::fabs(r.s1 - t0) < 1e-9 &&
                     r.sheet_opening == sheet_opening;
            });
            if (same != active.end()) {
              Run r = *same;
              r.s1 = t1;
              next.push_back(r);
              active.erase(same);
            } else {
              next.push_back({d, floor, hi, t0, t1, sheet_opening, -1});
            }
          }
        }
        // Runs that did not continue end here.
        flush(active, side);
        active.swap(next);
      }
      {
        MaterialId mat = -2;  // -2: nothing opaque across this half-edge
        const Vec2 ha = T.edge_from(h / 3, h % 3), hb = T.edge_to(h / 3, h % 3);
        if (u < 0) mat = plan.sky;
        else if (sheet_wall >= 0) mat = wall_material(plan, sheet_wall, ha, hb);
        else if (L.pieces[b].of[size_t(u)] < 0) mat = wall_material(plan, C.wall_of[b * size_t(n) + size_t(u)], ha, hb);
        if (mat != -2) {
          if (mat < 0 && c.kind == CellKind::Room && c.room < int(plan.rooms.size())) mat = plan.rooms[size_t(c.room)].walls;
          side_materials[size_t(side)][mat] += (zhi - zlo) * length(hb - ha);
          side_spans[size_t(side)].push_back({std::min(s0, s1), std::max(s0, s1), zhi - zlo, mat});
        }
      }
    }
    if (prev_side >= 0) flush(active, prev_side);
    }
    emit();

    // Opaque = the side from the cell's floor to its ceiling minus its portals, as convex
    // pieces (a sweep along s: between consecutive ends of portals, what no portal covers).
    for (size_t k = 0; k < nsides; ++k) {
      const Vec2 a = c.footprint[k], e = c.footprint[(k + 1) % nsides];
      const double len = length(e - a);
      const Vec2 dir = (1.0 / len) * (e - a);
      MaterialId side_material = -1;
      double most = 0;
      for (const auto& [m, area] : side_materials[k])
        if (area > most) most = area, side_material = m;
      std::vector<double> cuts{0, len};
      for (const Rect& r : open[k]) cuts.push_back(r.s0), cuts.push_back(r.s1);
      for (const Span& sp : side_spans[k])
        if (sp.material != side_material) cuts.push_back(std::clamp(sp.s0, 0.0, len)), cuts.push_back(std::clamp(sp.s1, 0.0, len));
      std::sort(cuts.begin(), cuts.end());
      // (A tall cell's side may have walls of several storeys behind one stretch: the one
      // that covers most of its height there.)
      auto material_at = [&](double s) {
        std::map<MaterialId, double> here;
        for (const Span& sp : side_spans[k])
          if (sp.s0 <= s && s <= sp.s1) here[sp.material] += sp.height;
        MaterialId m = side_material;
        double tallest = 0;
        for (const auto& [id, h] : here)
          if (h > tallest) tallest = h, m = id;
        return m;
      };
      std::vector<Rect> rects;
      const Level ceiling{c.z1, nullptr};
      for (size_t j = 0; j + 1 < cuts.size(); ++j) {
        double s0 = cuts[j], s1 = cuts[j + 1];
        if (s1 - s0 <= 1e-12) continue;
        const Vec2 pm = a + (0.5 * (s0 + s1)) * dir;
        std::vector<const Rect*> covering;
        for (const Rect& r : open[k])
          if (r.s0 < s0 + 0.5 * (s1 - s0) && s0 + 0.5 * (s1 - s0) < r.s1) covering.push_back(&r);
        std::sort(covering.begin(), covering.end(), [&](const Rect* x, const Rect* y) { return x->lo(pm) < y->lo(pm); });
        Level z = own_floor;
        std::vector<std::pair<Level, Level>> solid;
        for (const Rect* r : covering) {
          if (r->lo(pm) > z(pm) + kZTol) solid.push_back({z, r->lo});
          if (r->hi(pm) > z(pm)) z = r->hi;
        }
        if (c.z1 > z(pm) + kZTol) solid.push_back({z, ceiling});
        const MaterialId mat = material_at(0.5 * (s0 + s1));
        for (auto [lo, hi] : solid) {
          // Extend a piece of the previous s-interval between the same levels, of one material.
          auto prev = std::find_if(rects.begin(), rects.end(), [&](const Rect& r) {
            return std::fabs(r.s1 - s0) < 1e-12 && r.lo.identical(lo) && r.hi.identical(hi) && r.material == mat;
          });
          if (prev != rects.end()) prev->s1 = s1;
          else rects.push_back({s0, s1, lo, hi, mat});
        }
      }
      for (const Rect& r : rects) {
        Vec2 p0 = a + r.s0 * dir, p1 = a + r.s1 * dir;
        const double lo0 = height(ci, r.lo, p0), lo1 = height(ci, r.lo, p1);
        const double hi0 = std::max(lo0, height(ci, r.hi, p0)), hi1 = std::max(lo1, height(ci, r.hi, p1));
        if (!(hi0 > lo0 + kZTol) && !(hi1 > lo1 + kZTol)) continue;
        std::vector<Vec3> poly{at(p0, lo0)};
        if (hi0 > lo0 + kZTol) poly.push_back(at(p0, hi0));
        poly.push_back(at(p1, hi1));
        if (hi1 > lo1 + kZTol) poly.push_back(at(p1, lo1));
        c.faces[k].opaque.push_back({std::move(poly), r.material});
      }
    }
  }

  // --- 5d. horizontal interfaces: portals, floors and ceilings.
  auto floor_material = [&](const Cell& c, double z) {
    if (c.kind == CellKind::Room && c.room < int(plan.rooms.size())) return plan.rooms[size_t(c.room)].floor;
    if (c.kind == CellKind::Outside || c.kind == CellKind::Sky) return std::fabs(z) < kZTol ? plan.ground : plan.roof;
    return MaterialId(-1);
  };
  auto ceiling_material = [&](const Cell& c) {
    if (c.kind == CellKind::Room && c.room < int(plan.rooms.size())) return plan.rooms[size_t(c.room)].ceiling;
    return MaterialId(-1);
  };
  const size_t nb = C.bands.size();
  for (size_t b = 0; b <= nb; ++b) {
    // Interface between band b-1 (below) and band b (above); b = 0 is the box floor, b = nb its top.
    const double z = b < nb ? C.bands[b].z0 : C.bands[nb - 1].z1;
    std::vector<int32_t> label(size_t(n), -1);
    std::map<std::pair<CellId, CellId>, int32_t> pair_id;
    std::vector<std::pair<CellId, CellId>> pairs;
    for (int t = 0; t < n; ++t) {
      CellId below = kNoCell, above = kNoCell;
      if (b > 0) {
        int32_t p = L.pieces[b - 1].of[size_t(t)];
        if (p >= 0)
          for (CellId id : L.cells_of[b - 1][size_t(p)])
            if (std::fabs(out.cells[size_t(id)].z1 - z) < kZTol) below = id;
      }
      if (b < nb) {
        int32_t p = L.pieces[b].of[size_t(t)];
        if (p >= 0)
          for (CellId id : L.cells_of[b][size_t(p)])
            if (std::fabs(out.cells[size_t(id)].z0 - z) < kZTol && !L.floor_plane[size_t(id)]) above = id;
      }
      if (below == kNoCell && above == kNoCell) continue;
      auto [it, fresh] = pair_id.emplace(std::make_pair(below, above), int32_t(pairs.size()));
      if (fresh) pairs.push_back({below, above});
      label[size_t(t)] = it->second;
    }
    Pieces P = merge_convex(T, label, {});
    for (size_t p = 0; p < P.boundary.size(); ++p) {
      Outline2 o = footprint_of(T, P.boundary[p]);
      if (o.poly.size() < 3 || signed_area(o.poly) <= kMinArea) continue;
      auto [below, above] = pairs[size_t(P.label[p])];
      std::vector<Vec3> up, down;  // counter-clockwise seen from above / from below
      for (Vec2 v : o.poly) up.push_back(at(v, z));
      down.assign(up.rbegin(), up.rend());
      if (below != kNoCell && above != kNoCell) {
        const Cell &cb = out.cells[size_t(below)], &ca = out.cells[size_t(above)];
        PortalKind kind = (cb.kind == CellKind::Stairwell || ca.kind == CellKind::Stairwell) ? PortalKind::Stairwell
                          : (cb.kind == CellKind::Room && ca.kind == CellKind::Room && cb.room == ca.room)
                              ? PortalKind::Transparent
                              : PortalKind::Open;
        int opening = cb.kind == CellKind::Stairwell ? cb.opening : ca.kind == CellKind::Stairwell ? ca.opening : -1;
        PortalId pid = below < above ? add_portal(below, above, up, {0, 0, 1}, kind, opening)
                                     : add_portal(above, below, down, {0, 0, -1}, kind, opening);
        Cell& cbm = out.cells[size_t(below)];
        Cell& cam = out.cells[size_t(above)];
        cbm.faces.back().portals.push_back(pid);  // top face of the cell below
        cbm.portals.push_back(pid);
        cam.faces[cam.faces.size() - 2].portals.push_back(pid);  // bottom face of the cell above
        cam.portals.push_back(pid);
      } else if (below != kNoCell) {
        Cell& cb = out.cells[size_t(below)];
        cb.faces.back().opaque.push_back({down, b == nb ? plan.sky : ceiling_material(cb)});
      } else {
        Cell& ca = out.cells[size_t(above)];
        ca.faces[ca.faces.size() - 2].opaque.push_back({up, floor_material(ca, z)});
      }
    }
  }
  // Cells whose bottom or top lies inside their band (a doorway's sill and lintel, a
  // raised room floor, a lowered ceiling): wholly opaque there.
  for (size_t ci = 0; ci < out.cells.size(); ++ci) {
    Cell& c = out.cells[ci];
    const Band& band = C.bands[band_of[ci]];
    const bool room = c.kind == CellKind::Room && c.room >= 0 && c.room < int(plan.rooms.size());
    if (c.z0 > band.z0 + kZTol || L.floor_plane[ci])  // (a sloped floor is its wall's top)
      c.faces[c.faces.size() - 2].opaque.push_back({c.faces[c.faces.size() - 2].poly, room ? floor_material(c, c.z0) : -1});
    if (c.z1 < band.z1 - kZTol) c.faces.back().opaque.push_back({c.faces.back().poly, room ? ceiling_material(c) : -1});
  }

  // Portals on a side face in order along it, so a traversal can look up the few that a
  // mask can see on a long wall of doors (a corridor) instead of testing every one.
  for (Cell& c : out.cells)
    for (size_t k = 0; k < c.footprint.size(); ++k) {
      const Vec2 a = c.footprint[k], e = c.footprint[(k + 1) % c.footprint.size()];
      const Vec2 dir = (1.0 / length(e - a)) * (e - a);
      auto start = [&](PortalId p) {
        double s = HUGE_VAL;
        for (Vec3 v : out.portals[size_t(p)].poly) s = std::min(s, dot(Vec2{v.x, v.y} - a, dir));
        return s;
      };
      auto& ps = c.faces[k].portals;
      std::sort(ps.begin(), ps.end(), [&](PortalId x, PortalId y) { return start(x) < start(y); });
      double reach = -HUGE_VAL;  // the farthest end so far along the face
      for (PortalId p : ps) {
        double s0 = HUGE_VAL, s1 = -HUGE_VAL;
        for (Vec3 v : out.portals[size_t(p)].poly) {
          const double s = dot(Vec2{v.x, v.y} - a, dir);
          s0 = std::min(s0, s), s1 = std::max(s1, s);
        }
        if (s0 < reach - 1e-9) c.faces[k].portals_overlap = true;
        reach = std::max(reach, s1);
      }
    }

  // A cell over a sloped wall that rises to its ceiling (a gable's ridge) is a wedge: its
  // side there has no height, and is no face.
  for (size_t ci = 0; ci < out.cells.size(); ++ci) {
    if (!L.floor_plane[ci]) continue;
    auto& faces = out.cells[ci].faces;
    faces.erase(std::remove_if(faces.begin(), faces.end(),
                               [](const Face& f) { return f.poly.size() < 3 && f.portals.empty() && f.opaque.empty(); }),
                faces.end());
  }

  // Room floor areas.
  for (const Cell& c : out.cells)
    if (c.kind == CellKind::Room && c.room >= 0) {
      const Band& band = C.bands[band_of[size_t(&c - out.cells.data())]];
      if (band.kind == Band::Kind::Storey) out.rooms[size_t(c.room)].area += signed_area(c.footprint);
    }
  return L;
}

}  // namespace avenues::detail
