// Avenues — one polygon of a mesh cut into triangles (see polygon_triangulation.h). The
// only translation unit of plans/ that compiles CGAL.
#include "plans/polygon_triangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <cmath>

namespace avenues {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
/// A vertex's index in the mesh; -1 for a crossing of two edges, made by the triangulation.
struct Corner {
  int index = -1;
};
using Vb = CGAL::Triangulation_vertex_base_with_info_2<Corner, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Point = K::Point_2;

/// The polygon's normal (not unit): Newell's; for one whose parts cancel in it (a bow
/// tie with equal lobes), the largest of its fan's from the first corner; zero only when
/// every corner lies on one line.
Vec3 normal_of(const std::vector<Vec3>& v, const std::vector<int>& p) {
  Vec3 n{0, 0, 0}, largest{0, 0, 0};
  const Vec3 o = v[size_t(p[0])];
  for (size_t i = 0; i < p.size(); ++i) {
    const Vec3 c = cross(v[size_t(p[i])] - o, v[size_t(p[(i + 1) % p.size()])] - o);
    n = n + c;
    if (length(c) > length(largest)) largest = c;
  }
  return length(n) > 1e-9 * length(largest) ? n : largest;
}

/// The plane's coordinates, chosen so that counter-clockwise about n is counter-clockwise
/// in them: the two axes other than n's largest, in cyclic order, swapped when that
/// component is negative.
struct Projection {
  int k = 2, u = 0, w = 1;
  explicit Projection(Vec3 n) {
    const double a[3] = {std::fabs(n.x), std::fabs(n.y), std::fabs(n.z)};
    k = a[0] >= a[1] && a[0] >= a[2] ? 0 : a[1] >= a[2] ? 1 : 2;
    u = (k + 1) % 3, w = (k + 2) % 3;
    if ((k == 0 ? n.x : k == 1 ? n.y : n.z) < 0) std::swap(u, w);
  }
  static double at(Vec3 p, int i) { return i == 0 ? p.x : i == 1 ? p.y : p.z; }
  Point operator()(Vec3 p) const { return {at(p, u), at(p, w)}; }
};

/// How many times the projected polygon winds round q (signed).
int winding(const std::vector<Point>& poly, const Point& q) {
  int wn = 0;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Point &a = poly[i], &b = poly[(i + 1) % poly.size()];
    if (a.y() <= q.y()) {
      if (b.y() > q.y() && CGAL::orientation(a, b, q) == CGAL::LEFT_TURN) ++wn;
    } else if (b.y() <= q.y() && CGAL::orientation(a, b, q) == CGAL::RIGHT_TURN) {
      --wn;
    }
  }
  return wn;
}

}  // namespace

bool polygon_is_convex(const std::vector<Vec3>& v, const std::vector<int>& p) {
  const size_t n = p.size();
  if (n <= 3) return true;
  const Vec3 normal = normal_of(v, p);
  const double len = length(normal);
  if (!(len > 0)) return true;  // no area: whatever it is cut into has none either
  const Vec3 nn = (1.0 / len) * normal;
  double turning = 0;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 a = v[size_t(p[(i + n - 1) % n])], b = v[size_t(p[i])], c = v[size_t(p[(i + 1) % n])];
    const Vec3 e = b - a, f = c - b;
    const double s = dot(cross(e, f), nn), d = dot(e, f);
    // Rounding of the file's numbers aside, a right turn is a notch.
    if (s < -1e-12 * (length(e) * length(f))) return false;
    turning += std::atan2(s, d);
  }
  return std::fabs(turning - 2 * M_PI) < 1e-6;  // once round, not a star
}

std::vector<std::array<int, 3>> triangulate_polygon(std::vector<Vec3>& v, const std::vector<int>& p) {
  std::vector<std::array<int, 3>> out;
  const Vec3 normal = normal_of(v, p);
  const double len = length(normal);
  if (p.size() < 3 || !(len > 0)) return out;
  const Projection proj(normal);
  std::vector<Point> poly;
  poly.reserve(p.size());
  for (int i : p) poly.push_back(proj(v[size_t(i)]));
  CDT cdt;
  std::vector<CDT::Vertex_handle> handle;
  handle.reserve(p.size());
  for (size_t i = 0; i < p.size(); ++i) {
    CDT::Vertex_handle h = cdt.insert(poly[i]);
    if (h->info().index < 0) h->info().index = p[i];  // a corner given twice keeps its first index
    handle.push_back(h);
  }
  for (size_t i = 0; i < p.size(); ++i) {
    const CDT::Vertex_handle a = handle[i], b = handle[(i + 1) % p.size()];
    if (a != b) cdt.insert_constraint(a, b);
  }
  // Crossings of edges are new vertices, lifted to the polygon's plane.
  const Vec3 nn = (1.0 / len) * normal, o = v[size_t(p[0])];
  for (auto it = cdt.finite_vertices_begin(); it != cdt.finite_vertices_end(); ++it) {
    if (it->info().index >= 0) continue;
    double q[3] = {0, 0, 0};
    q[proj.u] = it->point().x(), q[proj.w] = it->point().y();
    const double nk = Projection::at(nn, proj.k);
    q[proj.k] = Projection::at(o, proj.k) -
                (Projection::at(nn, proj.u) * (q[proj.u] - Projection::at(o, proj.u)) +
                 Projection::at(nn, proj.w) * (q[proj.w] - Projection::at(o, proj.w))) / nk;
    it->info().index = int(v.size());
    v.push_back({q[0], q[1], q[2]});
  }
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const Point c = CGAL::centroid(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
    if (winding(poly, c) == 0) continue;
    out.push_back({f->vertex(0)->info().index, f->vertex(1)->info().index, f->vertex(2)->info().index});
  }
  return out;
}

}  // namespace avenues
