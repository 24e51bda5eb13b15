// Avenues — the cell complex's own operations: containment, point location, names.
#include "cells/cell_complex.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "plans/mesh.h"

namespace avenues {

const char* to_string(CellKind k) {
  switch (k) {
    case CellKind::Room: return "room";
    case CellKind::Doorway: return "doorway";
    case CellKind::Stairwell: return "stairwell";
    case CellKind::Outside: return "outside";
    case CellKind::Sky: return "sky";
  }
  return "?";
}

const char* to_string(PortalKind k) {
  switch (k) {
    case PortalKind::Transparent: return "transparent";
    case PortalKind::Door: return "door";
    case PortalKind::Window: return "window";
    case PortalKind::Hatch: return "hatch";
    case PortalKind::Gap: return "gap";
    case PortalKind::Stairwell: return "stairwell";
    case PortalKind::Open: return "open";
  }
  return "?";
}

const char* to_string(LineKind k) {
  switch (k) {
    case LineKind::Concave: return "concave";
    case LineKind::Convex: return "convex";
    case LineKind::Sheet: return "sheet";
  }
  return "?";
}

Box3 Cell::bounds() const {
  Box3 b;
  for (Vec2 p : footprint) {
    b.add({p.x, p.y, z0});
    b.add({p.x, p.y, z1});
  }
  return b;
}

namespace {
/// Closed containment of p in a convex counter-clockwise polygon, grown by tol.
bool in_convex(const std::vector<Vec2>& poly, Vec2 p, double tol) {
  const size_t m = poly.size();
  for (size_t k = 0; k < m; ++k) {
    Vec2 a = poly[k], b = poly[(k + 1) % m];
    Vec2 d = b - a;
    // Signed distance of p to the left of a->b.
    if (cross(d, p - a) < -tol * length(d)) return false;
  }
  return true;
}
}  // namespace

bool Cell::contains(Vec3 p, double tol) const {
  if (p.z < z0 - tol || p.z > z1 + tol) return false;
  if (!prism) {  // a general convex polyhedron: inside every face's plane
    for (const Face& f : faces)
      if (f.plane.eval(p) > tol) return false;
    return true;
  }
  return in_convex(footprint, {p.x, p.y}, tol);
}

Vec3 Cell::middle() const {
  Vec3 s{0, 0, 0};
  double k = 0;
  for (const Face& f : faces)
    for (Vec3 p : f.poly) s = s + p, k += 1;
  return (1.0 / k) * s;
}

double Cell::width() const {
  double width = HUGE_VAL;
  for (const Face& f : faces) {
    double depth = 0;
    for (const Face& g : faces)
      for (Vec3 v : g.poly) depth = std::max(depth, -f.plane.eval(v));
    width = std::min(width, depth);
  }
  return width;
}

double Cell::volume() const {
  if (prism) return signed_area(footprint) * (z1 - z0);
  // A general convex polyhedron: pyramids from one of its vertices to every face.
  const Vec3 r = faces.empty() || faces[0].poly.empty() ? Vec3{} : faces[0].poly[0];
  double v = 0;
  for (const Face& f : faces) {
    if (f.poly.size() < 3) continue;
    Vec3 n{0, 0, 0};
    for (size_t i = 0; i < f.poly.size(); ++i) n = n + cross(f.poly[i], f.poly[(i + 1) % f.poly.size()]);
    // poly is counter-clockwise from inside, so n points inwards: the height is r's side of the plane.
    v += length(n) / 2 * std::fabs(dot(f.plane.n, f.poly[0] - r)) / 3;
  }
  return v;
}

double total_volume(const CellComplex& c) {
  double v = 0;
  for (const Cell& cell : c.cells) v += cell.volume();
  return v;
}

void CellComplex::index_portals() { portal_table = lay_out_portals(*this); }

namespace {

/// The corners after corner 0 of `poly` spanning the most area with it (not simply the
/// first three, which may hold two a rounding apart): where the search reads a portal's
/// side from (PortalTable::Seen::spread).
uint32_t spread_of(const std::vector<Vec3>& poly) {
  uint32_t spread = 1;
  double most = -1;
  for (size_t k = 1; k + 1 < poly.size(); ++k) {
    const Vec3 n = cross(poly[k] - poly[0], poly[k + 1] - poly[0]);
    if (const double a = dot(n, n); a > most) most = a, spread = uint32_t(k);
  }
  return spread;
}

/// PortalTable::hulls for the face whose entries in t.seen run from `begin` to its end.
void lay_out_hulls(CellComplex::PortalTable& t, size_t begin) {
  using Seen = CellComplex::PortalTable::Seen;
  std::map<CellId, std::vector<size_t>> into;  // other cell -> its portals' entries
  for (size_t i = begin; i < t.seen.size(); ++i) into[t.seen[i].other].push_back(i);
  bool joins = false;
  for (const auto& [other, entries] : into) joins = joins || entries.size() > 1;
  if (!joins) return;
  for (const auto& [other, entries] : into) {
    const Seen& lead = t.seen[entries.front()];
    // The plane's normal into `other`, and the 2D axes that drop its largest component.
    const Vec3 n = lead.first ? lead.plane.n : -1.0 * lead.plane.n;
    const int drop = std::fabs(n.x) >= std::fabs(n.y) && std::fabs(n.x) >= std::fabs(n.z) ? 0
                     : std::fabs(n.y) >= std::fabs(n.z)                                  ? 1
                                                                                        : 2;
    auto uv = [&](Vec3 v) { return drop == 0 ? Vec2{v.y, v.z} : drop == 1 ? Vec2{v.z, v.x} : Vec2{v.x, v.y}; };
    std::vector<Vec3> points;
    PortalId least = lead.portal;
    for (size_t i : entries) {
      least = std::min(least, t.seen[i].portal);
      for (size_t k = 0; k < t.seen[i].corners; ++k) points.push_back(t.corners[size_t(t.seen[i].corner0) + k]);
    }
    // Their convex hull (core/geometry.h), counter-clockwise in (u, v), back in 3D: points
    // on a side are left out.
    std::map<std::pair<double, double>, Vec3> at;  // (u, v) -> the corner there
    std::vector<Vec2> flat;
    for (Vec3 q : points)
      if (const Vec2 f = uv(q); at.try_emplace({f.x, f.y}, q).second) flat.push_back(f);
    std::vector<Vec3> hull;
    for (Vec2 f : convex_hull(std::move(flat))) hull.push_back(at.at({f.x, f.y}));
    if (hull.size() < 3) {  // no area (rounding): the portals stay as they are, each its own
      for (size_t i : entries) t.hulls.push_back(t.seen[i]);
      continue;
    }
    // Counter-clockwise in (u, v) is anticlockwise about the dropped axis's positive
    // direction; the corners must turn about n, into `other`.
    const double axis = drop == 0 ? n.x : drop == 1 ? n.y : n.z;
    if (axis < 0) std::reverse(hull.begin(), hull.end());
    Seen s;
    s.plane = lead.first ? lead.plane : Plane{-1.0 * lead.plane.n, -lead.plane.d};
    s.portal = least;
    s.other = other;
    s.corner0 = int32_t(t.corners.size());
    s.corners = uint32_t(hull.size());
    s.spread = spread_of(hull);
    s.first = true;
    t.corners.insert(t.corners.end(), hull.begin(), hull.end());
    t.hulls.push_back(s);
  }
}

}  // namespace

CellComplex::PortalTable lay_out_portals(const CellComplex& c) {
  const auto& cells = c.cells;
  const auto& portals = c.portals;
  CellComplex::PortalTable t;
  size_t faces = 0, sides = 0;
  for (const Cell& cl : cells) {
    faces += cl.faces.size();
    for (const Face& f : cl.faces) sides += f.portals.size();
  }
  std::vector<int32_t> at(portals.size(), -1);  // per portal: its entry in the cell at hand
  t.listed.reserve(sides);
  t.cell_faces.reserve(cells.size() + 1);
  t.face_seen.reserve(faces + 1);
  t.seen.reserve(sides);
  for (CellId id = 0; id < CellId(cells.size()); ++id) {
    t.cell_faces.push_back(int32_t(t.face_seen.size()));
    const size_t first_seen = t.seen.size();
    for (const Face& f : cells[size_t(id)].faces) {
      t.face_seen.push_back(int32_t(t.seen.size()));
      t.face_hulls.push_back(int32_t(t.hulls.size()));
      for (PortalId pi : f.portals) {
        const Portal& p = portals[size_t(pi)];
        CellComplex::PortalTable::Seen s;
        s.plane = p.plane;
        s.portal = pi;
        s.other = p.other(id);
        s.corner0 = int32_t(t.corners.size());
        s.corners = uint32_t(p.poly.size());
        s.first = p.cell[0] == id;
        s.spread = spread_of(p.poly);
        t.corners.insert(t.corners.end(), p.poly.begin(), p.poly.end());
        at[size_t(pi)] = int32_t(t.seen.size());
        t.seen.push_back(s);
      }
      if (!cells[size_t(id)].prism) lay_out_hulls(t, size_t(t.face_seen.back()));
    }
    // The first of each face's portals into one cell, in the order of Cell::portals.
    const int32_t first_face = t.cell_faces.back();
    std::set<std::pair<CellId, size_t>> named;  // (other cell, face)
    for (PortalId pi : cells[size_t(id)].portals) {
      if (t.listed.size() >= t.seen.size() || pi < 0 || size_t(pi) >= at.size() || at[size_t(pi)] < 0) continue;
      const int32_t entry = at[size_t(pi)];
      const size_t face = size_t(std::upper_bound(t.face_seen.begin() + first_face, t.face_seen.end(), entry) -
                                 t.face_seen.begin()) - 1;
      if (named.insert({t.seen[size_t(entry)].other, face}).second) t.listed.push_back(entry);
    }
    t.listed.resize(t.seen.size(), -1);
    for (size_t i = first_seen; i < t.seen.size(); ++i) at[size_t(t.seen[i].portal)] = -1;
  }
  t.cell_faces.push_back(int32_t(t.face_seen.size()));
  t.face_seen.push_back(int32_t(t.seen.size()));
  t.face_hulls.push_back(int32_t(t.hulls.size()));
  t.portal_count = portals.size();
  return t;
}

void CellComplex::index_detail() {
  detail_start.assign(cells.size() + 1, 0);
  detail_boxes.clear();
  for (const Object& o : objects)
    if (o.cell >= 0 && size_t(o.cell) < cells.size() && o.model) ++detail_start[size_t(o.cell) + 1];
  for (size_t c = 0; c < cells.size(); ++c) detail_start[c + 1] += detail_start[c];
  detail_boxes.resize(size_t(detail_start.back()));
  std::vector<int32_t> at(detail_start.begin(), detail_start.end() - 1);
  for (size_t i = 0; i < objects.size(); ++i) {
    const Object& o = objects[i];
    if (!(o.cell >= 0 && size_t(o.cell) < cells.size() && o.model)) continue;
    DetailBox& d = detail_boxes[size_t(at[size_t(o.cell)]++)];
    d.object = int32_t(i);
    for (const Vec3& v : o.model->vertices) d.box.add(v);  // a detail model is in world space
  }
}

void CellComplex::index() {
  index_surfaces();
  index_portals();
  index_detail();
  // One uniform grid in plan over the far box; each grid square lists the cells whose
  // footprint's bounding box overlaps it (all heights: a few storeys per square).
  bands.assign(1, Band{});
  Band& g = bands[0];
  g.z0 = far_box.lo.z;
  g.z1 = far_box.hi.z;
  const double w = far_box.hi.x - far_box.lo.x, h = far_box.hi.y - far_box.lo.y;
  if (!(w > 0 && h > 0)) return;
  g.x0 = far_box.lo.x;
  g.y0 = far_box.lo.y;
  g.cell_size = std::max(std::sqrt(w * h / double(std::max<size_t>(cells.size(), 1))), 1e-3);
  g.nx = std::clamp(int(w / g.cell_size) + 1, 1, 2048);
  g.ny = std::clamp(int(h / g.cell_size) + 1, 1, 2048);
  g.cell_size = std::max(w / g.nx, h / g.ny) * (1 + 1e-9);
  std::vector<std::vector<CellId>> sq(size_t(g.nx) * size_t(g.ny));
  auto ix = [&](double x) { return std::clamp(int((x - g.x0) / g.cell_size), 0, g.nx - 1); };
  auto iy = [&](double y) { return std::clamp(int((y - g.y0) / g.cell_size), 0, g.ny - 1); };
  for (CellId c = 0; c < CellId(cells.size()); ++c) {
    Box3 b = cells[size_t(c)].bounds();
    for (int j = iy(b.lo.y); j <= iy(b.hi.y); ++j)
      for (int i = ix(b.lo.x); i <= ix(b.hi.x); ++i) sq[size_t(j) * size_t(g.nx) + size_t(i)].push_back(c);
  }
  g.start.assign(1, 0);
  g.items.clear();
  for (auto& s : sq) {
    g.items.insert(g.items.end(), s.begin(), s.end());
    g.start.push_back(int32_t(g.items.size()));
  }
}

Location CellComplex::locate(Vec3 p, CellId hint) const {
  Location loc;
  if (!far_box.contains(p)) return loc;
  auto in = [&](CellId c) -> Location {
    for (const ClosedSurface& s : detail_solids)
      if (s.holds(p)) return {Location::What::Solid, kNoCell, s.name()};
    return {Location::What::Cell, c, {}};
  };
  // Walk: the hint, then the cells one portal away (a moving eye rarely goes further).
  if (hint >= 0 && hint < CellId(cells.size())) {
    const Cell& h = cells[size_t(hint)];
    if (h.contains(p)) return in(hint);
    for (PortalId pi : h.portals) {
      CellId o = portals[size_t(pi)].other(hint);
      if (cells[size_t(o)].contains(p)) return in(o);
    }
  }
  if (!bands.empty() && bands[0].nx > 0) {
    const Band& g = bands[0];
    int i = std::clamp(int((p.x - g.x0) / g.cell_size), 0, g.nx - 1);
    int j = std::clamp(int((p.y - g.y0) / g.cell_size), 0, g.ny - 1);
    size_t s = size_t(j) * size_t(g.nx) + size_t(i);
    for (int32_t k = g.start[s]; k < g.start[s + 1]; ++k)
      if (cells[size_t(g.items[size_t(k)])].contains(p)) return in(g.items[size_t(k)]);
  }
  // Not in free space: say what it is inside.
  loc.what = Location::What::Solid;
  for (const SolidBox& s : solids)
    if (p.z >= s.z0 && p.z <= s.z1 && in_convex(s.quad, {p.x, p.y}, 0)) {
      loc.solid = s.what;
      return loc;
    }
  for (size_t k = 0; k < storeys.size(); ++k) {
    const Storey& st = storeys[k];
    if (p.z >= st.elevation + st.height && p.z <= st.elevation + st.height + st.slab) {
      loc.solid = "the slab above storey '" + st.name + "'";
      return loc;
    }
    if (p.z >= st.elevation && p.z <= st.elevation + st.height) {
      loc.solid = "a wall of storey '" + st.name + "'";
      return loc;
    }
  }
  loc.solid = p.z < 0 ? "the ground" : "solid";
  return loc;
}

CellId CellComplex::largest_cell_of(RoomId room) const {
  CellId best = kNoCell;
  for (CellId id = 0; id < CellId(cells.size()); ++id) {
    const Cell& cell = cells[size_t(id)];
    if (cell.kind == CellKind::Room && cell.room == room &&
        (best == kNoCell || signed_area(cell.footprint) > signed_area(cells[size_t(best)].footprint)))
      best = id;
  }
  return best;
}

Location CellComplex::locate(Vec3 p, Vec3 facing, CellId hint) const {
  const Location loc = locate(p, hint);
  const double l = length(facing);
  if (loc.what != Location::What::Cell || !(l > 0) || !std::isfinite(l)) return loc;
  constexpr double kAhead = 1e-6;  // [m] a step far below any plan's detail, and well above rounding
  const Vec3 ahead = p + (kAhead / l) * facing;
  if (cells[size_t(loc.cell)].contains(ahead)) return loc;
  const Location there = locate(ahead, loc.cell);
  if (there.what == Location::What::Cell && cells[size_t(there.cell)].contains(p)) return there;
  return loc;
}

std::vector<CellId> CellComplex::cells_holding(Vec3 p, double tol) const {
  std::vector<CellId> out;
  if (!far_box.contains(p) || bands.empty() || bands[0].nx <= 0) return out;
  const Band& g = bands[0];
  // The grid squares the point's tol-box meets (a cell touching p may be listed only in
  // the square beside p's own when p lies on a square's edge).
  const int i0 = std::clamp(int((p.x - tol - g.x0) / g.cell_size), 0, g.nx - 1);
  const int i1 = std::clamp(int((p.x + tol - g.x0) / g.cell_size), 0, g.nx - 1);
  const int j0 = std::clamp(int((p.y - tol - g.y0) / g.cell_size), 0, g.ny - 1);
  const int j1 = std::clamp(int((p.y + tol - g.y0) / g.cell_size), 0, g.ny - 1);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const size_t s = size_t(j) * size_t(g.nx) + size_t(i);
      for (int32_t k = g.start[s]; k < g.start[s + 1]; ++k)
        if (cells[size_t(g.items[size_t(k)])].contains(p, tol)) out.push_back(g.items[size_t(k)]);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void CellComplex::cells_near(const Box3& b, std::vector<CellId>& out) const {
  out.clear();
  if (bands.empty() || bands[0].nx <= 0) {
    for (CellId c = 0; c < CellId(cells.size()); ++c) out.push_back(c);
    return;
  }
  const Band& g = bands[0];
  auto square = [&](double v, double v0, int n) { return std::clamp(int((v - v0) / g.cell_size), 0, n - 1); };
  for (int j = square(b.lo.y, g.y0, g.ny); j <= square(b.hi.y, g.y0, g.ny); ++j)
    for (int i = square(b.lo.x, g.x0, g.nx); i <= square(b.hi.x, g.x0, g.nx); ++i) {
      const size_t s = size_t(j) * size_t(g.nx) + size_t(i);
      out.insert(out.end(), g.items.begin() + g.start[s], g.items.begin() + g.start[s + 1]);
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace avenues
