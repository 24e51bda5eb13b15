// Avenues — the exact arrangement of wall curves (see wall_arrangement.h). CGAL lives
// here and nowhere else in plans/formats.
#include "plans/formats/wall_arrangement.h"

#include <algorithm>
#include <cmath>
#include <list>
#include <map>
#include <boost/variant/get.hpp>

#include <CGAL/Arr_batched_point_location.h>
#include <CGAL/Arr_consolidated_curve_data_traits_2.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

namespace avenues {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using SegTraits = CGAL::Arr_segment_traits_2<K>;
using Traits = CGAL::Arr_consolidated_curve_data_traits_2<SegTraits, int>;
using Arr = CGAL::Arrangement_2<Traits>;
using Point = Traits::Point_2;
using Curve = Traits::Curve_2;

Vec2 to_vec(const Point& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

bool in_rings(Vec2 p, const std::vector<std::vector<Vec2>>& rings) {
  bool in = false;
  for (const std::vector<Vec2>& r : rings)
    for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
      if ((r[i].y > p.y) != (r[j].y > p.y) && p.x < (r[j].x - r[i].x) * (p.y - r[i].y) / (r[j].y - r[i].y) + r[i].x)
        in = !in;
  return in;
}

/// Where each point lies: the face, or nothing when on an edge or vertex.
std::vector<Arr::Face_const_handle> locate_all(const Arr& arr, const std::vector<Point>& pts) {
  using Result = CGAL::Arr_point_location_result<Arr>::Type;
  std::vector<std::pair<Point, Result>> found;
  CGAL::locate(arr, pts.begin(), pts.end(), std::back_inserter(found));
  std::map<Point, Arr::Face_const_handle> by_point;
  for (const auto& [p, r] : found)
    if (const Arr::Face_const_handle* f = boost::get<Arr::Face_const_handle>(&r)) by_point.emplace(p, *f);
  std::vector<Arr::Face_const_handle> out;
  for (const Point& p : pts) {
    auto it = by_point.find(p);
    out.push_back(it == by_point.end() ? Arr::Face_const_handle() : it->second);
  }
  return out;
}

}  // namespace

WallArrangement arrange_walls(const WallArrangementInput& in) {
  WallArrangement out;
  std::vector<Curve> curves;
  curves.reserve(in.segments.size());
  auto finite = [](Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); };
  for (const ArrangedSegment& s : in.segments) {
    if (!finite(s.a) || !finite(s.b)) continue;  // a degenerate curve of the drawing
    const Point a(s.a.x, s.a.y), b(s.b.x, s.b.y);
    if (a != b) curves.emplace_back(SegTraits::Segment_2(a, b), s.closes);
  }
  Arr arr;
  CGAL::insert(arr, curves.begin(), curves.end());

  // A point inside each bounded face: a little to the left of the middle of one of its
  // outer boundary's edges (a face lies left of its boundary's halfedges), checked by
  // locating it; the longest edges are tried first.
  std::vector<Arr::Face_const_handle> faces;
  std::map<Arr::Face_const_handle, int> index;
  std::vector<std::vector<Arr::Halfedge_const_handle>> candidates;
  std::vector<double> area, perimeter;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded() || f->is_fictitious()) continue;
    index[f] = int(faces.size());
    faces.push_back(f);
    double a = 0, per = 0;
    std::vector<Arr::Halfedge_const_handle> es;
    auto add_ccb = [&](Arr::Ccb_halfedge_const_circulator c, bool outer) {
      auto e = c;
      do {
        const Vec2 p = to_vec(e->source()->point()), q = to_vec(e->target()->point());
        a += cross(p, q) / 2;
        if (e->twin()->face() != e->face()) per += length(q - p);  // not a line standing free in the face
        if (outer && e->twin()->face() != e->face() && length(q - p) > 1e-7) es.push_back(e);
      } while (++e != c);
    };
    add_ccb(f->outer_ccb(), true);
    for (auto h = f->inner_ccbs_begin(); h != f->inner_ccbs_end(); ++h) add_ccb(*h, false);
    std::sort(es.begin(), es.end(), [](Arr::Halfedge_const_handle x, Arr::Halfedge_const_handle y) {
      return length(to_vec(x->target()->point()) - to_vec(x->source()->point())) >
             length(to_vec(y->target()->point()) - to_vec(y->source()->point()));
    });
    if (es.size() > 6) es.resize(6);
    candidates.push_back(es);
    area.push_back(a);
    perimeter.push_back(per);
  }
  std::vector<std::optional<Vec2>> inside(faces.size());
  for (size_t round = 0; round < 6; ++round) {
    std::vector<Point> pts;
    std::vector<size_t> who;
    for (size_t i = 0; i < faces.size(); ++i) {
      if (inside[i] || round >= candidates[i].size()) continue;
      const Arr::Halfedge_const_handle e = candidates[i][round];
      const Vec2 p = to_vec(e->source()->point()), q = to_vec(e->target()->point());
      const double len = length(q - p);
      const double eps = std::min(0.002, 0.05 * std::sqrt(std::fabs(area[i])));
      const Vec2 m = 0.5 * (p + q), n{-(q.y - p.y) / len, (q.x - p.x) / len};
      const Vec2 c = m + eps * n;
      if (!std::isfinite(c.x) || !std::isfinite(c.y)) continue;
      pts.emplace_back(c.x, c.y);
      who.push_back(i);
    }
    if (pts.empty()) break;
    const std::vector<Arr::Face_const_handle> at = locate_all(arr, pts);
    for (size_t k = 0; k < pts.size(); ++k)
      if (at[k] != Arr::Face_const_handle() && at[k] == faces[who[k]]) inside[who[k]] = to_vec(pts[k]);
  }

  // Classify: -1 wall face, >= 0 the space's index.
  std::vector<int> cls(faces.size(), -1);
  out.faces = int(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    bool wall = !inside[i] || !(perimeter[i] > 0) || 2 * area[i] / perimeter[i] <= in.max_wall_width;
    bool hatched = false;
    if (inside[i])
      for (const auto& h : in.hatches) hatched = hatched || in_rings(*inside[i], h);
    if (hatched && !wall) ++out.hatched_faces;
    if (wall && !hatched && inside[i] && faces[i]->number_of_inner_ccbs() == 0) {
      // A gap face? Its boundary's length on each gap's closing lines.
      std::map<int, double> on_gap;
      auto e = faces[i]->outer_ccb();
      do {
        if (e->twin()->face() == e->face()) continue;
        const double len = length(to_vec(e->target()->point()) - to_vec(e->source()->point()));
        for (int d : e->curve().data())
          if (d >= 0) on_gap[d] += len;
      } while (++e != faces[i]->outer_ccb());
      int best = -1;
      for (auto [g, len] : on_gap)
        if (len >= in.gap_share * perimeter[i] && (best < 0 || len > on_gap[best])) best = g;
      if (best >= 0) {
        // Convex (exactly), its corners where the boundary turns.
        std::vector<Point> ring;
        e = faces[i]->outer_ccb();
        do ring.push_back(e->source()->point());
        while (++e != faces[i]->outer_ccb());
        std::vector<Point> corners;
        bool convex = true;
        for (size_t k = 0; k < ring.size(); ++k) {
          const Point& a = ring[(k + ring.size() - 1) % ring.size()];
          const Point& b = ring[k];
          const Point& c = ring[(k + 1) % ring.size()];
          const CGAL::Orientation o = CGAL::orientation(a, b, c);
          if (o == CGAL::RIGHT_TURN) convex = false;
          if (o == CGAL::LEFT_TURN) corners.push_back(b);
        }
        GapFace gf;
        for (const Point& p : corners) gf.poly.push_back(to_vec(p));
        gf.closes = best;
        // Convex in doubles too, as a plan's footprint must be (a sliver a few units in
        // the last place wide may turn the other way once rounded: it stays wall).
        if (convex && is_convex_ccw(gf.poly)) {
          cls[i] = -3 - int(out.gap_faces.size());
          out.gap_faces.push_back(std::move(gf));
          continue;
        }
      }
    }
    if (wall || hatched) {
      ++out.wall_faces;
      continue;
    }
    cls[i] = int(out.spaces.size());
    out.spaces.push_back({*inside[i], area[i]});
  }
  // >= 0: a space; -1: a wall face; -2: the outside; <= -3: gap face -3 - k.
  auto class_of = [&](Arr::Face_const_handle f) {
    if (f->is_unbounded()) return -2;
    return cls[size_t(index.at(f))];
  };

  // Sheets: edges with a space on at least one side and something else on the other,
  // and edges between a wall face and the outside (so that the wall face is enclosed).
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const int c1 = class_of(e->face()), c2 = class_of(e->twin()->face());
    if (c1 == c2 || (c1 == -1 && c2 == -1)) continue;
    Sheet s{to_vec(e->source()->point()), to_vec(e->target()->point()), -1, c1 >= 0 && c2 >= 0};
    const int gap_face = c1 <= -3 ? c1 : c2 <= -3 ? c2 : 0;
    if (gap_face < 0) {
      // Its jambs (beside a wall face) are wall; its other sides are the opening.
      if (c1 != -1 && c2 != -1) {
        s.closes = out.gap_faces[size_t(-3 - gap_face)].closes;
        s.beside_gap_face = true;
      }
    } else if (c1 >= 0 || c2 >= 0) {
      for (int d : e->curve().data()) s.closes = std::max(s.closes, d);  // on a door's or window's closing line
    }
    out.sheets.push_back(s);
  }

  std::vector<Point> probes;
  for (Vec2 p : in.probes) probes.emplace_back(finite(p) ? p.x : 1e300, finite(p) ? p.y : 1e300);
  const std::vector<Arr::Face_const_handle> at = locate_all(arr, probes);
  for (const Arr::Face_const_handle& f : at) {
    const int c = f == Arr::Face_const_handle() ? -1 : class_of(f);
    out.probe_space.push_back(c <= -3 ? -1 : c);  // a gap face counts as wall here
  }
  return out;
}

}  // namespace avenues
