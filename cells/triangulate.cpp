// Avenues — the exact constrained triangulation (see triangulation.h).
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "cells/triangulation.h"

namespace avenues::detail {

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int32_t, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// The "plus" hierarchy keeps input constraints whole, so crossings are computed from
// input points only (no cascade of constructions on constructed points).
using CDT = CGAL::Constrained_triangulation_plus_2<
    CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_intersections_tag>>;
using Point = K::Point_2;

Point P(Vec2 v) { return Point(v.x, v.y); }

/// A uniform grid of item bounding boxes over the far box, for "what covers this point".
struct Grid {
  Vec2 lo;
  double size = 1;
  int nx = 1, ny = 1;
  std::vector<std::vector<int32_t>> cell;
  Grid(Vec2 lo_, Vec2 hi, size_t items) : lo(lo_) {
    double w = hi.x - lo.x, h = hi.y - lo.y;
    size = std::max(std::sqrt(w * h / double(std::max<size_t>(items, 1))), 1e-6);
    nx = std::clamp(int(w / size) + 1, 1, 4096);
    ny = std::clamp(int(h / size) + 1, 1, 4096);
    size = std::max(w / nx, h / ny) * (1 + 1e-9);
    cell.resize(size_t(nx) * size_t(ny));
  }
  int ix(double x) const { return std::clamp(int((x - lo.x) / size), 0, nx - 1); }
  int iy(double y) const { return std::clamp(int((y - lo.y) / size), 0, ny - 1); }
  void add(int32_t id, const std::vector<Vec2>& pts) {
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
    for (Vec2 p : pts) x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
    for (int j = iy(y0); j <= iy(y1); ++j)
      for (int i = ix(x0); i <= ix(x1); ++i) cell[size_t(j) * size_t(nx) + size_t(i)].push_back(id);
  }
  const std::vector<int32_t>& at(Vec2 p) const { return cell[size_t(iy(p.y)) * size_t(nx) + size_t(ix(p.x))]; }
};

bool strictly_inside_convex(const std::vector<Point>& poly, const Point& c) {
  for (size_t i = 0; i < poly.size(); ++i)
    if (CGAL::orientation(poly[i], poly[(i + 1) % poly.size()], c) != CGAL::LEFT_TURN) return false;
  return true;
}

/// Numbers the CDT's finite faces 0.. (their info) and fills T's triangles (by the
/// vertices' info) and neighbours; returns the faces in that order.
template <class Cdt>
std::vector<typename Cdt::Face_handle> number_faces(Cdt& cdt, Triangulation& T) {
  int32_t nf = 0;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) f->info() = nf++;
  T.tri.resize(size_t(nf));
  T.nbr.resize(size_t(nf));
  std::vector<typename Cdt::Face_handle> faces(static_cast<size_t>(nf));
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const int t = f->info();
    faces[size_t(t)] = f;
    for (int i = 0; i < 3; ++i) {
      T.tri[size_t(t)][size_t(i)] = f->vertex(i)->info();
      auto g = f->neighbor(i);
      T.nbr[size_t(t)][size_t(i)] = cdt.is_infinite(g) ? -1 : g->info();
    }
  }
  return faces;
}

}  // namespace

int orientation(Vec2 a, Vec2 b, Vec2 c) {
  using Ik = CGAL::Exact_predicates_inexact_constructions_kernel;
  return int(CGAL::orientation(Ik::Point_2(a.x, a.y), Ik::Point_2(b.x, b.y), Ik::Point_2(c.x, c.y)));
}

struct ExactTriangulation::Exact {
  CDT cdt;
  std::vector<CDT::Vertex_handle> handle;  ///< per vertex of the rounded triangulation
};

namespace {

/// The CDT rounded once: vertices, triangles, neighbours, and what covers each triangle
/// and lies on each edge (regions, holes, sheets, and the cuts given).
Triangulation round_off(CDT& cdt, std::vector<CDT::Vertex_handle>& handle, const Outline& outline,
                        const std::vector<Vec2>& points, const std::vector<std::array<Point, 2>>& cut_segments,
                        const std::vector<int32_t>& cut_bands) {
  Triangulation T;
  handle.clear();
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    v->info() = int32_t(T.vert.size());
    T.vert.push_back({CGAL::to_double(v->point().x()), CGAL::to_double(v->point().y())});
    handle.push_back(v);
  }
  const std::vector<CDT::Face_handle> faces = number_faces(cdt, T);
  const int nf = T.size();

  // Which thick-wall regions cover each triangle: its centroid, exactly, in the convex region.
  std::vector<std::vector<Point>> exact_regions(outline.regions.size());
  Grid grid(outline.lo, outline.hi, outline.regions.size());
  for (size_t r = 0; r < outline.regions.size(); ++r) {
    const Region& reg = outline.regions[r];
    for (Vec2 v : reg.poly) exact_regions[r].push_back(P(v));
    grid.add(int32_t(r), reg.poly);
  }
  std::vector<std::vector<Point>> exact_holes;
  Grid hole_grid(outline.lo, outline.hi, outline.holes.size());
  for (size_t h = 0; h < outline.holes.size(); ++h) {
    exact_holes.emplace_back();
    for (Vec2 v : outline.holes[h]) exact_holes.back().push_back(P(v));
    hole_grid.add(int32_t(h), outline.holes[h]);
  }
  Grid cut_grid(outline.lo, outline.hi, cut_segments.size());
  for (size_t k = 0; k < cut_segments.size(); ++k)
    cut_grid.add(int32_t(k), {{CGAL::to_double(cut_segments[k][0].x()), CGAL::to_double(cut_segments[k][0].y())},
                              {CGAL::to_double(cut_segments[k][1].x()), CGAL::to_double(cut_segments[k][1].y())}});
  T.region_start.assign(1, 0);
  T.hole_start.assign(1, 0);
  T.sheet_start.assign(1, 0);
  if (!cut_segments.empty()) T.cut_start.assign(1, 0);
  for (int t = 0; t < nf; ++t) {
    auto f = faces[size_t(t)];
    Point c = CGAL::centroid(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
    Vec2 cd{CGAL::to_double(c.x()), CGAL::to_double(c.y())};
    for (int32_t r : grid.at(cd)) {
      const Region& reg = outline.regions[size_t(r)];
      if (!reg.sheet && strictly_inside_convex(exact_regions[size_t(r)], c)) T.region_items.push_back(r);
    }
    T.region_start.push_back(int32_t(T.region_items.size()));
    for (int32_t h : hole_grid.at(cd))
      if (CGAL::bounded_side_2(exact_holes[size_t(h)].begin(), exact_holes[size_t(h)].end(), c, K()) ==
          CGAL::ON_BOUNDED_SIDE)
        T.hole_items.push_back(h);
    T.hole_start.push_back(int32_t(T.hole_items.size()));
    // Sheets (walls of no thickness) lying on each constrained edge: its midpoint on the
    // sheet; likewise the cuts.
    for (int i = 0; i < 3; ++i) {
      if (f->is_constrained(i)) {
        const Point& a = f->vertex((i + 1) % 3)->point();
        const Point& b = f->vertex((i + 2) % 3)->point();
        Point mid = CGAL::midpoint(a, b);
        Vec2 md{CGAL::to_double(mid.x()), CGAL::to_double(mid.y())};
        for (int32_t r : grid.at(md)) {
          const Region& reg = outline.regions[size_t(r)];
          if (!reg.sheet) continue;
          const auto& s = exact_regions[size_t(r)];
          if (CGAL::collinear(s[0], s[1], mid) && CGAL::collinear_are_ordered_along_line(s[0], mid, s[1]))
            T.sheet_items.push_back(r);
        }
        if (!cut_segments.empty())
          for (int32_t k : cut_grid.at(md)) {
            const auto& s = cut_segments[size_t(k)];
            if (CGAL::collinear(s[0], s[1], mid) && CGAL::collinear_are_ordered_along_line(s[0], mid, s[1]) &&
                std::find(T.cut_items.begin() + T.cut_start.back(), T.cut_items.end(), cut_bands[size_t(k)]) ==
                    T.cut_items.end())
              T.cut_items.push_back(cut_bands[size_t(k)]);
          }
      }
      T.sheet_start.push_back(int32_t(T.sheet_items.size()));
      if (!cut_segments.empty()) T.cut_start.push_back(int32_t(T.cut_items.size()));
    }
  }
  // Locate query points (room labels).
  for (Vec2 p : points) {
    auto f = cdt.locate(P(p));
    T.label_tri.push_back(f == nullptr || cdt.is_infinite(f) ? -1 : f->info());
  }
  return T;
}

}  // namespace

ExactTriangulation::ExactTriangulation(const Outline& outline, const std::vector<Vec2>& points)
    : exact_(std::make_unique<Exact>()), outline_(outline), points_(points) {
  // Every outline edge becomes a constraint; exact intersections split crossing ones.
  std::vector<Point> pts;
  std::vector<std::pair<size_t, size_t>> segs;
  auto add_loop = [&](const std::vector<Vec2>& loop, bool closed) {
    size_t base = pts.size();
    for (Vec2 v : loop) pts.push_back(P(v));
    size_t n = loop.size();
    for (size_t i = 0; i + (closed ? 0 : 1) < n; ++i) segs.push_back({base + i, base + (i + 1) % n});
  };
  add_loop({outline.lo, {outline.hi.x, outline.lo.y}, outline.hi, {outline.lo.x, outline.hi.y}}, true);
  for (const Region& r : outline.regions) add_loop(r.poly, !r.sheet);
  for (const auto& h : outline.holes) add_loop(h, true);
  // Drop zero-length constraints (coincident points), which CGAL rejects.
  segs.erase(std::remove_if(segs.begin(), segs.end(), [&](auto s) { return pts[s.first] == pts[s.second]; }),
             segs.end());
  exact_->cdt.insert_constraints(pts.begin(), pts.end(), segs.begin(), segs.end());
  rounded_ = round_off(exact_->cdt, exact_->handle, outline_, points_, {}, {});
}

ExactTriangulation::~ExactTriangulation() = default;

std::vector<int32_t> ExactTriangulation::cut(const std::vector<Cut>& cuts, const std::vector<uint8_t>& keep) {
  CDT& cdt = exact_->cdt;
  // The edges to keep become constraints, so that no triangle after straddles one: each
  // lies where the triangles before it agree (the caller keeps every edge between
  // triangles it tells apart).
  const Triangulation& T = rounded_;
  for (int t = 0; t < T.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int32_t u = T.nbr[size_t(t)][size_t(i)];
      if (!keep[3 * size_t(t) + size_t(i)] || u < 0 || u < t) continue;
      const auto a = exact_->handle[size_t(T.tri[size_t(t)][size_t((i + 1) % 3)])];
      const auto b = exact_->handle[size_t(T.tri[size_t(t)][size_t((i + 2) % 3)])];
      CDT::Face_handle f;
      int j = 0;
      if (cdt.is_edge(a, b, f, j) && !cdt.is_constrained({f, j})) cdt.insert_constraint(a, b);
    }
  const CDT before = cdt;
  std::vector<CDT::Vertex_handle> before_vertex(T.vert.size());
  for (auto v = before.finite_vertices_begin(); v != before.finite_vertices_end(); ++v) before_vertex[size_t(v->info())] = v;
  std::unordered_set<const void*> known;
  for (const auto& v : exact_->handle) known.insert(&*v);
  std::vector<std::array<Point, 2>> segments;
  std::vector<int32_t> bands;
  for (const Cut& c : cuts) {
    const auto a = exact_->handle[size_t(c.a)], b = exact_->handle[size_t(c.b)];
    if (a == b) continue;
    segments.push_back({a->point(), b->point()});
    bands.push_back(c.band);
    cdt.insert_constraint(a, b);
  }
  // Each triangle after: the triangle before that holds its centroid, looked for from a
  // corner it shares with the triangulation before (its vertex's index is still the old one).
  std::unordered_map<const void*, int32_t> parent_of;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    CDT::Face_handle hint;
    for (int k = 0; k < 3 && hint == CDT::Face_handle(); ++k)
      if (known.count(&*f->vertex(k))) hint = before_vertex[size_t(f->vertex(k)->info())]->face();
    const Point c = CGAL::centroid(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
    const CDT::Face_handle in = before.locate(c, hint);
    parent_of[&*f] = before.is_infinite(in) ? -1 : in->info();
  }
  rounded_ = round_off(cdt, exact_->handle, outline_, points_, segments, bands);
  rounded_.cut_made.assign(rounded_.vert.size(), 0);
  for (size_t v = 0; v < exact_->handle.size(); ++v) rounded_.cut_made[v] = !known.count(&*exact_->handle[v]);
  std::vector<int32_t> parent(rounded_.tri.size(), -1);
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) parent[size_t(f->info())] = parent_of.at(&*f);
  return parent;
}

SegmentTriangulation triangulate_segments(const std::vector<Vec2>& points,
                                          const std::vector<std::array<int32_t, 2>>& segments) {
  // Its points are the given doubles and no others: exact predicates suffice, and a
  // crossing of two segments (which would need a constructed point) ends it.
  using Ik = CGAL::Exact_predicates_inexact_constructions_kernel;
  using IVb = CGAL::Triangulation_vertex_base_with_info_2<int32_t, Ik>;
  using IFb = CGAL::Constrained_triangulation_face_base_2<Ik, CGAL::Triangulation_face_base_with_info_2<int, Ik>>;
  using ICdt = CGAL::Constrained_Delaunay_triangulation_2<Ik, CGAL::Triangulation_data_structure_2<IVb, IFb>,
                                                          CGAL::No_constraint_intersection_requiring_constructions_tag>;
  SegmentTriangulation out;
  ICdt cdt;
  std::vector<ICdt::Vertex_handle> vh;
  vh.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    vh.push_back(cdt.insert(Ik::Point_2(points[i].x, points[i].y)));
    vh.back()->info() = int32_t(i);
  }
  if (cdt.number_of_vertices() != points.size()) {  // two points one
    out.crossed = true;
    return out;
  }
  try {
    for (auto [a, b] : segments)
      if (vh[size_t(a)] != vh[size_t(b)]) cdt.insert_constraint(vh[size_t(a)], vh[size_t(b)]);
  } catch (const ICdt::Intersection_of_constraints_exception&) {
    out.crossed = true;
    return out;
  }
  Triangulation& T = out.T;
  T.vert = points;
  const std::vector<ICdt::Face_handle> faces = number_faces(cdt, T);
  out.constrained.resize(3 * faces.size());
  for (size_t t = 0; t < faces.size(); ++t)
    for (int i = 0; i < 3; ++i) out.constrained[3 * t + size_t(i)] = faces[t]->is_constrained(i);
  return out;
}

}  // namespace avenues::detail
