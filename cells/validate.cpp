// Avenues — cells_are_valid: an independent check of a cell complex (CGAL's habit of
// re-checking its output). It reads only the complex, never the passes' bookkeeping.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "cells/build_cells.h"
#include "core/check.h"

namespace avenues {

namespace {

/// Part of convex polygon `a` inside convex counter-clockwise polygon `b`.
std::vector<Vec2> clip(std::vector<Vec2> a, const std::vector<Vec2>& b) {
  for (size_t k = 0; k < b.size() && !a.empty(); ++k) {
    Vec2 o = b[k], d = b[(k + 1) % b.size()] - o;
    std::vector<Vec2> out;
    for (size_t i = 0; i < a.size(); ++i) {
      Vec2 p = a[i], q = a[(i + 1) % a.size()];
      double sp = cross(d, p - o), sq = cross(d, q - o);
      if (sp >= 0) out.push_back(p);
      if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
    }
    a.swap(out);
  }
  return a;
}

/// How far the turn cross(b − a, d − b) at b may go the wrong way in a convex polygon
/// whose vertices were each rounded by up to eps: moving the three vertices by eps moves
/// the cross product by up to about 2·eps·(|b − a| + |d − b|), so a short edge's direction
/// is known only to eps over its length, however long the edge beside it.
template <class V>
double turn_allowance(V a, V b, V d, double eps) {
  return 2 * eps * (length(b - a) + length(d - b));
}

/// Every vertex of a cell's faces (prism or not).
std::vector<Vec3> vertices_of(const Cell& cell) {
  std::vector<Vec3> v;
  for (const Face& f : cell.faces) v.insert(v.end(), f.poly.begin(), f.poly.end());
  return v;
}

/// What is wrong with a cell that is a general convex polyhedron (Cell::prism == false),
/// or "": at least four faces, each a planar convex polygon counter-clockwise seen from
/// inside with a unit outward normal; every vertex inside every face's plane (convex);
/// the faces closing up (their area vectors sum to zero); the outline from above and the
/// heights holding every vertex.
std::string polyhedron_problem(const Cell& cell, double eps) {
  std::ostringstream why;
  if (cell.faces.size() < 4) return (why << "has " << cell.faces.size() << " faces", why.str());
  const std::vector<Vec3> all = vertices_of(cell);
  Vec3 closure{0, 0, 0};
  double total = 0;
  for (size_t k = 0; k < cell.faces.size(); ++k) {
    const Face& f = cell.faces[k];
    if (std::fabs(length(f.plane.n) - 1) > 1e-9) return (why << "face " << k << " has no unit normal", why.str());
    const size_t m = f.poly.size();
    if (m < 3) return (why << "face " << k << " has " << m << " vertices", why.str());
    Vec3 s{0, 0, 0};
    for (size_t i = 0; i < m; ++i) {
      const Vec3 a = f.poly[i], b = f.poly[(i + 1) % m], d = f.poly[(i + 2) % m];
      if (std::fabs(f.plane.eval(a)) > eps) return (why << "face " << k << " is not planar", why.str());
      if (dot(cross(b - a, d - b), f.plane.n) > turn_allowance(a, b, d, eps))
        return (why << "face " << k << " is not convex (or not counter-clockwise seen from inside)", why.str());
      s = s + cross(a - all.front(), b - all.front());  // about a vertex of the cell: no large products
    }
    for (const OpaquePoly& o : f.opaque)
      for (Vec3 v : o.poly)
        if (std::fabs(f.plane.eval(v)) > eps) return (why << "an opaque piece of face " << k << " leaves its plane", why.str());
    closure = closure + s;
    total += length(s);
    for (Vec3 v : all)
      if (f.plane.eval(v) > eps) return (why << "is not convex: a vertex lies outside face " << k, why.str());
  }
  if (length(closure) > 1e-6 * std::max(total, 1.0)) return (why << "is not closed by its faces", why.str());
  double zlo = HUGE_VAL, zhi = -HUGE_VAL;
  for (Vec3 v : all) {
    zlo = std::min(zlo, v.z), zhi = std::max(zhi, v.z);
    const std::vector<Vec2>& fp = cell.footprint;
    for (size_t i = 0; i < fp.size(); ++i) {
      const Vec2 a = fp[i], b = fp[(i + 1) % fp.size()];
      if (cross(b - a, Vec2{v.x, v.y} - a) < -eps * length(b - a))
        return (why << "has a vertex outside its outline from above", why.str());
    }
  }
  if (std::fabs(zlo - cell.z0) > eps || std::fabs(zhi - cell.z1) > eps)
    return (why << "has heights " << cell.z0 << ".." << cell.z1 << " but its vertices span " << zlo << ".." << zhi, why.str());
  return {};
}

/// True when two convex cells share interior, deeper than `depth` [m] along every axis of
/// the separating-axis test (face normals of both, cross products of their edges).
bool polyhedra_overlap(const Cell& a, const Cell& b, double depth) {
  const std::vector<Vec3> va = vertices_of(a), vb = vertices_of(b);
  auto separated_along = [&](Vec3 axis) {
    const double l = length(axis);
    if (!(l > 1e-12)) return false;
    axis = (1.0 / l) * axis;
    double a0 = HUGE_VAL, a1 = -HUGE_VAL, b0 = HUGE_VAL, b1 = -HUGE_VAL;
    for (Vec3 v : va) a0 = std::min(a0, dot(axis, v)), a1 = std::max(a1, dot(axis, v));
    for (Vec3 v : vb) b0 = std::min(b0, dot(axis, v)), b1 = std::max(b1, dot(axis, v));
    return std::min(a1, b1) - std::max(a0, b0) <= depth;
  };
  for (const Cell* c : {&a, &b})
    for (const Face& f : c->faces)
      if (separated_along(f.plane.n)) return false;
  auto edges = [](const Cell& c) {
    std::vector<Vec3> e;
    for (const Face& f : c.faces)
      for (size_t i = 0; i < f.poly.size(); ++i) e.push_back(f.poly[(i + 1) % f.poly.size()] - f.poly[i]);
    return e;
  };
  const std::vector<Vec3> ea = edges(a), eb = edges(b);
  for (Vec3 u : ea)
    for (Vec3 w : eb)
      if (separated_along(cross(u, w))) return false;
  return true;
}

}  // namespace

std::string cells_are_valid(const CellComplex& c) {
  std::ostringstream why;
  const double scale = std::max({1.0, std::fabs(c.far_box.lo.x), std::fabs(c.far_box.hi.x),
                                 std::fabs(c.far_box.lo.y), std::fabs(c.far_box.hi.y)});
  const double eps = 1e-9 * scale;  // [m] tolerance on coordinates rounded once from exact ones
  auto fail = [&](auto&&... parts) {
    (why << ... << parts);
    return why.str();
  };

  // Cells: convex, counter-clockwise, of positive height, inside the far box.
  for (size_t i = 0; i < c.cells.size(); ++i) {
    const Cell& cell = c.cells[i];
    const auto& f = cell.footprint;
    if (f.size() < 3) return fail("cell ", i, " has a footprint of ", f.size(), " vertices");
    if (!(cell.z1 > cell.z0)) return fail("cell ", i, " has no height");
    if (signed_area(f) <= 0) return fail("cell ", i, " is not counter-clockwise");
    for (size_t k = 0; k < f.size(); ++k) {
      Vec2 a = f[k], b = f[(k + 1) % f.size()], d = f[(k + 2) % f.size()];
      if (cross(b - a, d - b) < -turn_allowance(a, b, d, eps)) return fail("cell ", i, " is not convex at vertex ", k + 1);
    }
    if (!c.far_box.contains(cell.bounds().lo, eps) || !c.far_box.contains(cell.bounds().hi, eps))
      return fail("cell ", i, " leaves the far box");
    if (!cell.prism) {
      const std::string problem = polyhedron_problem(cell, eps);
      if (!problem.empty()) return fail("cell ", i, " ", problem);
    } else if (cell.faces.size() != f.size() + 2) {
      return fail("cell ", i, " has ", cell.faces.size(), " faces");
    }
    // Every face is accounted for: opaque pieces plus portals cover it exactly.
    for (size_t k = 0; k < cell.faces.size(); ++k) {
      const Face& face = cell.faces[k];
      double covered = 0;
      for (const OpaquePoly& o : face.opaque) covered += polygon_area(o.poly);
      for (PortalId p : face.portals) covered += polygon_area(c.portals[size_t(p)].poly);
      double whole = polygon_area(face.poly);
      if (std::fabs(covered - whole) > 1e-6 * std::max(1.0, whole))
        return fail("face ", k, " of cell ", i, " has area ", whole, " but opaque + portals cover ", covered);
    }
  }

  // Portals: join two different cells, convex and planar, lying in a face of each.
  for (size_t p = 0; p < c.portals.size(); ++p) {
    const Portal& portal = c.portals[p];
    if (portal.cell[0] == portal.cell[1]) return fail("portal ", p, " joins cell ", portal.cell[0], " to itself");
    for (CellId id : portal.cell)
      if (id < 0 || id >= CellId(c.cells.size())) return fail("portal ", p, " names no cell");
    if (portal.poly.size() < 3 || polygon_area(portal.poly) <= 0) return fail("portal ", p, " is degenerate");
    for (Vec3 v : portal.poly)
      if (std::fabs(portal.plane.eval(v)) > eps) return fail("portal ", p, " is not planar");
    // Convex, and counter-clockwise about its normal.
    const size_t m = portal.poly.size();
    for (size_t k = 0; k < m; ++k) {
      Vec3 a = portal.poly[k], b = portal.poly[(k + 1) % m], d = portal.poly[(k + 2) % m];
      if (dot(cross(b - a, d - b), portal.plane.n) < -turn_allowance(a, b, d, eps))
        return fail("portal ", p, " is not convex (or not oriented by its normal)");
    }
    for (int s = 0; s < 2; ++s) {
      const Cell& cell = c.cells[size_t(portal.cell[s])];
      Vec3 n = s == 0 ? portal.plane.n : -1.0 * portal.plane.n;
      bool in_face = false;
      for (const Face& f : cell.faces) {
        if (dot(f.plane.n, n) < 1 - 1e-9) continue;
        bool on = true;
        for (Vec3 v : portal.poly) on = on && std::fabs(f.plane.eval(v)) <= eps && cell.contains(v, eps);
        if (on && std::find(f.portals.begin(), f.portals.end(), PortalId(p)) != f.portals.end()) in_face = true;
      }
      if (!in_face) return fail("portal ", p, " does not lie in a face of cell ", portal.cell[s]);
    }
  }

  // No two cells overlap: footprints of cells sharing heights meet in no area.
  std::vector<size_t> order(c.cells.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<Box3> box(c.cells.size());
  for (size_t i = 0; i < c.cells.size(); ++i) box[i] = c.cells[i].bounds();
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return box[a].lo.x < box[b].lo.x; });
  for (size_t x = 0; x < order.size(); ++x)
    for (size_t y = x + 1; y < order.size() && box[order[y]].lo.x < box[order[x]].hi.x - eps; ++y) {
      size_t i = order[x], j = order[y];
      const Box3 &a = box[i], &b = box[j];
      if (a.lo.y >= b.hi.y - eps || b.lo.y >= a.hi.y - eps) continue;
      if (a.lo.z >= b.hi.z - eps || b.lo.z >= a.hi.z - eps) continue;
      if (!c.cells[i].prism || !c.cells[j].prism) {  // general convex polyhedra
        if (polyhedra_overlap(c.cells[i], c.cells[j], 1e-7 * scale)) return fail("cells ", i, " and ", j, " overlap");
        continue;
      }
      double overlap = signed_area(clip(c.cells[i].footprint, c.cells[j].footprint));
      if (overlap > 1e-7 * std::max(1.0, scale)) return fail("cells ", i, " and ", j, " overlap by ", overlap, " m²");
    }

  // Real lines: each cell's parts lie on the cell's boundary.
  for (size_t i = 0; i < c.cells.size(); ++i)
    for (const CellLine& cl : c.cells[i].lines) {
      if (cl.line < 0 || cl.line >= LineId(c.lines.size()) || !(cl.t0 < cl.t1))
        return fail("cell ", i, " has a bad line part");
      const RealLine& l = c.lines[size_t(cl.line)];
      for (double t : {cl.t0, cl.t1}) {
        Vec3 q = l.a + t * (l.b - l.a);
        if (!c.cells[i].contains(q, 1e-6 * scale)) return fail("a line of cell ", i, " leaves the cell");
      }
    }
  return {};
}

void check_complex(const CellComplex& complex, const std::string& what) {
  if constexpr (kInvariantChecks) {
    const std::string why = cells_are_valid(complex);
    AVENUES_CHECK(why.empty(), "the cell complex of " + what + " is invalid: " + why);
  }
}

}  // namespace avenues
