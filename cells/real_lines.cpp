// Avenues — pass 6 of build_cells: the real lines of the architecture.
//
// Jones drew "all the lines in the cell which are not part of the boundary of an
// opening" and flagged artificial ones as dummies. Here a real line is an edge of the
// opaque surface that bounds free space where that surface is not flat: a crease
// (wall–floor, an inner corner), a convex edge (an outer corner, a reveal, the roof's
// rim), or an edge of a wall of no thickness. The building is cut into slices between
// every height at which anything changes (floors, ceilings, sills, heads); in each
// slice every triangle is solid or free. Then:
//  - at a vertex, a vertical line stands in a slice where the solid/free boundary
//    around it is not one straight line;
//  - on an edge, a horizontal line lies at a slice boundary where the four quarters
//    around it (left/right, below/above) are not a flat surface.
// Collinear pieces are chained into long lines, and each cell gets the parts of the
// lines on its boundary. Edges of transparent faces never appear: both sides are free.
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "cells/passes.h"

namespace avenues::detail {

namespace {

struct Slices {
  std::vector<double> z;  ///< breakpoints, ascending; slice j spans (z[j], z[j+1])
  std::vector<size_t> band;  ///< per slice
};

}  // namespace

void real_lines(const Outline& outline, const Triangulation& T, const Classes& C, const Layout& L,
                CellComplex& out) {
  const int n = T.size();
  Slices S;
  for (const Band& b : C.bands) S.z.push_back(b.z0), S.z.push_back(b.z1);
  for (const SpaceClass& c : C.classes)
    for (auto [lo, hi] : c.open) S.z.push_back(lo), S.z.push_back(hi);
  for (const Region& r : outline.regions)
    for (auto [lo, hi] : r.open) S.z.push_back(lo), S.z.push_back(hi);
  // A sloped floor (a wall's top) at every vertex under its cell (its corners, and points
  // on its sides where a neighbour's edge ends): where a vertical line there starts.
  for (size_t b = 0; b < L.pieces.size(); ++b)
    for (int t = 0; t < n; ++t) {
      const int32_t p = L.pieces[b].of[size_t(t)];
      if (p < 0) continue;
      for (CellId id : L.cells_of[b][size_t(p)])
        if (const auto& f = L.floor_plane[size_t(id)])
          for (int32_t v : T.tri[size_t(t)])
            S.z.push_back(std::clamp((*f)(T.vert[size_t(v)]), out.cells[size_t(id)].z0, out.cells[size_t(id)].z1));
    }
  std::sort(S.z.begin(), S.z.end());
  S.z.erase(std::unique(S.z.begin(), S.z.end(), [](double a, double b) { return std::fabs(a - b) < 1e-9; }), S.z.end());
  const int ns = int(S.z.size()) - 1;
  for (int j = 0; j < ns; ++j) {
    double zm = (S.z[size_t(j)] + S.z[size_t(j) + 1]) / 2;
    size_t b = 0;
    while (b + 1 < C.bands.size() && C.bands[b].z1 < zm) ++b;
    S.band.push_back(b);
  }
  auto mid = [&](int j) { return (S.z[size_t(j)] + S.z[size_t(j) + 1]) / 2; };

  // free_at[j][t]: the cell holding triangle t in slice j, or -1 (solid). Slices -1 and ns are solid.
  std::vector<std::vector<CellId>> free_at(size_t(ns), std::vector<CellId>(size_t(n), kNoCell));
  for (int j = 0; j < ns; ++j)
    for (int t = 0; t < n; ++t) free_at[size_t(j)][size_t(t)] = L.cell_at(out, S.band[size_t(j)], t, mid(j));
  // The cell free in slice j over triangle t at point p of it and height z in the slice
  // (or at its bottom, or top): a cell over a sloped wall is free only above the wall's
  // top at p. `at_or_above`: z itself counts when the top meets it (the slice just above
  // a height looked at from it).
  auto cell = [&](int j, int t, Vec2 p, double z, bool at_or_above) -> CellId {
    if (j < 0 || j >= ns || t < 0) return kNoCell;
    const CellId id = free_at[size_t(j)][size_t(t)];
    if (id == kNoCell || !L.floor_plane[size_t(id)]) return id;
    const double top = (*L.floor_plane[size_t(id)])(p);
    return (at_or_above ? z >= top : z > top) ? id : kNoCell;
  };
  // A wall of no thickness standing (opaque) on half-edge h in slice j.
  auto sheet = [&](int j, int32_t h) {
    if (j < 0 || j >= ns) return false;
    const Band& band = C.bands[S.band[size_t(j)]];
    if (band.kind != Band::Kind::Storey) return false;
    double zm = mid(j);
    for (int32_t k = T.sheet_start[size_t(h)]; k < T.sheet_start[size_t(h) + 1]; ++k) {
      const Region& r = outline.regions[size_t(T.sheet_items[size_t(k)])];
      if (r.storey != band.storey) continue;
      bool open = false;
      for (auto [lo, hi] : r.open) open |= lo < zm && zm < hi;
      if (!open) return true;
    }
    return false;
  };

  // Elementary pieces, each with the cells it bounds.
  struct Piece { Vec3 a, b; LineKind kind; std::vector<CellId> cells; };
  std::vector<Piece> pieces;
  auto add_cells = [](std::vector<CellId>& v, CellId c) {
    if (c != kNoCell && std::find(v.begin(), v.end(), c) == v.end()) v.push_back(c);
  };

  // --- horizontal pieces at every breakpoint, on every edge (once per edge).
  std::vector<double> cuts;
  for (int k = 0; k <= ns; ++k) {
    const double z = S.z[size_t(k)];
    for (int t = 0; t < n; ++t)
      for (int i = 0; i < 3; ++i) {
        const int u = T.nbr[size_t(t)][size_t(i)];
        if (u >= 0 && u < t) continue;
        const int32_t h = 3 * t + i;
        const Vec2 ea = T.edge_from(t, i), eb = T.edge_to(t, i);
        // An edge between points that rounded to one, or to points a rounding apart: no
        // line (a piece 1e-16 m long at a line's end has no length in the line's parameter).
        if (rounding_apart(ea, eb)) continue;
        // Where a sloped top beside the edge passes z along it, what lies just below and
        // just above z changes there: the edge is judged in parts between such points.
        cuts.assign({0.0, 1.0});
        for (int below = 0; below < 2; ++below)
          for (int tri : {t, u}) {
            if (tri < 0 || k - below < 0 || k - below >= ns) continue;
            const CellId id = free_at[size_t(k - below)][size_t(tri)];
            if (id == kNoCell || !L.floor_plane[size_t(id)]) continue;
            const double fa = (*L.floor_plane[size_t(id)])(ea) - z, fb = (*L.floor_plane[size_t(id)])(eb) - z;
            if ((fa > 1e-12 && fb < -1e-12) || (fa < -1e-12 && fb > 1e-12)) cuts.push_back(fa / (fa - fb));
          }
        std::sort(cuts.begin(), cuts.end());
        for (size_t part = 0; part + 1 < cuts.size(); ++part) {
          const Vec2 pa = ea + cuts[part] * (eb - ea), pb = ea + cuts[part + 1] * (eb - ea);
          if (cuts.size() > 2 && (cuts[part + 1] - cuts[part] < 1e-9 || rounding_apart(pa, pb))) continue;
          const Vec2 m = 0.5 * (pa + pb);
          // Just below z and just above it, at the part's middle.
          CellId lb = cell(k - 1, t, m, z, false), la = cell(k, t, m, z, true), rb = cell(k - 1, u, m, z, false),
                 ra = cell(k, u, m, z, true);
          bool Lb = lb == kNoCell, La = la == kNoCell, Rb = rb == kNoCell, Ra = ra == kNoCell;
          int solid = Lb + La + Rb + Ra;
          bool sb = !Lb && !Rb && sheet(k - 1, h), sa = !La && !Ra && sheet(k, h);
          bool line = false;
          LineKind kind = LineKind::Concave;
          if (solid == 1) line = true, kind = LineKind::Convex;
          else if (solid == 3) line = true, kind = LineKind::Concave;
          else if (solid == 2 && Lb == Ra && La == Rb) line = true, kind = LineKind::Convex;  // two edges meet
          else if (solid == 2 && Lb == Rb && La == Ra) line = sa || sb, kind = LineKind::Concave;  // a sheet on a floor
          else if (solid == 0) line = sa != sb, kind = LineKind::Sheet;  // top or bottom edge of a sheet
          if (!line) continue;
          Piece p{{pa.x, pa.y, z}, {pb.x, pb.y, z}, kind, {}};
          if (cuts.size() == 2) p.a = {ea.x, ea.y, z}, p.b = {eb.x, eb.y, z};  // (the edge's own ends, exactly)
          for (CellId c : {lb, la, rb, ra}) add_cells(p.cells, c);
          pieces.push_back(std::move(p));
        }
      }
  }

  // --- vertical pieces at every vertex, in every slice.
  // Incident (triangle, local index) lists per vertex.
  std::vector<int32_t> vstart(T.vert.size() + 1, 0), vitems(size_t(3 * n));
  for (int t = 0; t < n; ++t)
    for (int i = 0; i < 3; ++i) ++vstart[size_t(T.tri[size_t(t)][size_t(i)]) + 1];
  std::partial_sum(vstart.begin(), vstart.end(), vstart.begin());
  {
    std::vector<int32_t> fill(vstart.begin(), vstart.end() - 1);
    for (int t = 0; t < n; ++t)
      for (int i = 0; i < 3; ++i) vitems[size_t(fill[size_t(T.tri[size_t(t)][size_t(i)])]++)] = 3 * t + i;
  }
  // The triangles around each vertex in counter-clockwise order (a fan), starting, where
  // the fan is open (on the far box's rim), at the triangle with nothing clockwise of it.
  // Around v in triangle t (v at local index i), the next triangle counter-clockwise lies
  // across the edge v -> vertex i+2, i.e. opposite vertex i+1.
  std::vector<std::pair<int, int>> fan;
  auto build_fan = [&](size_t v) {
    fan.clear();
    int t0 = vitems[size_t(vstart[v])] / 3, i0 = vitems[size_t(vstart[v])] % 3;
    for (int32_t k = vstart[v]; k < vstart[v + 1]; ++k) {
      const int t = vitems[size_t(k)] / 3, i = vitems[size_t(k)] % 3;
      if (T.nbr[size_t(t)][size_t((i + 2) % 3)] < 0) t0 = t, i0 = i;  // nothing clockwise: start here
    }
    int t = t0, i = i0;
    for (int guard = vstart[v + 1] - vstart[v]; guard-- > 0;) {
      fan.push_back({t, i});
      const int u = T.nbr[size_t(t)][size_t((i + 1) % 3)];
      if (u < 0 || u == t0) break;
      const auto& tu = T.tri[size_t(u)];
      i = tu[0] == int32_t(v) ? 0 : tu[1] == int32_t(v) ? 1 : 2;
      t = u;
    }
  };
  for (size_t v = 0; v < T.vert.size(); ++v) {
    const Vec2 pv = T.vert[v];
    build_fan(v);
    const size_t m = fan.size();
    const bool open_fan = T.nbr[size_t(fan[0].first)][size_t((fan[0].second + 2) % 3)] < 0;
    auto start_dir = [&](size_t f) {  // v -> the fan triangle's first vertex after v
      return T.vert[size_t(T.tri[size_t(fan[f].first)][size_t((fan[f].second + 1) % 3)])] - pv;
    };
    auto end_dir = [&](size_t f) {
      return T.vert[size_t(T.tri[size_t(fan[f].first)][size_t((fan[f].second + 2) % 3)])] - pv;
    };
    for (int j = 0; j < ns; ++j) {
      // Boundary before fan triangle f: free and solid meet there, or a sheet stands there
      // between two free sides, or (open fan) the far box's rim.
      std::vector<CellId> here(m);
      for (size_t f = 0; f < m; ++f) here[f] = cell(j, fan[f].first, pv, mid(j), false);
      std::vector<uint8_t> boundary(m + 1, 0), sheet_before(m + 1, 0);
      for (size_t f = 0; f < m; ++f) {
        if (f == 0 && open_fan) { boundary[0] = here[0] != kNoCell; continue; }
        const CellId prev = here[(f + m - 1) % m];
        const int32_t h = 3 * fan[f].first + (fan[f].second + 2) % 3;  // edge v -> start vertex
        sheet_before[f] = prev != kNoCell && here[f] != kNoCell && sheet(j, h);
        boundary[f] = (prev == kNoCell) != (here[f] == kNoCell) || sheet_before[f];
      }
      if (open_fan) boundary[m] = here[m - 1] != kNoCell;
      // Each sector of free triangles between two boundaries sees a line at v unless its two
      // bounding edges run straight on (a flat wall, a sheet passing by): then it sees none.
      // This is decided per sector, so a sheet meeting a flat wall at v draws the corner on
      // its own side only.
      std::vector<CellId> cells;
      LineKind kind = LineKind::Concave;
      bool any = false;
      size_t first = m;
      for (size_t f = 0; f < m; ++f)
        if (boundary[f]) { first = f; break; }
      if (first == m) continue;  // no boundary around v: nothing stands here
      const size_t limit = open_fan ? m : m + first;
      for (size_t f = first; f < limit;) {
        const size_t fi = f % m;
        if (here[fi] == kNoCell) { ++f; continue; }
        // A sector starts at fi (a boundary precedes it) and runs while no boundary follows.
        std::vector<CellId> sector{here[fi]};
        bool sheet_edge = sheet_before[fi];
        size_t g = f + 1;
        while (g < (open_fan ? m : f + m) && !boundary[g % m] && here[g % m] != kNoCell) {
          if (std::find(sector.begin(), sector.end(), here[g % m]) == sector.end()) sector.push_back(here[g % m]);
          ++g;
        }
        const size_t last = (g - 1) % m;
        sheet_edge |= (open_fan ? (g == m ? false : bool(sheet_before[g % m])) : bool(sheet_before[g % m]));
        const Vec2 a = start_dir(fi), b = end_dir(last);
        const bool whole_turn = !open_fan && g - f == m;  // one boundary only: a sheet's end
        const bool flat = !whole_turn && orientation(pv + a, pv, pv + b) == 0 && dot(a, b) < 0;
        if (!flat) {
          any = true;
          for (CellId c : sector) add_cells(cells, c);
          const double turn = std::atan2(cross(a, b), dot(a, b));  // the free sector's angle
          kind = whole_turn || sheet_edge ? LineKind::Sheet : (turn > 0 && turn < std::acos(-1.0)) ? LineKind::Concave
                                                                                          : LineKind::Convex;
        }
        f = g;
      }
      if (!any || cells.empty()) continue;
      pieces.push_back({{pv.x, pv.y, S.z[size_t(j)]}, {pv.x, pv.y, S.z[size_t(j) + 1]}, kind, cells});
    }
  }

  // --- sloped pieces: the edges of a sloped wall's top along which it rises (the slice
  // pieces above take the level ones). Where a portal leads off the top to a cell of
  // another floor, the edge is the wall's convex edge, seen from there; where the side is
  // opaque, the top meets a face rising from it, a crease; where the cell beyond has the
  // same top, the top runs on and there is no line.
  for (size_t id = 0; id < out.cells.size(); ++id) {
    if (!L.floor_plane[id]) continue;
    const Slope& top = *L.floor_plane[id];
    const Cell& c = out.cells[id];
    auto top_at = [&](Vec2 p) { return std::clamp(top(p), c.z0, c.z1); };  // as extrude made the floor
    const size_t m = c.footprint.size();
    for (size_t k = 0; k < m; ++k) {
      const Vec2 a = c.footprint[k], b = c.footprint[(k + 1) % m];
      const double za = top_at(a), zb = top_at(b);
      if (std::fabs(za - zb) <= 1e-9 || (za >= c.z1 - 1e-9 && zb >= c.z1 - 1e-9)) continue;
      const double len = length(b - a);
      const Vec2 dir = (1.0 / len) * (b - a);
      // The side's face: the upright face whose plane passes nearest both ends of the edge
      // (a sliver's two long sides are nearly one plane; its own is exact to a rounding).
      const Face* side = nullptr;
      double nearest = 1e-9;
      for (const Face& f : c.faces) {
        if (std::fabs(f.plane.n.z) >= 1e-12) continue;
        const double off = std::max(std::fabs(f.plane.eval({a.x, a.y, 0})), std::fabs(f.plane.eval({b.x, b.y, 0})));
        if (off <= nearest) nearest = off, side = &f;
      }
      if (!side) continue;
      // The portals of this side that reach down to the top: their spans along it.
      struct Span { double s0, s1; CellId beyond; };
      std::vector<Span> spans;
      for (PortalId pid : side->portals) {
        const Portal& p = out.portals[size_t(pid)];
        // Its span, and whether its bottom is the top at both ends of it (a portal over a
        // sloped top has it for a bottom all along, or none of it).
        double s0 = HUGE_VAL, s1 = -HUGE_VAL;
        for (Vec3 v : p.poly) {
          const double sv = dot(Vec2{v.x, v.y} - a, dir);
          s0 = std::min(s0, sv), s1 = std::max(s1, sv);
        }
        bool low = s1 > s0;
        for (double end : {s0, s1}) {
          double bottom = HUGE_VAL;
          for (Vec3 v : p.poly)
            if (std::fabs(dot(Vec2{v.x, v.y} - a, dir) - end) <= 1e-9) bottom = std::min(bottom, v.z);
          const Vec2 q = a + end * dir;
          low = low && std::fabs(bottom - top_at(q)) <= 1e-9;
        }
        if (low) spans.push_back({std::max(0.0, s0), std::min(len, s1), p.other(CellId(id))});
      }
      std::sort(spans.begin(), spans.end(), [](const Span& x, const Span& y) { return x.s0 < y.s0; });
      auto add = [&](double s0, double s1, LineKind kind, CellId beyond) {
        if (s1 - s0 <= 1e-9) return;
        const Vec2 p0 = a + s0 * dir, p1 = a + s1 * dir;
        Piece p{{p0.x, p0.y, top_at(p0)}, {p1.x, p1.y, top_at(p1)}, kind, {}};
        add_cells(p.cells, CellId(id));
        add_cells(p.cells, beyond);
        pieces.push_back(std::move(p));
      };
      double s = 0;
      for (const Span& sp : spans) {
        add(s, sp.s0, LineKind::Concave, kNoCell);
        const auto& beyond = L.floor_plane[size_t(sp.beyond)];
        if (!(beyond && *beyond == top)) add(std::max(s, sp.s0), sp.s1, LineKind::Convex, sp.beyond);
        s = std::max(s, sp.s1);
      }
      add(s, len, LineKind::Concave, kNoCell);
    }
  }

  // --- chain collinear touching pieces of one kind into lines (union-find on shared ends).
  std::vector<int32_t> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int32_t x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  };
  {
    // Index piece ends by (point, unit direction) so collinear continuations meet.
    std::map<std::tuple<double, double, double>, std::vector<int32_t>> at_point;
    for (size_t p = 0; p < pieces.size(); ++p) {
      at_point[{pieces[p].a.x, pieces[p].a.y, pieces[p].a.z}].push_back(int32_t(p));
      at_point[{pieces[p].b.x, pieces[p].b.y, pieces[p].b.z}].push_back(int32_t(p));
    }
    for (auto& [pt, ids] : at_point) {
      Vec3 here{std::get<0>(pt), std::get<1>(pt), std::get<2>(pt)};
      for (size_t x = 0; x < ids.size(); ++x)
        for (size_t y = x + 1; y < ids.size(); ++y) {
          const Piece &P = pieces[size_t(ids[x])], &Q = pieces[size_t(ids[y])];
          if (P.kind != Q.kind) continue;
          Vec3 dp = (P.a == here ? P.b : P.a) - here, dq = (Q.a == here ? Q.b : Q.a) - here;
          // Opposite directions, exactly collinear: for vertical pieces trivially; for
          // horizontal ones (same z) by the exact planar orientation; for sloped ones (a
          // wall's top) within a rounding.
          const bool vertical = dp.x == 0 && dp.y == 0, sloped = dp.z != 0 && !vertical;
          bool collinear = sloped ? length(cross(dp, dq)) <= 1e-12 * length(dp) * length(dq)
                           : dp.z != 0 ? (dq.z != 0 && dp.x == 0 && dq.x == 0 && dp.y == 0 && dq.y == 0)
                                       : (dq.z == 0 && orientation({here.x + dp.x, here.y + dp.y}, {here.x, here.y},
                                                                   {here.x + dq.x, here.y + dq.y}) == 0);
          if (collinear && dot(dp, dq) < 0) parent[size_t(find(ids[x]))] = find(ids[y]);
        }
    }
  }
  // Each chain becomes one RealLine from its extreme ends.
  std::map<int32_t, LineId> line_of_root;
  for (size_t p = 0; p < pieces.size(); ++p) {
    int32_t r = find(int32_t(p));
    auto [it, fresh] = line_of_root.emplace(r, LineId(out.lines.size()));
    if (fresh) out.lines.push_back({pieces[p].a, pieces[p].b, pieces[p].kind});
    RealLine& l = out.lines[size_t(it->second)];
    // Grow the line along its direction to cover this piece.
    Vec3 d = l.b - l.a;
    for (Vec3 q : {pieces[p].a, pieces[p].b}) {
      double t = dot(q - l.a, d) / dot(d, d);
      if (t < 0) l.a = q, d = l.b - l.a;
      else if (t > 1) l.b = q, d = l.b - l.a;
    }
  }
  // Per cell: the parameter ranges of each line it bounds, merged where they touch.
  std::vector<std::vector<CellLine>> per_cell(out.cells.size());
  for (size_t p = 0; p < pieces.size(); ++p) {
    LineId id = line_of_root.at(find(int32_t(p)));
    const RealLine& l = out.lines[size_t(id)];
    Vec3 d = l.b - l.a;
    double t0 = dot(pieces[p].a - l.a, d) / dot(d, d), t1 = dot(pieces[p].b - l.a, d) / dot(d, d);
    if (t0 > t1) std::swap(t0, t1);
    for (CellId c : pieces[p].cells) per_cell[size_t(c)].push_back({id, std::clamp(t0, 0.0, 1.0), std::clamp(t1, 0.0, 1.0)});
  }
  for (size_t c = 0; c < per_cell.size(); ++c) {
    auto& v = per_cell[c];
    std::sort(v.begin(), v.end(), [](const CellLine& x, const CellLine& y) {
      return x.line != y.line ? x.line < y.line : x.t0 < y.t0;
    });
    for (const CellLine& cl : v) {
      auto& lines = out.cells[c].lines;
      if (!lines.empty() && lines.back().line == cl.line && cl.t0 <= lines.back().t1 + 1e-12)
        lines.back().t1 = std::max(lines.back().t1, cl.t1);
      else
        lines.push_back(cl);
    }
  }
}

}  // namespace avenues::detail
