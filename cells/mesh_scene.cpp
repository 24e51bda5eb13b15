// Avenues — meshes as whole scenes (see mesh_scene.h): free space as exact Nef polyhedra,
// cut into convex cells by CGAL::convex_decomposition_3.
//
// The pipeline, each stage timed into CellComplex::timings:
//   solids    — each connected component becomes a closed solid: as it is when it is a
//               closed, consistently oriented, self-intersection-free triangle mesh;
//               otherwise repaired (convex hull, or a thin plate when it lies flat) with a
//               warning. Each becomes a Nef polyhedron; their union is taken.
//   free      — the far box minus that union (regularised);
//   decompose — CGAL::convex_decomposition_3 inserts walls until every marked volume is convex;
//   cells     — each bounded marked volume is a cell. Its halffacets, grouped by plane, are
//               its faces; a halffacet whose other side is another cell is part of the portal
//               between them, every other one is opaque (a solid, or the far box). Exact to
//               the end: each face is the exact convex hull of its vertices, each portal the
//               hull of its halffacets (the meeting of two convex faces is convex), the opaque
//               rest the face minus its portals, cut into convex pieces; then rounded to
//               double once;
//   lines     — the solids' feature edges, assigned to the cells whose boundary holds them.
// This is the only file that includes CGAL's Nef machinery; nothing leaves it but
// Avenues' own structs.
#include "cells/mesh_scene.h"

#include "cells/build_cells.h"
#include "cells/free_regions.h"
#include "core/angles.h"
#include "cells/solid_insides.h"
#include "cells/soup_bsp.h"
#include "cells/soup_detail.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_nary_union_3.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_decomposition_3.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace avenues {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = K::FT;
using EPoint = K::Point_3;
using EPoint2 = K::Point_2;
using EPlane = K::Plane_3;
using Nef = CGAL::Nef_polyhedron_3<K>;
using SurfaceMesh = CGAL::Surface_mesh<EPoint>;

Vec3 to_vec(const EPoint& p) {
  return {CGAL::to_double(CGAL::exact(p.x())), CGAL::to_double(CGAL::exact(p.y())),
          CGAL::to_double(CGAL::exact(p.z()))};
}

// --- solids --------------------------------------------------------------------------

/// A closed solid, triangles counter-clockwise seen from outside, exact and rounded.
struct Solid {
  std::string name;                       ///< for warnings and point location
  std::vector<EPoint> p;                  ///< exact vertices
  std::vector<Vec3> v;                    ///< the same, rounded
  std::vector<std::array<int, 3>> tris;
  std::vector<int> polygon_of;            ///< per triangle: its polygon (no line between triangles of one)
};

Vec3 tri_normal(const std::vector<Vec3>& v, const std::array<int, 3>& t) {
  return cross(v[size_t(t[1])] - v[size_t(t[0])], v[size_t(t[2])] - v[size_t(t[0])]);
}

/// Surface mesh of a solid; false when its triangles do not make a manifold surface.
bool to_surface_mesh(const Solid& s, SurfaceMesh& sm) {
  std::vector<SurfaceMesh::Vertex_index> vi;
  for (const EPoint& p : s.p) vi.push_back(sm.add_vertex(p));
  for (const auto& t : s.tris) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return false;
    if (sm.add_face(vi[size_t(t[0])], vi[size_t(t[1])], vi[size_t(t[2])]) == SurfaceMesh::null_face()) return false;
  }
  return true;
}

/// The solid as read from a closed, triangulated surface mesh (a convex hull): one
/// polygon per triangle, coplanar neighbours are told apart by their normals later.
Solid from_surface_mesh(const SurfaceMesh& sm, std::string name) {
  Solid s;
  s.name = std::move(name);
  std::map<SurfaceMesh::Vertex_index, int> index;
  for (auto v : sm.vertices()) {
    index[v] = int(s.p.size());
    s.p.push_back(sm.point(v));
    s.v.push_back(to_vec(sm.point(v)));
  }
  for (auto f : sm.faces()) {
    std::vector<int> ids;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) ids.push_back(index[v]);
    for (size_t k = 1; k + 1 < ids.size(); ++k) {
      s.tris.push_back({ids[0], ids[k], ids[k + 1]});
      s.polygon_of.push_back(int(s.polygon_of.size()));
    }
  }
  return s;
}

/// Convex hull of the points (at least four, not coplanar).
Solid hull_solid(const std::vector<Vec3>& pts, std::string name) {
  std::vector<EPoint> ep;
  for (Vec3 q : pts) ep.emplace_back(q.x, q.y, q.z);
  SurfaceMesh sm;
  CGAL::convex_hull_3(ep.begin(), ep.end(), sm);
  return from_surface_mesh(sm, std::move(name));
}

/// Monotone chain over exact 2D points: indices of the convex hull, counter-clockwise,
/// without collinear or repeated points.
std::vector<size_t> hull2(const std::vector<EPoint2>& p) {
  std::vector<size_t> idx(p.size());
  std::iota(idx.begin(), idx.end(), size_t(0));
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return CGAL::compare_xy(p[a], p[b]) == CGAL::SMALLER; });
  idx.erase(std::unique(idx.begin(), idx.end(), [&](size_t a, size_t b) { return p[a] == p[b]; }), idx.end());
  if (idx.size() < 3) return idx;
  std::vector<size_t> h(2 * idx.size());
  size_t k = 0;
  for (size_t i = 0; i < idx.size(); ++i) {  // lower chain
    while (k >= 2 && CGAL::orientation(p[h[k - 2]], p[h[k - 1]], p[idx[i]]) != CGAL::LEFT_TURN) --k;
    h[k++] = idx[i];
  }
  for (size_t i = idx.size() - 1, lo = k + 1; i-- > 0;) {  // upper chain
    while (k >= lo && CGAL::orientation(p[h[k - 2]], p[h[k - 1]], p[idx[i]]) != CGAL::LEFT_TURN) --k;
    h[k++] = idx[i];
  }
  h.resize(k - 1);
  return h;
}

/// The axis a plane with normal (a, b, c) is projected along (its largest component),
/// and the two kept, in cyclic order so that counter-clockwise in 2D is counter-clockwise
/// about +axis in 3D.
int dominant_axis(const FT& a, const FT& b, const FT& c) {
  const FT aa = CGAL::abs(a), ab = CGAL::abs(b), ac = CGAL::abs(c);
  if (aa >= ab && aa >= ac) return 0;
  return ab >= ac ? 1 : 2;
}
FT coord(const EPoint& p, int i) { return i == 0 ? p.x() : i == 1 ? p.y() : p.z(); }
EPoint2 project(const EPoint& p, int axis) { return {coord(p, (axis + 1) % 3), coord(p, (axis + 2) % 3)}; }

/// A component lying flat becomes a plate `thickness` thick about its mid-plane: its
/// outline (the exact hull of its points projected along the dominant axis) lifted
/// exactly onto two parallel planes, so every face is exactly planar.
Solid plate_solid(const std::vector<Vec3>& pts, Vec3 n, double mid_d, double thickness, std::string name) {
  const FT a(n.x), b(n.y), c(n.z);
  const int k = dominant_axis(a, b, c);
  const FT nk = k == 0 ? a : k == 1 ? b : c;
  const FT nu = k == 0 ? b : k == 1 ? c : a, nv = k == 0 ? c : k == 1 ? a : b;
  std::vector<EPoint2> q;
  for (Vec3 p : pts) q.push_back(project(EPoint(p.x, p.y, p.z), k));
  std::vector<size_t> h = hull2(q);
  if (nk < 0) std::reverse(h.begin(), h.end());  // counter-clockwise about +n
  auto lift = [&](const EPoint2& uv, const FT& d) {
    FT w = -(nu * uv.x() + nv * uv.y() + d) / nk;
    FT xyz[3];
    xyz[k] = w, xyz[(k + 1) % 3] = uv.x(), xyz[(k + 2) % 3] = uv.y();
    return EPoint(xyz[0], xyz[1], xyz[2]);
  };
  // n·p + d = 0 with |n| = 1: the top plane is t/2 along +n from the mid-plane.
  const FT d_top = FT(mid_d) - FT(thickness / 2), d_bottom = FT(mid_d) + FT(thickness / 2);
  Solid s;
  s.name = std::move(name);
  const int m = int(h.size());
  for (size_t i : h) s.p.push_back(lift(q[i], d_top));
  for (size_t i : h) s.p.push_back(lift(q[i], d_bottom));
  for (const EPoint& p : s.p) s.v.push_back(to_vec(p));
  int poly = 0;
  for (int i = 1; i + 1 < m; ++i) s.tris.push_back({0, i, i + 1}), s.polygon_of.push_back(poly);  // top
  ++poly;
  for (int i = 1; i + 1 < m; ++i) s.tris.push_back({m, m + i + 1, m + i}), s.polygon_of.push_back(poly);  // bottom
  ++poly;
  for (int i = 0; i < m; ++i, ++poly) {  // sides: bottom_i, bottom_i+1, top_i+1, top_i
    const int j = (i + 1) % m;
    s.tris.push_back({m + i, m + j, j}), s.polygon_of.push_back(poly);
    s.tris.push_back({m + i, j, i}), s.polygon_of.push_back(poly);
  }
  return s;
}

/// Makes a closed solid of one component, repaired if need be; a solid with no triangles
/// when there is nothing to keep. Each repair or drop is one line in `warnings`.
Solid solid_of(const Mesh& m, const std::string& name, double sheet_thickness, std::vector<std::string>& warnings) {
  Solid none;
  // Distinct points, their extent and how flat they lie.
  std::vector<Vec3> pts = m.vertices;
  Box3 box;
  for (Vec3 p : pts) box.add(p);
  const double ext = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
  Vec3 p0 = pts[0], p1 = p0, p2 = p0;
  for (Vec3 p : pts)
    if (length(p - p0) > length(p1 - p0)) p1 = p;
  double best = 0;
  for (Vec3 p : pts) {
    double d = length(cross(p1 - p0, p - p0));
    if (d > best) best = d, p2 = p;
  }
  const double tiny = 1e-12 * std::max(ext, 1.0);
  if (!(length(p1 - p0) > tiny) || !(best / length(p1 - p0) > tiny)) {
    warnings.push_back(name + " has no area (its points lie on a line): dropped");
    return none;
  }
  Vec3 n = cross(p1 - p0, p2 - p0);
  n = (1.0 / length(n)) * n;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (Vec3 p : pts) lo = std::min(lo, dot(n, p - p0)), hi = std::max(hi, dot(n, p - p0));
  const bool flat = hi - lo <= sheet_thickness;
  const double mid_d = -(dot(n, p0) + (lo + hi) / 2);

  // Closed and consistently oriented: every directed edge once, its reverse once.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) directed[{t[size_t(k)], t[size_t((k + 1) % 3)]}]++;
  int boundary = 0;
  bool consistent = true;
  for (const auto& [e, count] : directed) {
    auto r = directed.find({e.second, e.first});
    const int back = r == directed.end() ? 0 : r->second;
    if (back == 0) ++boundary;
    if (count != 1 || back > 1) consistent = false;
  }
  double volume = 0;
  for (const auto& t : m.triangles)
    volume += dot(m.vertices[size_t(t[0])] - p0, cross(m.vertices[size_t(t[1])] - p0, m.vertices[size_t(t[2])] - p0)) / 6;

  const std::string polys = " (" + std::to_string(m.polygon_of.empty() ? m.triangles.size() : size_t(m.polygon_of.back() + 1)) + " polygons)";
  auto as_plate = [&](const std::string& why) {
    char t[32];
    std::snprintf(t, sizeof t, "%g", sheet_thickness);
    warnings.push_back(name + polys + " " + why + " and lies flat: kept as a sheet, a plate " + t +
                       " m thick with both sides opaque");
    return plate_solid(pts, n, mid_d, sheet_thickness, name);
  };
  auto as_hull = [&](const std::string& why) {
    warnings.push_back(name + polys + " " + why + ": closed by its convex hull");
    return hull_solid(pts, name);
  };
  if (boundary > 0) {
    const std::string why = "is not closed (" + std::to_string(boundary) + " boundary edges)";
    return flat ? as_plate(why) : as_hull(why);
  }
  if (!consistent) return flat ? as_plate("is not consistently oriented") : as_hull("is not consistently oriented");
  if (!(std::fabs(volume) > 1e-9 * ext * ext * ext))
    return flat ? as_plate("encloses no volume") : as_hull("encloses no volume");

  Solid s;
  s.name = name;
  for (Vec3 p : m.vertices) s.p.emplace_back(p.x, p.y, p.z), s.v.push_back(p);
  s.tris = m.triangles;
  s.polygon_of = m.polygon_of;
  if (s.polygon_of.size() != s.tris.size()) {
    s.polygon_of.resize(s.tris.size());
    std::iota(s.polygon_of.begin(), s.polygon_of.end(), 0);
  }
  if (volume < 0) {
    warnings.push_back(name + polys + " is inside out: turned");
    for (auto& t : s.tris) std::swap(t[1], t[2]);
  }
  SurfaceMesh sm;
  if (!to_surface_mesh(s, sm)) return as_hull("is not a manifold surface");
  if (CGAL::Polygon_mesh_processing::does_self_intersect(sm)) return as_hull("intersects itself");
  return s;
}

// --- exact faces -----------------------------------------------------------------------

/// An exact convex polygon in a face's 2D projection, counter-clockwise.
using Poly2 = std::vector<EPoint2>;

FT area2(const Poly2& p) {
  FT a = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    const EPoint2 &u = p[i], &w = p[(i + 1) % p.size()];
    a += u.x() * w.y() - u.y() * w.x();
  }
  return a;
}

/// The part of convex `poly` on the left of (or on) the line a→b.
Poly2 clip_left(const Poly2& poly, const EPoint2& a, const EPoint2& b) {
  Poly2 out;
  auto side = [&](const EPoint2& p) { return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x()); };
  for (size_t i = 0; i < poly.size(); ++i) {
    const EPoint2 &p = poly[i], &q = poly[(i + 1) % poly.size()];
    const FT sp = side(p), sq = side(q);
    if (sp >= 0) out.push_back(p);
    if ((sp > 0 && sq < 0) || (sp < 0 && sq > 0)) {
      const FT t = sp / (sp - sq);
      out.emplace_back(p.x() + t * (q.x() - p.x()), p.y() + t * (q.y() - p.y()));
    }
  }
  // Drop repeated and collinear vertices.
  for (bool changed = true; changed && out.size() >= 3;) {
    changed = false;
    for (size_t i = 0; i < out.size() && out.size() >= 3; ++i) {
      const EPoint2 &u = out[(i + out.size() - 1) % out.size()], &w = out[(i + 1) % out.size()];
      if (out[i] == w || CGAL::orientation(u, out[i], w) == CGAL::COLLINEAR) {
        out.erase(out.begin() + long(i));
        changed = true;
      }
    }
  }
  if (out.size() < 3) out.clear();
  return out;
}

/// Convex pieces of `pieces` minus convex `hole` (both counter-clockwise).
std::vector<Poly2> subtract(const std::vector<Poly2>& pieces, const Poly2& hole) {
  std::vector<Poly2> out;
  for (const Poly2& piece : pieces) {
    // Separated by a line of the hole's: untouched.
    bool apart = false;
    for (size_t e = 0; e < hole.size() && !apart; ++e) {
      const EPoint2 &a = hole[e], &b = hole[(e + 1) % hole.size()];
      apart = std::all_of(piece.begin(), piece.end(), [&](const EPoint2& p) { return CGAL::orientation(a, b, p) != CGAL::LEFT_TURN; });
    }
    if (apart) {
      out.push_back(piece);
      continue;
    }
    Poly2 rest = piece;
    for (size_t e = 0; e < hole.size() && !rest.empty(); ++e) {
      const EPoint2 &a = hole[e], &b = hole[(e + 1) % hole.size()];
      Poly2 outside = clip_left(rest, b, a);
      if (!outside.empty() && area2(outside) > 0) out.push_back(std::move(outside));
      rest = clip_left(rest, a, b);
    }
  }
  return out;
}

/// Canonical key of an oriented plane: coefficients scaled by 1/|largest normal component|.
using PlaneKey = std::array<FT, 4>;
struct PlaneLess {
  bool operator()(const PlaneKey& x, const PlaneKey& y) const {
    for (int i = 0; i < 4; ++i) {
      if (x[size_t(i)] < y[size_t(i)]) return true;
      if (y[size_t(i)] < x[size_t(i)]) return false;
    }
    return false;
  }
};
PlaneKey key_of(const EPlane& h) {
  const int k = dominant_axis(h.a(), h.b(), h.c());
  const FT s = CGAL::abs(k == 0 ? h.a() : k == 1 ? h.b() : h.c());
  return {h.a() / s, h.b() / s, h.c() / s, h.d() / s};
}

struct FacetCollector {
  std::vector<Nef::Halffacet_const_handle>* out;
  void visit(Nef::Vertex_const_handle) {}
  void visit(Nef::Halfedge_const_handle) {}
  void visit(Nef::Halffacet_const_handle f) { out->push_back(f); }
  void visit(Nef::SHalfedge_const_handle) {}
  void visit(Nef::SHalfloop_const_handle) {}
  void visit(Nef::SFace_const_handle) {}
};

/// One face of a cell being built: its halffacets, by the cell on their other side.
struct FaceBuild {
  EPlane plane;                                     ///< outward
  std::vector<Nef::Vertex_const_handle> all;        ///< every vertex of its halffacets
  std::map<CellId, std::vector<Nef::Vertex_const_handle>> toward;  ///< portal vertices per neighbour
};

/// The part of convex polygon p inside convex polygon q seen along w (q projected along w
/// on to p's plane): p cut (core's cut_polygon) by the plane through each edge of q that
/// holds w. Empty when nothing of area is left.
std::vector<Vec3> clip_along(std::vector<Vec3> p, const std::vector<Vec3>& q, Vec3 w) {
  const double turn = dot(polygon_normal(q), w) >= 0 ? 1 : -1;  // q counter-clockwise about w: inside on the left
  for (size_t k = 0; k < q.size() && p.size() >= 3; ++k) {
    const Vec3 a = q[k], left = turn * cross(w, q[(k + 1) % q.size()] - a);
    p = cut_polygon(p, [&](Vec3 x) { return dot(left, x - a); });
  }
  return p.size() >= 3 ? p : std::vector<Vec3>{};
}

/// p turned counter-clockwise about n (its corners' order reversed if it turns the other way).
std::vector<Vec3> turned_about(std::vector<Vec3> p, Vec3 n) {
  if (dot(polygon_normal(p), n) < 0) std::reverse(p.begin(), p.end());
  return p;
}

/// Rays crossed a free sliver from one kept neighbour into another: where the sliver's
/// two large faces lie back to back (turned apart within 1e-10, each a rounding from the
/// other) and hold only portals to kept cells and opaque pieces, each portal P of one face
/// and each piece Q of the other are joined over P ∩ Q (Q projected on P's plane): a portal
/// between the two neighbours, or an opaque piece of P's cell in Q's material. Those
/// portals are then taken off the sliver, so remove_cells does not close them. The join is
/// as exact as the rounding that made the sliver: a point moves across it by its width,
/// under the tolerance cells_are_valid allows. Returns how many portals it made.
size_t join_across_slivers(CellComplex& out, const std::vector<bool>& sliver, double thin) {
  size_t made = 0;
  std::vector<bool> handled(out.portals.size(), false);  // taken off their sliver already
  for (size_t s = 0; s < out.cells.size(); ++s) {
    if (!sliver[s]) continue;
    const Cell& cell = out.cells[s];
    for (size_t fa = 0; fa < cell.faces.size(); ++fa)
      for (size_t fb = fa + 1; fb < cell.faces.size(); ++fb) {
        const Face &A = cell.faces[fa], &B = cell.faces[fb];
        if (dot(A.plane.n, B.plane.n) > -(1 - 1e-10)) continue;
        // Each face within the tolerance of the other's plane, and only portals to kept
        // cells beside opaque pieces.
        bool usable = true;
        for (Vec3 p : A.poly) usable = usable && std::fabs(B.plane.eval(p)) <= 0.9 * thin;
        for (Vec3 p : B.poly) usable = usable && std::fabs(A.plane.eval(p)) <= 0.9 * thin;
        for (const Face* f : {&A, &B})
          for (PortalId p : f->portals)
            usable = usable && !handled[size_t(p)] && !sliver[size_t(out.portals[size_t(p)].other(CellId(s)))];
        if (!usable || (A.portals.empty() && B.portals.empty())) continue;
        // Which portals leave the sliver here, with the neighbour and its face holding them.
        struct Side {
          PortalId portal;
          CellId cell;
          size_t face;
        };
        auto sides = [&](const Face& f) {
          std::vector<Side> v;
          for (PortalId p : f.portals) {
            const CellId o = out.portals[size_t(p)].other(CellId(s));
            const Cell& oc = out.cells[size_t(o)];
            for (size_t k = 0; k < oc.faces.size(); ++k)
              if (std::find(oc.faces[k].portals.begin(), oc.faces[k].portals.end(), p) != oc.faces[k].portals.end())
                v.push_back({p, o, k});
          }
          return v;
        };
        const std::vector<Side> sa = sides(A), sb = sides(B);
        if (sa.size() != A.portals.size() || sb.size() != B.portals.size()) continue;
        // Face A of the sliver is turned towards the cells of sa (its outward normal points
        // into them), so from them the way across is −A's normal, into B's cells.
        std::vector<Portal> portals;
        std::vector<std::vector<size_t>> portal_of_a(sa.size()), portal_of_b(sb.size());
        std::vector<std::vector<OpaquePoly>> opaque_a(sa.size()), opaque_b(sb.size());
        const double tiny = thin * thin;
        // The way across from sa's cells is −A's normal: a new portal turns counter-
        // clockwise about it (its normal into cell[1]), an opaque piece of sa's cell about
        // A's normal (seen from inside that cell); the same for sb's cells with B.
        for (size_t i = 0; i < sa.size(); ++i) {
          const std::vector<Vec3>& pa = out.portals[size_t(sa[i].portal)].poly;
          for (size_t j = 0; j < sb.size(); ++j) {
            if (sb[j].cell == sa[i].cell) continue;
            std::vector<Vec3> x = clip_along(pa, out.portals[size_t(sb[j].portal)].poly, A.plane.n);
            if (!(polygon_area(x) > tiny)) continue;
            Portal q;
            q.cell[0] = sa[i].cell, q.cell[1] = sb[j].cell;
            q.poly = turned_about(std::move(x), -1.0 * A.plane.n);
            q.plane = out.cells[size_t(sa[i].cell)].faces[sa[i].face].plane;  // outward from cell[0]: into cell[1]
            portal_of_a[i].push_back(portals.size());
            portal_of_b[j].push_back(portals.size());
            portals.push_back(std::move(q));
          }
          for (const OpaquePoly& o : B.opaque) {  // turned into the sliver: towards sa's cells
            std::vector<Vec3> x = clip_along(pa, o.poly, A.plane.n);
            if (polygon_area(x) > tiny) opaque_a[i].push_back({turned_about(std::move(x), A.plane.n), o.material});
          }
        }
        for (size_t j = 0; j < sb.size(); ++j) {
          const std::vector<Vec3>& pb = out.portals[size_t(sb[j].portal)].poly;
          for (const OpaquePoly& o : A.opaque) {
            std::vector<Vec3> x = clip_along(pb, o.poly, B.plane.n);
            if (polygon_area(x) > tiny) opaque_b[j].push_back({turned_about(std::move(x), B.plane.n), o.material});
          }
        }
        // Only where the pieces cover each portal they replace (the two faces' extents
        // alike): else the sliver is left to remove_cells.
        auto covered = [&](const Portal& p, const std::vector<size_t>& joins, const std::vector<OpaquePoly>& pieces) {
          double a = 0;
          for (size_t k : joins) a += polygon_area(portals[k].poly);
          for (const OpaquePoly& o : pieces) a += polygon_area(o.poly);
          return std::fabs(a - polygon_area(p.poly)) <= 1e-9 * std::max(1.0, polygon_area(p.poly));
        };
        bool all = true;
        for (size_t i = 0; i < sa.size(); ++i) all = all && covered(out.portals[size_t(sa[i].portal)], portal_of_a[i], opaque_a[i]);
        for (size_t j = 0; j < sb.size(); ++j) all = all && covered(out.portals[size_t(sb[j].portal)], portal_of_b[j], opaque_b[j]);
        if (!all) continue;
        // In place of each portal into the sliver: its joins and opaque pieces.
        const PortalId first = PortalId(out.portals.size());
        for (Portal& q : portals) out.portals.push_back(std::move(q));
        auto replace = [&](const Side& side, const std::vector<size_t>& joins, std::vector<OpaquePoly>& pieces) {
          Face& f = out.cells[size_t(side.cell)].faces[side.face];
          f.portals.erase(std::find(f.portals.begin(), f.portals.end(), side.portal));
          for (size_t k : joins) f.portals.push_back(first + PortalId(k));
          for (OpaquePoly& o : pieces) f.opaque.push_back(std::move(o));
        };
        for (size_t i = 0; i < sa.size(); ++i) replace(sa[i], portal_of_a[i], opaque_a[i]), handled[size_t(sa[i].portal)] = true;
        for (size_t j = 0; j < sb.size(); ++j) replace(sb[j], portal_of_b[j], opaque_b[j]), handled[size_t(sb[j].portal)] = true;
        made += portals.size();
      }
  }
  return made;
}

/// The material a cell dropped as a sliver showed through a face of outward normal n of
/// its neighbour: that of the largest opaque piece on the sliver's far side (its face
/// turned most nearly along n), or none (-1) where that side is open too.
MaterialId material_beyond(const Cell& dropped, Vec3 n) {
  const Face* far = nullptr;
  for (const Face& g : dropped.faces)
    if (!far || dot(g.plane.n, n) > dot(far->plane.n, n)) far = &g;
  MaterialId m = -1;
  double most = 0;
  if (far && dot(far->plane.n, n) > 0.5)
    for (const OpaquePoly& o : far->opaque)
      if (const double a = polygon_area(o.poly); a > most) most = a, m = o.material;
  return m;
}

}  // namespace

/// Cells that rounding to double leaves without a shape: thinner than `1e-9 · scale`
/// (the tolerance cells_are_valid allows coordinates rounded once) across some face, or
/// with no outline from above. Where shallow solids cross (the ripple torus) the exact
/// decomposition leaves a few such slivers, nanometres across; a soup's nearly coplanar
/// faces leave many, some between free cells. They are dropped: their neighbours joined
/// across them where they can be (join_across_slivers), the other portals into them
/// opaque pieces of their neighbours' faces in the material seen through them
/// (material_beyond); one warning counts them.
void drop_slivers(CellComplex& out) {
  const Box3& fb = out.far_box;
  const double scale = fb.magnitude();
  const double thin = 1e-9 * scale;
  // A face rounded to fewer than three corners (the thin end of a wedge of a cell, a
  // rounding wide: the duplex's triangles written out as an OBJ left one 3.7 m long)
  // bounds nothing; the faces beside it close the cell.
  for (Cell& cell : out.cells)
    cell.faces.erase(std::remove_if(cell.faces.begin(), cell.faces.end(),
                                    [](const Face& f) { return f.poly.size() < 3 && f.portals.empty(); }),
                     cell.faces.end());
  std::vector<bool> sliver(out.cells.size(), false);
  size_t dropped = 0;
  double thinnest = HUGE_VAL;
  for (size_t i = 0; i < out.cells.size(); ++i) {
    const Cell& cell = out.cells[i];
    const double width = cell.width();
    sliver[i] = cell.faces.size() < 4 || cell.footprint.size() < 3 || !(width > thin) ||
                !(signed_area(cell.footprint) > thin * thin) || !(cell.z1 > cell.z0);
    if (sliver[i]) thinnest = std::min(thinnest, width), ++dropped;
  }
  if (dropped == 0) return;
  const size_t joined = join_across_slivers(out, sliver, thin);
  // What is closed: the portals left between kept cells and slivers (their area says how
  // much surface the drop made where there was none).
  double closed = 0;
  for (size_t i = 0; i < out.cells.size(); ++i) {
    if (sliver[i]) continue;
    for (const Face& f : out.cells[i].faces)
      for (PortalId p : f.portals)
        if (sliver[size_t(out.portals[size_t(p)].other(CellId(i)))]) closed += polygon_area(out.portals[size_t(p)].poly);
  }
  remove_cells(out, sliver);
  char what[480];
  std::snprintf(what, sizeof what,
                "%zu slivers of free space thinner than %.3g m (the thinnest %.3g m), left by rounding the exact cells "
                "to double, were dropped; %zu portals join the cells on their two sides, and the other portals into "
                "them (%.3g m² in all) became opaque, in the material seen through them",
                dropped, thin, std::max(thinnest, 0.0), joined, closed);
  out.warnings.push_back(what);
}

void remove_cells(CellComplex& out, const std::vector<bool>& drop) {
  std::vector<CellId> new_id(out.cells.size(), kNoCell);
  CellId kept = 0;
  for (size_t i = 0; i < out.cells.size(); ++i)
    if (!drop[i]) new_id[i] = kept++;
  if (kept == CellId(out.cells.size())) return;
  std::vector<PortalId> new_portal(out.portals.size(), -1);
  std::vector<Portal> portals;
  for (size_t p = 0; p < out.portals.size(); ++p) {
    Portal q = out.portals[p];
    if (new_id[size_t(q.cell[0])] == kNoCell || new_id[size_t(q.cell[1])] == kNoCell) continue;
    q.cell[0] = new_id[size_t(q.cell[0])], q.cell[1] = new_id[size_t(q.cell[1])];
    new_portal[p] = PortalId(portals.size());
    portals.push_back(std::move(q));
  }
  std::vector<Cell> cells;
  for (size_t i = 0; i < out.cells.size(); ++i) {
    if (new_id[i] == kNoCell) continue;
    Cell cell = std::move(out.cells[i]);
    cell.portals.clear();
    for (Face& f : cell.faces) {
      std::vector<PortalId> keep;
      for (PortalId p : f.portals) {
        if (new_portal[size_t(p)] >= 0) {
          keep.push_back(new_portal[size_t(p)]);
          continue;
        }
        // Into a dropped cell: opaque now, counter-clockwise seen from this cell, with the
        // material of what was seen through it (the dropped cell's surface on its far side).
        const Portal& q = out.portals[size_t(p)];
        std::vector<Vec3> poly = q.poly;
        if (q.cell[0] == CellId(i)) std::reverse(poly.begin(), poly.end());
        f.opaque.push_back({std::move(poly), material_beyond(out.cells[size_t(q.other(CellId(i)))], f.plane.n)});
      }
      f.portals = keep;
      cell.portals.insert(cell.portals.end(), keep.begin(), keep.end());
    }
    cells.push_back(std::move(cell));
  }
  out.cells = std::move(cells);
  out.portals = std::move(portals);
}

namespace {

/// The cells, faces and portals of the decomposed free space (see the file comment).
void build_cells_of(const Nef& free, CellComplex& out) {
  std::map<const void*, CellId> id_of;
  std::vector<Nef::Volume_const_handle> volumes;
  {
    auto v = free.volumes_begin();
    ++v;  // the outer volume
    for (; v != free.volumes_end(); ++v)
      if (v->mark()) {
        id_of[&*v] = CellId(volumes.size());
        volumes.push_back(v);
      }
  }
  std::map<const void*, Vec3> rounded;  // each exact vertex converted once
  auto vec = [&](Nef::Vertex_const_handle h) {
    auto [it, fresh] = rounded.try_emplace(&*h);
    if (fresh) it->second = to_vec(h->point());
    return it->second;
  };
  std::map<std::pair<CellId, CellId>, PortalId> portal_of;
  out.cells.resize(volumes.size());

  for (CellId id = 0; id < CellId(volumes.size()); ++id) {
    const Nef::Volume_const_handle vol = volumes[size_t(id)];
    std::vector<Nef::Halffacet_const_handle> facets;
    FacetCollector collect{&facets};
    for (auto sh = vol->shells_begin(); sh != vol->shells_end(); ++sh)
      free.visit_shell_objects(Nef::SFace_const_handle(sh), collect);
    // The cell's vertices (for orienting planes, the footprint and heights).
    std::vector<Nef::Vertex_const_handle> verts;
    std::map<const void*, bool> seen;
    auto vertices_of = [&](Nef::Halffacet_const_handle f) {
      std::vector<Nef::Vertex_const_handle> vs;
      for (auto c = f->facet_cycles_begin(); c != f->facet_cycles_end(); ++c) {
        if (!c.is_shalfedge()) continue;
        Nef::SHalfedge_around_facet_const_circulator s(c), end(s);
        CGAL_For_all(s, end) vs.push_back(s->source()->source());
      }
      return vs;
    };
    for (auto f : facets)
      for (auto h : vertices_of(f))
        if (!seen[&*h]) seen[&*h] = true, verts.push_back(h);

    std::map<PlaneKey, FaceBuild, PlaneLess> faces;
    for (auto f : facets) {
      if (f->incident_volume() != vol) f = f->twin();
      EPlane h = f->plane();
      // Outward: every vertex of the (convex) cell on the negative side or on it.
      for (auto v : verts) {
        CGAL::Oriented_side s = h.oriented_side(v->point());
        if (s == CGAL::ON_ORIENTED_BOUNDARY) continue;
        if (s == CGAL::ON_POSITIVE_SIDE) h = h.opposite();
        break;
      }
      FaceBuild& fb = faces.try_emplace(key_of(h), FaceBuild{h, {}, {}}).first->second;
      std::vector<Nef::Vertex_const_handle> vs = vertices_of(f);
      fb.all.insert(fb.all.end(), vs.begin(), vs.end());
      Nef::Volume_const_handle other = f->twin()->incident_volume();
      auto o = id_of.find(&*other);
      if (o != id_of.end() && o->second != id && f->mark()) {
        auto& t = fb.toward[o->second];
        t.insert(t.end(), vs.begin(), vs.end());
      }
    }

    Cell& cell = out.cells[size_t(id)];
    cell.kind = CellKind::Outside;
    cell.prism = false;
    {  // Outline from above and heights.
      std::vector<EPoint2> xy;
      for (auto v : verts) xy.emplace_back(v->point().x(), v->point().y());
      for (size_t i : hull2(xy)) cell.footprint.push_back({vec(verts[i]).x, vec(verts[i]).y});
      cell.z0 = HUGE_VAL, cell.z1 = -HUGE_VAL;
      for (auto v : verts) cell.z0 = std::min(cell.z0, vec(v).z), cell.z1 = std::max(cell.z1, vec(v).z);
    }
    for (auto& [key, fb] : faces) {
      const EPlane& h = fb.plane;
      const int k = dominant_axis(h.a(), h.b(), h.c());
      const bool flip = (k == 0 ? h.a() : k == 1 ? h.b() : h.c()) > 0;  // 2D ccw is about +axis
      // The projected hull of some vertices, as indices into them, counter-clockwise
      // about +n when `about_n` else about -n.
      auto hull_of = [&](const std::vector<Nef::Vertex_const_handle>& vs, bool about_n, Poly2* exact) {
        std::vector<EPoint2> q;
        for (auto v : vs) q.push_back(project(v->point(), k));
        std::vector<size_t> hh = hull2(q);
        Poly2 ccw2;
        for (size_t i : hh) ccw2.push_back(q[i]);
        if (exact) *exact = ccw2;
        if (flip != about_n) std::reverse(hh.begin(), hh.end());
        std::vector<Vec3> poly;
        for (size_t i : hh) poly.push_back(vec(vs[i]));
        return poly;
      };
      Face face;
      Poly2 whole;
      face.poly = hull_of(fb.all, false, &whole);
      if (face.poly.size() < 3) continue;
      Vec3 n{CGAL::to_double(h.a()), CGAL::to_double(h.b()), CGAL::to_double(h.c())};
      n = (1.0 / length(n)) * n;
      double d = 0;
      for (Vec3 p : face.poly) d -= dot(n, p);
      face.plane = {n, d / double(face.poly.size())};
      std::vector<Poly2> opaque{whole};
      for (auto& [other, vs] : fb.toward) {
        Poly2 hole;
        std::vector<Vec3> poly = hull_of(vs, true, &hole);
        if (poly.size() < 3) continue;
        opaque = subtract(opaque, hole);
        PortalId pid;
        const auto pair = std::minmax(id, other);
        auto it = portal_of.find(pair);
        if (it != portal_of.end()) {
          pid = it->second;
        } else {
          Portal p;
          p.cell[0] = id, p.cell[1] = other;
          p.poly = std::move(poly);
          p.plane = face.plane;
          p.kind = PortalKind::Open;
          pid = PortalId(out.portals.size());
          out.portals.push_back(std::move(p));
          portal_of[pair] = pid;
        }
        face.portals.push_back(pid);
        cell.portals.push_back(pid);
      }
      // The opaque rest, lifted from the projection back onto the plane.
      const FT nk = k == 0 ? h.a() : k == 1 ? h.b() : h.c();
      const FT nu = k == 0 ? h.b() : k == 1 ? h.c() : h.a(), nv = k == 0 ? h.c() : k == 1 ? h.a() : h.b();
      for (const Poly2& piece : opaque) {
        OpaquePoly op;
        for (const EPoint2& uv : piece) {
          double xyz[3];
          xyz[k] = CGAL::to_double(CGAL::exact(-(nu * uv.x() + nv * uv.y() + h.d()) / nk));
          xyz[(k + 1) % 3] = CGAL::to_double(CGAL::exact(uv.x()));
          xyz[(k + 2) % 3] = CGAL::to_double(CGAL::exact(uv.y()));
          op.poly.push_back({xyz[0], xyz[1], xyz[2]});
        }
        if (flip) std::reverse(op.poly.begin(), op.poly.end());  // counter-clockwise about -n
        face.opaque.push_back(std::move(op));
      }
      cell.faces.push_back(std::move(face));
    }
    // Faces in no particular order (Cell::prism == false); those with the most portals
    // last, where a traversal that scans side faces by footprint index never looks.
    std::stable_sort(cell.faces.begin(), cell.faces.end(),
                     [](const Face& a, const Face& b) { return a.portals.size() < b.portals.size(); });
  }
  drop_slivers(out);
}

/// The feature edges of triangles (v, tris, polygon_of): between triangles of different
/// polygons whose planes differ; with `open_edges`, also the edges of one triangle only
/// (the border of a sheet).
std::vector<RealLine> feature_edges(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& tris,
                                    const std::vector<int>& polygon_of, bool open_edges) {
  std::map<std::pair<int, int>, std::vector<size_t>> edge;
  for (size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      int a = tris[t][size_t(k)], b = tris[t][size_t((k + 1) % 3)];
      edge[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  auto poly = [&](size_t t) { return t < polygon_of.size() ? polygon_of[t] : int(t); };
  std::vector<RealLine> lines;
  for (const auto& [e, ts] : edge) {
    const Vec3 a = v[size_t(e.first)], b = v[size_t(e.second)];
    if (ts.size() == 1) {
      if (open_edges && length(tri_normal(v, tris[ts[0]])) > 0) lines.push_back({a, b, LineKind::Sheet});
      continue;
    }
    if (ts.size() != 2 || poly(ts[0]) == poly(ts[1])) continue;
    Vec3 n1 = tri_normal(v, tris[ts[0]]), n2 = tri_normal(v, tris[ts[1]]);
    const double l1 = length(n1), l2 = length(n2);
    if (!(l1 > 0 && l2 > 0)) continue;
    n1 = (1.0 / l1) * n1, n2 = (1.0 / l2) * n2;
    if (dot(n1, n2) > 1 - 1e-10) continue;  // coplanar
    // Convex when the second triangle's far vertex lies below the first's plane.
    const auto& t2 = tris[ts[1]];
    int far = t2[0];
    for (int w : t2)
      if (w != e.first && w != e.second) far = w;
    lines.push_back({a, b, dot(n1, v[size_t(far)] - a) < 0 ? LineKind::Convex : LineKind::Concave});
  }
  return lines;
}

}  // namespace

std::vector<Mesh> mesh_components(const Mesh& mesh) {
  std::vector<int> parent(mesh.vertices.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[size_t(a)] != a) a = parent[size_t(a)] = parent[size_t(parent[size_t(a)])];
    return a;
  };
  for (const auto& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) parent[size_t(find(t[size_t(k)]))] = find(t[0]);
  std::map<int, size_t> comp_of;  // root -> component
  std::vector<Mesh> out;
  std::vector<std::map<int, int>> vmap, pmap;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    auto [it, fresh] = comp_of.try_emplace(find(t[0]), out.size());
    if (fresh) {
      out.emplace_back();
      out.back().path = mesh.path;
      vmap.emplace_back();
      pmap.emplace_back();
    }
    const size_t c = it->second;
    Mesh& m = out[c];
    std::array<int, 3> nt{};
    for (int k = 0; k < 3; ++k) {
      auto [v, added] = vmap[c].try_emplace(t[size_t(k)], int(m.vertices.size()));
      if (added) m.vertices.push_back(mesh.vertices[size_t(t[size_t(k)])]);
      nt[size_t(k)] = v->second;
      if (3 * i + size_t(k) < mesh.corner_normals.size()) m.corner_normals.push_back(mesh.corner_normals[3 * i + size_t(k)]);
    }
    m.triangles.push_back(nt);
    const int poly = i < mesh.polygon_of.size() ? mesh.polygon_of[i] : int(i);
    m.polygon_of.push_back(pmap[c].try_emplace(poly, int(pmap[c].size())).first->second);
  }
  for (Mesh& m : out) {
    m.boundary_edges = boundary_edges(m.triangles);
    m.closed = m.boundary_edges == 0;
  }
  return out;
}

void add_real_lines(CellComplex& c, const std::vector<RealLine>& lines) {
  const double scale = c.far_box.magnitude();
  const double tol = 1e-9 * scale;       // [m] a line on a face is on it within rounding
  const double min_len = 1e-6 * scale;   // [m] shorter stretches only touch the cell
  std::vector<Box3> bounds(c.cells.size());
  for (size_t i = 0; i < c.cells.size(); ++i) bounds[i] = c.cells[i].bounds();
  // The cells a line may touch come from the complex's own grid in plan (CellComplex::
  // cells_near), tested in ascending order; testing every line against every cell grew
  // as lines × cells.
  if (c.bands.empty()) c.index();
  std::vector<CellId> candidates;
  for (const RealLine& l : lines) {
    const LineId id = LineId(c.lines.size());
    c.lines.push_back(l);
    Box3 lb;
    lb.add(l.a), lb.add(l.b);
    const double len = length(l.b - l.a);
    if (!(len > min_len)) continue;
    c.cells_near(lb.grown(tol), candidates);
    for (const CellId i : candidates) {
      if (!lb.meets(bounds[size_t(i)], tol)) continue;
      // The stretch inside every face's plane (grown by tol): a + t·s <= tol; and within
      // the cell's heights (grown by tol), which near an acute edge of a cell the grown
      // planes alone do not keep.
      double t0 = 0, t1 = 1;
      const Cell& cell = c.cells[size_t(i)];
      const double dz = l.b.z - l.a.z;
      if (std::fabs(dz) > 1e-300) {
        const double s0 = (cell.z0 - tol - l.a.z) / dz, s1 = (cell.z1 + tol - l.a.z) / dz;
        t0 = std::max(t0, std::min(s0, s1)), t1 = std::min(t1, std::max(s0, s1));
      } else if (l.a.z < cell.z0 - tol || l.a.z > cell.z1 + tol) {
        continue;
      }
      for (const Face& f : cell.faces) {
        const double a = f.plane.eval(l.a), s = f.plane.eval(l.b) - a;
        if (std::fabs(s) < 1e-300) {
          if (a > tol) t1 = -1;
        } else if (s > 0) {
          t1 = std::min(t1, (tol - a) / s);
        } else {
          t0 = std::max(t0, (tol - a) / s);
        }
        if (t1 < t0) break;
      }
      if ((t1 - t0) * len > min_len) c.cells[size_t(i)].lines.push_back({id, t0, t1});
    }
  }
}

namespace {

/// The first view the files keep (Mesh::viewpoint: a model's camera, a VRML Viewpoint, an
/// Irrlicht camera); nullptr when none keeps one.
const Viewpoint* view_of_files(const std::vector<Mesh>& meshes) {
  for (const Mesh& m : meshes)
    if (m.viewpoint) return &*m.viewpoint;
  return nullptr;
}

/// The scene's box grown to hold the eye of the files' view, so that the far box holds it
/// too (start_at_view_of_files).
void include_view_of_files(Box3& box, const std::vector<Mesh>& meshes) {
  const Viewpoint* v = view_of_files(meshes);
  if (v && std::isfinite(v->eye.x) && std::isfinite(v->eye.y) && std::isfinite(v->eye.z)) box.add(v->eye);
}

/// The far box around `box` (the scene's contents) with margin m, and a first view from a
/// corner of the margin (free, whatever the scene is), looking at the middle of the
/// scene, wide enough to take in the sphere around it.
void frame_scene(CellComplex& out, const Box3& box, double m) {
  // Avenues works at the scale of buildings: a near plane of 1 cm, this margin of metres.
  // A scene a few centimetres across is most often one whose unit was lost on the way (a
  // model in millimetres read as metres); the user is told, not second-guessed.
  if (const double across = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z}); across < 0.1) {
    char size[64];
    std::snprintf(size, sizeof size, "%.3g cm", 100 * across);
    out.warnings.push_back(std::string("the scene is only ") + size +
                           " across: Avenues works at the scale of buildings (its pictures' near plane is 1 cm "
                           "away), so views from inside it show little; if its unit was lost, give --unit where "
                           "its format declares none");
  }
  out.far_box.lo = box.lo - Vec3{m, m, m};
  out.far_box.hi = box.hi + Vec3{m, m, m};
  const Vec3 middle = 0.5 * (box.lo + box.hi);
  const Vec3 eye{box.lo.x - m / 2, box.lo.y - m / 2, middle.z};
  const double fov = deg_from_rad(2 * std::atan(length(box.hi - box.lo) / 2 / length(middle - eye)));
  out.view = Viewpoint{eye, middle, std::clamp(fov, 40.0, 120.0)};
}

/// The first view inside the scene's largest enclosed free region, where it has one: free
/// space that no portal joins to the far box's (the inside of a closed house, a room with
/// its door shut), of at least a tenth of the scene's box, and not inside a closed solid
/// (a winding number of the soup about it under ½: not the inside of a closed cushion,
/// block or statue). The eye at the middle of the region's largest cell, looking level
/// towards the farthest of the region's cells. Without such a region the view stays
/// frame_scene's, outside looking at the scene.
void view_inside_largest_region(CellComplex& out, const Box3& scene, const std::vector<Triangle3>& soup) {
  const size_t n = out.cells.size();
  const FreeRegions regions = free_regions(out);
  if (regions.outside == n) return;
  const Vec3 e = scene.hi - scene.lo;
  std::vector<size_t> roots;
  for (size_t i = 0; i < n; ++i)
    if (regions.of[i] == i && i != regions.outside && regions.volume[i] >= 0.1 * e.x * e.y * e.z) roots.push_back(i);
  std::sort(roots.begin(), roots.end(), [&](size_t a, size_t b) { return regions.volume[a] > regions.volume[b]; });
  size_t best = n;
  for (size_t r : roots)
    if (winding_number(soup, out.cells[regions.largest[r]].middle()) < 0.5) {
      best = r;
      break;
    }
  if (best == n) return;
  const Vec3 eye = out.cells[regions.largest[best]].middle();
  Vec3 look = eye + Vec3{1, 0, 0};
  double far = 0;
  for (size_t i = 0; i < n; ++i) {
    if (regions.of[i] != best) continue;
    const Vec3 m = out.cells[i].middle();
    const double d = std::hypot(m.x - eye.x, m.y - eye.y);
    if (d > far) far = d, look = {m.x, m.y, eye.z};
  }
  out.view = Viewpoint{eye, look, 70};
}

/// The first view: the files' own (view_of_files), where its eye stands in free space,
/// as the file's own viewer starts there.
void start_at_view_of_files(CellComplex& out, const std::vector<Mesh>& meshes) {
  const Viewpoint* v = view_of_files(meshes);
  if (v && length(v->look - v->eye) > 0 && out.locate(v->eye).what == Location::What::Cell) out.view = *v;
}

/// The meshes with only the triangles `keep` says (numbered through all meshes in order).
std::vector<Mesh> meshes_keeping(const std::vector<Mesh>& meshes, const std::vector<bool>& keep) {
  std::vector<Mesh> out;
  size_t at = 0;
  for (const Mesh& m : meshes) {
    Mesh& k = out.emplace_back();
    k.path = m.path;
    k.vertices = m.vertices;
    k.materials = m.materials;
    for (size_t t = 0; t < m.triangles.size(); ++t, ++at) {
      if (!keep[at]) continue;
      k.triangles.push_back(m.triangles[t]);
      if (t < m.polygon_of.size()) k.polygon_of.push_back(m.polygon_of[t]);
      if (t < m.material_of.size()) k.material_of.push_back(m.material_of[t]);
      for (size_t c = 3 * t; c < 3 * t + 3 && c < m.corner_normals.size(); ++c) k.corner_normals.push_back(m.corner_normals[c]);
    }
  }
  return out;
}

/// MeshSceneMethod::Bsp: the meshes' triangles as one soup (soup_bsp.h); a large soup's
/// small polygons as detail (soup_detail.h).
CellComplex build_soup_scene(const std::vector<Mesh>& meshes, const MeshSceneParams& params) {
  CellComplex out;
  std::vector<SoupTriangle> soup;
  std::vector<size_t> mesh_of;    // per soup triangle
  std::vector<int64_t> polygon;   // per soup triangle: its input polygon, through all meshes
  Box3 box = params.include;
  for (size_t i = 0; i < meshes.size(); ++i) {
    const Mesh& m = meshes[i];
    // The mesh's colours become the complex's materials, carried onto the faces they cover.
    const MaterialId first = MaterialId(out.materials.size());
    out.materials.insert(out.materials.end(), m.materials.begin(), m.materials.end());
    for (size_t k = 0; k < m.triangles.size(); ++k) {
      const auto& t = m.triangles[k];
      const MaterialId own = k < m.material_of.size() ? m.material_of[k] : -1;
      const MaterialId material = own >= 0 && size_t(own) < m.materials.size() ? first + own : -1;
      soup.push_back({{m.vertices[size_t(t[0])], m.vertices[size_t(t[1])], m.vertices[size_t(t[2])]}, material});
      mesh_of.push_back(i);
      polygon.push_back(int64_t(i) << 32 | int64_t(uint32_t(k < m.polygon_of.size() ? m.polygon_of[k] : int(k))));
      for (Vec3 p : soup.back().p) box.add(p);
    }
  }
  if (!(box.lo.x <= box.hi.x)) throw std::invalid_argument("mesh scene: no triangles and nothing to include");
  include_view_of_files(box, meshes);
  frame_scene(out, box, params.margin);
  const Vec3 extent = box.hi - box.lo;
  const double least_area = std::min(params.structural_area_cap,
                                     params.structural_share * std::max({extent.x * extent.y, extent.y * extent.z, extent.x * extent.z}));
  // Closed curved solids are detail whatever the soup's size (cells/closed_surface.h).
  std::vector<bool> curved;  // per soup triangle, when some solid is curved
  std::vector<ClosedSolid> curved_solids;
  std::vector<ClosedSolid> meshes_solids;  // closed_solids(meshes), the curved ones moved out
  if (params.curved_directions > 0) {
    ScopedStageTimer t(out.timings, "curved solids");
    std::vector<size_t> first_of(meshes.size() + 1, 0);  // each mesh's first soup triangle
    for (size_t i = 0; i < meshes.size(); ++i) first_of[i + 1] = first_of[i] + meshes[i].triangles.size();
    meshes_solids = closed_solids(meshes);
    for (ClosedSolid& s : meshes_solids) {
      if (!is_curved(s, params.curved_directions)) continue;
      curved.resize(soup.size(), false);
      for (size_t k : s.source) curved[first_of[s.mesh] + k] = true;
      curved_solids.push_back(std::move(s));
    }
  }
  // A split ranks flat surfaces, not single polygons (soup_detail.h: flat_surfaces): found
  // only for a soup that may be split (more triangles than detail_above, or cluttered).
  std::vector<int64_t> surface;
  auto surfaces = [&]() -> const std::vector<int64_t>& {
    if (surface.empty()) {
      ScopedStageTimer t(out.timings, "flat surfaces");
      surface = flat_surfaces(soup, polygon);
    }
    return surface;
  };
  SoupSplit split = split_detail(soup, soup.size() > params.detail_above ? surfaces() : polygon, params.detail_above, params.structural_triangles, least_area, curved);
  // What cuts space: the whole soup, or its structural part (`cut_of`: its soup numbers).
  std::vector<SoupTriangle> structural, detail;
  std::vector<size_t> cut_of;
  std::vector<int64_t> detail_polygon;
  std::map<size_t, size_t> dropped;  // mesh -> triangles with no area
  auto partition = [&] {
    structural.clear(), detail.clear(), cut_of.clear(), detail_polygon.clear(), dropped.clear();
    if (split.detail_triangles == 0) return;
    for (size_t t = 0; t < soup.size(); ++t) {
      if (!split.detail[t]) {
        structural.push_back(soup[t]);
        cut_of.push_back(t);
      } else if (length(cross(soup[t].p[1] - soup[t].p[0], soup[t].p[2] - soup[t].p[0])) > 0) {
        detail.push_back(soup[t]);
        // One polygon a flat surface and material, lit as one (one shade, no diagonals).
        detail_polygon.push_back(surface.empty() ? polygon[t] : surface[t] << 32 | int64_t(uint32_t(soup[t].material)));
      } else {
        dropped[mesh_of[t]]++;
      }
    }
  };
  partition();
  auto what_cuts = [&]() -> const std::vector<SoupTriangle>& { return split.detail_triangles > 0 ? structural : soup; };
  // A cluttered soup (its planes cut space into more than params.leaf_budget leaves) is
  // split as a large one is, by a quarter of the triangles that cut space at each try.
  SoupBspStats stats;
  bool cluttered = false;
  for (;;) {
    try {
      stats = decompose_soup(what_cuts(), out.far_box, out, params.leaf_budget);
      break;
    } catch (const SoupTooCluttered&) {
      if (!out.timings.empty()) out.timings.back().stage = "decompose, abandoned";
      cluttered = true;
      split = split_detail(soup, surfaces(), 0, split.structural / 4, least_area, curved);
      partition();
    }
  }
  for (size_t t : stats.degenerate) dropped[mesh_of[cut_of.empty() ? t : cut_of[t]]]++;
  for (const auto& [mesh, count] : dropped)
    out.warnings.push_back((meshes[mesh].path.empty() ? std::string("mesh") : meshes[mesh].path) + ": " +
                           std::to_string(count) + " triangles with no area (corners on a line): dropped");
  drop_slivers(out);
  // The closed solids and the lines are those of what cuts space; detail draws its own.
  std::vector<bool> keep(split.detail.size());
  for (size_t t = 0; t < keep.size(); ++t) keep[t] = !split.detail[t];
  const std::vector<Mesh> structural_meshes = split.detail_triangles > 0 ? meshes_keeping(meshes, keep) : std::vector<Mesh>{};
  const std::vector<Mesh>& solid_meshes = split.detail_triangles > 0 ? structural_meshes : meshes;
  {
    // A closed, outward-oriented solid is seen from outside only: the cells inside it go.
    ScopedStageTimer t(out.timings, "solids");
    // With nothing detail (no curved solid either), the solids of what cuts space are those
    // already found for the curved ones, none moved out.
    const std::vector<ClosedSolid> solids = split.detail_triangles == 0 && params.curved_directions > 0
                                                ? std::move(meshes_solids)
                                                : closed_solids(solid_meshes);
    const std::vector<int> inside = cells_inside_solids(out, solids);
    std::vector<bool> drop(inside.size());
    std::vector<bool> named(solids.size(), false);
    for (size_t i = 0; i < inside.size(); ++i)
      if ((drop[i] = inside[i] >= 0)) named[size_t(inside[i])] = true;
    remove_cells(out, drop);
    for (size_t k = 0; k < solids.size(); ++k) {
      if (!named[k]) continue;
      const Box3& b = solids[k].box;
      out.solids.push_back({{{b.lo.x, b.lo.y}, {b.hi.x, b.lo.y}, {b.hi.x, b.hi.y}, {b.lo.x, b.hi.y}}, b.lo.z, b.hi.z,
                            solids[k].name});
    }
  }
  {
    ScopedStageTimer t(out.timings, "seams");
    out.close_seams();
  }
  out.index();  // before the lines: add_real_lines takes its candidate cells from it
  for (ClosedSolid& s : curved_solids) out.detail_solids.emplace_back(s.name, std::move(s.triangles));
  {
    std::vector<Triangle3> cutting;
    for (const SoupTriangle& t : what_cuts()) cutting.push_back(t.p);
    view_inside_largest_region(out, box, cutting);
  }
  start_at_view_of_files(out, meshes);
  if (!detail.empty()) {
    ScopedStageTimer t(out.timings, "detail");
    const std::string source = meshes.size() == 1 && !meshes[0].path.empty() ? meshes[0].path : "the meshes";
    add_detail_objects(out, detail, detail_polygon, source);
    std::vector<CellId> holding;
    for (const Object& o : out.objects) holding.push_back(o.cell);
    std::sort(holding.begin(), holding.end());
    const size_t cells_holding = size_t(std::unique(holding.begin(), holding.end()) - holding.begin());
    const std::string drawn_in =
        cells_holding == 1 ? std::string("the one cell") : "the " + std::to_string(cells_holding) + " cells";
    if (!out.detail_solids.empty()) {
      // "FILE: solid N" each; said once per file where they all come from one.
      std::ostringstream said;
      const size_t n = out.detail_solids.size();
      auto file_of = [](const std::string& name) { return name.substr(0, name.rfind(": solid ")); };
      const std::string file = file_of(out.detail_solids[0].name());
      bool one_file = true;
      for (const ClosedSurface& d : out.detail_solids) one_file &= file_of(d.name()) == file;
      if (n == 1) {
        said << out.detail_solids[0].name() << " (" << split.curved
             << " triangles) is closed and curved: detail, not cut into a cell per facet but drawn in the cells "
                "around it; the walker stays out of it, the search sees through it";
      } else {
        said << (one_file ? file + ": " : std::string()) << n << " closed curved solids ("
             << (one_file ? "solids " : "");
        for (size_t k = 0; k < std::min<size_t>(n, 3); ++k) {
          const std::string& name = out.detail_solids[k].name();
          said << (k ? ", " : "") << (one_file ? name.substr(name.rfind(' ') + 1) : name);
        }
        if (n > 3) said << " and " << n - 3 << " more";
        said << "; " << split.curved << " triangles) are detail: not cut into a cell per facet but drawn in the "
             << "cells around them; the walker stays out of them, the search sees through them";
      }
      out.warnings.push_back(said.str());
    }
    if (split.detail_triangles > split.curved) {
      std::ostringstream said;
      said << source << ": " << split.structural + split.detail_triangles - split.curved << " triangles with area"
           << (cluttered ? " whose planes cut space into more than " + std::to_string(params.leaf_budget) + " pieces"
                         : std::string(", more than a decomposition takes in seconds"));
      if (split.structural > 0)
        said << ": its largest flat surfaces (from " << split.smallest_structural << " m², " << split.structural
             << " triangles) cut space into cells, and the other ";
      else
        said << ": none of its polygons is large enough to cut space (" << least_area << " m² or more), and all ";
      said << split.detail_triangles - split.curved << " triangles are detail, drawn in " << drawn_in
           << " they cross; the search sees through detail, the pictures show it, the walker stops at it";
      out.warnings.push_back(said.str());
    }
  }
  {
    ScopedStageTimer t(out.timings, "lines");
    std::vector<RealLine> lines;
    for (const Mesh& m : solid_meshes) {
      std::vector<RealLine> l = feature_edges(m.vertices, m.triangles, m.polygon_of, true);
      lines.insert(lines.end(), l.begin(), l.end());
    }
    add_real_lines(out, lines);
  }
  check_complex(out, "a mesh scene (soup BSP)");
  return out;
}

}  // namespace

CellComplex build_mesh_scene(const std::vector<Mesh>& meshes, const MeshSceneParams& params) {
  if (!(params.margin > 0)) throw std::invalid_argument("mesh scene: margin must be > 0");
  if (!(params.sheet_thickness > 0)) throw std::invalid_argument("mesh scene: sheet thickness must be > 0");
  if (params.method == MeshSceneMethod::Bsp) return build_soup_scene(meshes, params);
  CellComplex out;
  std::vector<Solid> solids;
  Nef free;
  {
    ScopedStageTimer t(out.timings, "solids");
    for (const Mesh& mesh : meshes) {
      std::vector<Mesh> parts = mesh_components(mesh);
      const std::string file = mesh.path.empty() ? std::string("mesh") : mesh.path;
      for (size_t i = 0; i < parts.size(); ++i) {
        const std::string name = parts.size() == 1 ? file : file + ": component " + std::to_string(i + 1);
        Solid s = solid_of(parts[i], name, params.sheet_thickness, out.warnings);
        if (!s.tris.empty()) solids.push_back(std::move(s));
      }
    }
  }
  Box3 box = params.include;
  for (const Solid& s : solids)
    for (Vec3 p : s.v) box.add(p);
  if (!(box.lo.x <= box.hi.x)) throw std::invalid_argument("mesh scene: no solids and nothing to include");
  include_view_of_files(box, meshes);
  frame_scene(out, box, params.margin);
  {
    ScopedStageTimer t(out.timings, "free");
    CGAL::Nef_nary_union_3<Nef> all;
    bool any = false;
    for (const Solid& s : solids) {
      SurfaceMesh sm;
      if (!to_surface_mesh(s, sm)) {
        out.warnings.push_back(s.name + ": not a manifold surface after repair: dropped");
        continue;
      }
      all.add_polyhedron(Nef(sm));
      any = true;
    }
    const Vec3 lo = out.far_box.lo, hi = out.far_box.hi;
    // The far box (a bounded Nef polyhedron: half-spaces need the extended kernel).
    Solid far;
    for (int k = 0; k < 8; ++k) far.p.emplace_back(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) far.tris.push_back({q[0], q[1], q[2]}), far.tris.push_back({q[0], q[2], q[3]});
    SurfaceMesh box_mesh;
    to_surface_mesh(far, box_mesh);
    free = Nef(box_mesh);
    if (any) free = (free - all.get_union()).regularization();
  }
  {
    ScopedStageTimer t(out.timings, "decompose");
    CGAL::convex_decomposition_3(free);
  }
  {
    ScopedStageTimer t(out.timings, "cells");
    build_cells_of(free, out);
  }
  {
    ScopedStageTimer t(out.timings, "seams");
    out.close_seams();
  }
  out.index();  // before the lines: add_real_lines takes its candidate cells from it
  {
    ScopedStageTimer t(out.timings, "lines");
    std::vector<RealLine> lines;
    for (const Solid& s : solids) {
      std::vector<RealLine> l = feature_edges(s.v, s.tris, s.polygon_of, false);
      lines.insert(lines.end(), l.begin(), l.end());
      // What a point inside the solid is in, by its bounding box (for locate()).
      Box3 b;
      for (Vec3 p : s.v) b.add(p);
      out.solids.push_back({{{b.lo.x, b.lo.y}, {b.hi.x, b.lo.y}, {b.hi.x, b.hi.y}, {b.lo.x, b.hi.y}}, b.lo.z, b.hi.z, s.name});
    }
    add_real_lines(out, lines);
  }
  start_at_view_of_files(out, meshes);
  check_complex(out, "a mesh scene");
  return out;
}

CellComplex read_mesh_scene(const std::string& path, const MeshSceneParams& params) {
  Mesh mesh = load_mesh(path);  // names the file when it cannot be read
  CellComplex c;
  try {
    c = build_mesh_scene({mesh}, params);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  c.plan_name = std::filesystem::path(path).stem().string();
  return c;
}

}  // namespace avenues
