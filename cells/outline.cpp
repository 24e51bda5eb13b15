// Avenues — walls as convex outlines (see outline.h).
#include "cells/outline.h"

#include <algorithm>
#include <cmath>

namespace avenues::detail {

Intervals unite(Intervals a) {
  std::sort(a.begin(), a.end());
  Intervals out;
  for (auto iv : a) {
    if (iv.second <= iv.first) continue;
    if (!out.empty() && iv.first <= out.back().second)
      out.back().second = std::max(out.back().second, iv.second);
    else
      out.push_back(iv);
  }
  return out;
}

Intervals intersect(const Intervals& a, const Intervals& b) {
  Intervals out;
  for (auto x : a)
    for (auto y : b) {
      double lo = std::max(x.first, y.first), hi = std::min(x.second, y.second);
      if (hi > lo) out.push_back({lo, hi});
    }
  return unite(out);
}

int opening_id(const Outline& outline, int wall, int opening) { return outline.first_opening[size_t(wall)] + opening; }

namespace {

Vec2 perp(Vec2 d) { return {-d.y, d.x}; }
Vec2 unit(Vec2 d) { return (1.0 / length(d)) * d; }

/// Intersection of lines p + s·d and q + t·e; nullopt when (nearly) parallel.
std::optional<Vec2> meet(Vec2 p, Vec2 d, Vec2 q, Vec2 e) {
  double den = cross(d, e);
  if (std::fabs(den) < 1e-12 * length(d) * length(e)) return std::nullopt;
  return p + (cross(q - p, e) / den) * d;
}

/// Keeps the part of convex polygon `poly` where dot(p - o, n) >= 0 (Sutherland–Hodgman).
std::vector<Vec2> clip(const std::vector<Vec2>& poly, Vec2 o, Vec2 n) {
  std::vector<Vec2> out;
  for (size_t i = 0; i < poly.size(); ++i) {
    Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    double da = dot(a - o, n), db = dot(b - o, n);
    if (da >= 0) out.push_back(a);
    if ((da > 0 && db < 0) || (da < 0 && db > 0)) out.push_back(a + (da / (da - db)) * (b - a));
  }
  // Drop repeated points the clip may leave at a vertex on the line.
  std::vector<Vec2> clean;
  for (auto p : out)
    if (clean.empty() || !(p == clean.back())) clean.push_back(p);
  while (clean.size() > 1 && clean.front() == clean.back()) clean.pop_back();
  return clean;
}

/// Distance from p to segment ab.
double distance(Vec2 p, Vec2 a, Vec2 b) {
  Vec2 d = b - a;
  double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
  return length(p - (a + t * d));
}

/// Cuts every convex polygon of `pieces` where the linear function f(p) = c + dot(g, p)
/// changes sign inside it, into its parts with f >= 0 and f <= 0.
void split_where(std::vector<std::vector<Vec2>>& pieces, double c, Vec2 g) {
  const double gg = dot(g, g);
  if (!(gg > 1e-24)) return;
  std::vector<std::vector<Vec2>> out;
  for (auto& poly : pieces) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (Vec2 p : poly) lo = std::min(lo, c + dot(g, p)), hi = std::max(hi, c + dot(g, p));
    const double tol = 1e-9 * std::sqrt(gg);  // a nanometre of plan: nothing built is thinner
    if (!(lo < -tol && hi > tol)) {
      out.push_back(std::move(poly));
      continue;
    }
    const Vec2 o = (-c / gg) * g;  // a point where f = 0
    for (Vec2 n : {g, -1.0 * g}) {
      std::vector<Vec2> part = clip(poly, o, n);
      if (part.size() >= 3 && signed_area(part) > 1e-18) out.push_back(std::move(part));
    }
  }
  pieces.swap(out);
}

/// Regions over sloped walls (Region::top) cut where the wall's top passes a height that
/// matters: the floor and ceiling of its storey, the sill and head of its own opening, and
/// every height at which a wall overlapping it opens or closes; and where it passes the top
/// of another sloped wall it overlaps. Each part then says exactly what it is open over:
/// nothing where the top is above the ceiling, all the storey where it is below the floor,
/// else its opening's heights and, from the top up, the sloped interval (or one interval
/// from the sill up where the opening reaches the top).
void settle_slopes(Outline& out, const Plan& plan) {
  bool any = false;
  for (const Region& r : out.regions) any |= r.top.has_value();
  if (!any) return;
  std::vector<Box3> box(out.regions.size());  // in plan (z = 0)
  for (size_t i = 0; i < out.regions.size(); ++i)
    for (Vec2 p : out.regions[i].poly) box[i].add({p.x, p.y, 0});
  std::vector<Region> settled;
  settled.reserve(out.regions.size());
  for (size_t i = 0; i < out.regions.size(); ++i) {
    const Region& r = out.regions[i];
    if (!r.top) {
      settled.push_back(r);
      continue;
    }
    const Slope top = *r.top;
    const Storey& st = plan.storeys[size_t(r.storey)];
    const double floor = st.elevation, ceiling = st.elevation + st.height;
    std::vector<double> heights{floor, ceiling};
    for (auto [a, b] : r.open) heights.push_back(a), heights.push_back(b);  // its opening's sill and head
    std::vector<Slope> others;
    for (size_t j = 0; j < out.regions.size(); ++j) {
      const Region& q = out.regions[j];
      if (j == i || q.storey != r.storey || !box[j].meets(box[i], 1e-9)) continue;
      for (size_t k = 0; k < q.open.size(); ++k) {
        if (!(q.top && k + 1 == q.open.size())) heights.push_back(q.open[k].first);  // a sloped bound is no height
        heights.push_back(q.open[k].second);
      }
      if (q.top && !(*q.top == top)) others.push_back(*q.top);
    }
    std::vector<std::vector<Vec2>> pieces{r.poly};
    for (double h : heights) split_where(pieces, top.z0 - h - dot(top.grad, top.at), top.grad);
    for (const Slope& o : others)
      split_where(pieces, top.z0 - dot(top.grad, top.at) - (o.z0 - dot(o.grad, o.at)), top.grad - o.grad);
    for (auto& poly : pieces) {
      Region part = r;
      part.poly = std::move(poly);
      double lo = HUGE_VAL, hi = -HUGE_VAL;
      Vec2 mid{0, 0};
      for (Vec2 p : part.poly) lo = std::min(lo, top(p)), hi = std::max(hi, top(p)), mid = mid + p;
      mid = (1.0 / double(part.poly.size())) * mid;
      constexpr double tol = 1e-9;
      part.top.reset();
      if (hi <= floor + tol) {
        part.open.push_back({floor, ceiling});  // the top below the floor: no wall here
      } else if (lo < ceiling - tol) {
        // The sloped interval, stood for by its height at the part's middle while it is
        // united with the opening's: it stays sloped unless the opening reaches over it.
        const double at_mid = std::clamp(top(mid), floor, ceiling);
        part.open.push_back({at_mid, ceiling});
        part.open = unite(part.open);
        if (!part.open.empty() && part.open.back().first == at_mid) {
          // (Not united again: the opening's head may touch the top at a corner.)
          part.open.back().first = std::max(lo, floor);
          part.top = top;
        }
      } else {
        part.open = unite(part.open);
      }
      settled.push_back(std::move(part));
    }
  }
  out.regions.swap(settled);
}

}  // namespace

Outline make_outline(const Plan& plan) {
  Outline out;
  int openings = 0;  // (a running count: summing the walls before each was quadratic in walls)
  for (const Wall& w : plan.walls) {
    out.first_opening.push_back(openings);
    openings += int(w.openings.size());
  }
  // Jones's "large opaque box surrounding the objects": the plan's extent plus a margin.
  Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  auto grow = [&](Vec2 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  };
  for (const Wall& w : plan.walls) {
    for (Vec2 p : w.centre) grow(p);
    for (Vec2 p : w.footprint) grow(p);
  }
  const double m = plan.far_margin;
  double top = 0, bottom = 0;
  for (const Storey& s : plan.storeys) {
    top = std::max(top, s.elevation + s.height + s.slab);
    bottom = std::min(bottom, s.elevation);
  }
  out.lo = {lo.x - m, lo.y - m};
  out.hi = {hi.x + m, hi.y + m};
  out.z_bottom = bottom;
  out.z_top = top + m;

  for (int wi = 0; wi < int(plan.walls.size()); ++wi) {
    const Wall& w = plan.walls[size_t(wi)];
    const Storey& st = plan.storeys[size_t(w.storey)];
    const double floor = st.elevation, ceiling = st.elevation + st.height;
    const auto& c = w.centre;
    const size_t nseg = c.size() - 1;
    const bool closed = c.size() > 2 && c.front() == c.back();
    const double h = w.thickness / 2;
    // A sloped wall's top is a plane over each segment (settle_slopes cuts its regions).
    const bool sloped = h > 0 && w.sloped();
    // The top's straight pieces along the centre line: from brk[k] to brk[k + 1] it runs
    // from top_z[k] to top_z[k + 1] above the floor (Wall::top_bends).
    std::vector<double> brk{0}, top_z{w.height};
    if (sloped) {
      for (Vec2 b : w.top_bends) brk.push_back(b.x), top_z.push_back(b.y);
      brk.push_back(w.length());
      top_z.push_back(w.height_at_end);
    }
    // A low wall is open from its top to the ceiling, along its whole length.
    Intervals always;
    if (!sloped && w.height >= 0 && w.height < st.height) always.push_back({floor + w.height, ceiling});

    // Does a wall end touch another wall of the storey? Then cap it square by h so
    // that L and T junctions of separate walls close (the cap stays inside the other wall).
    // Not where the other wall only carries on in the same line from this very point (the
    // steps of a sloped wall, a low wall continuing a high one): their square ends meet
    // flush, and a cap would lay this wall's height over the other's for h.
    auto carries_on = [&](const Wall& o, Vec2 p, Vec2 away) {  // away: the direction leaving this wall at p
      const auto& oc = o.centre;
      if (oc.size() < 2 || !o.footprint.empty()) return false;
      for (int e = 0; e < 2; ++e) {
        const Vec2 q = e == 0 ? oc.front() : oc.back(), next = e == 0 ? oc[1] : oc[oc.size() - 2];
        if (length(q - p) > 1e-9) continue;
        const Vec2 d = unit(next - q);
        if (std::fabs(cross(d, away)) <= 1e-9 && dot(d, away) > 0) return true;
      }
      return false;
    };
    auto touches_other = [&](Vec2 p, Vec2 away) {
      for (int oi = 0; oi < int(plan.walls.size()); ++oi) {
        const Wall& o = plan.walls[size_t(oi)];
        if (oi == wi || o.storey != w.storey || carries_on(o, p, away)) continue;
        for (size_t k = 0; k + 1 < o.centre.size(); ++k)
          if (distance(p, o.centre[k], o.centre[k + 1]) <= o.thickness / 2 + 1e-9) return true;
      }
      return false;
    };

    // End lines of each segment: point + direction along which the segment's quad is cut.
    // Mitred at joints (both quads share the mitre line exactly), square at free ends;
    // a joint sharper than the mitre limit is bevelled with a filler triangle.
    struct Cut { Vec2 left, right; };
    std::vector<Cut> start(nseg), end(nseg);
    std::vector<Vec2> dir(nseg), nrm(nseg);
    for (size_t i = 0; i < nseg; ++i) {
      dir[i] = unit(c[i + 1] - c[i]);
      nrm[i] = perp(dir[i]);
    }
    auto square = [&](size_t i, Vec2 p) { return Cut{p + h * nrm[i], p - h * nrm[i]}; };
    for (size_t i = 0; i < nseg; ++i) {
      start[i] = square(i, c[i]);
      end[i] = square(i, c[i + 1]);
    }
    std::vector<std::vector<Vec2>> fillers;
    std::vector<size_t> filler_segment;  // the segment whose top (at its end) a filler takes
    auto join = [&](size_t a, size_t b) {  // segment a ends where b starts
      Vec2 p = c[a + 1];
      double cosang = dot(dir[a], dir[b]);
      auto l = meet(p + h * nrm[a], dir[a], p + h * nrm[b], dir[b]);
      auto r = meet(p - h * nrm[a], dir[a], p - h * nrm[b], dir[b]);
      const double limit = 4 * h;  // mitre limit, as in SVG's stroke-miterlimit
      if (h > 0 && l && r && length(*l - p) <= limit && length(*r - p) <= limit) {
        end[a] = {*l, *r};
        start[b] = {*l, *r};
      } else if (h > 0 && cosang < 1 - 1e-12) {
        // Bevel: square ends plus the triangle closing the outer side of the turn.
        bool left_turn = cross(dir[a], dir[b]) > 0;
        Vec2 o1 = left_turn ? end[a].right : end[a].left;
        Vec2 o2 = left_turn ? start[b].right : start[b].left;
        std::vector<Vec2> tri{p, o1, o2};
        if (signed_area(tri) < 0) std::reverse(tri.begin(), tri.end());
        if (std::fabs(signed_area(tri)) > 0) fillers.push_back(tri), filler_segment.push_back(a);
      }
    };
    for (size_t i = 0; i + 1 < nseg; ++i) join(i, i + 1);
    if (closed && nseg > 2) join(nseg - 1, 0);
    if (!closed && h > 0 && w.footprint.empty()) {
      if (touches_other(c.front(), -1.0 * dir[0])) start[0] = square(0, c.front() - h * dir[0]);
      if (touches_other(c.back(), dir[nseg - 1])) end[nseg - 1] = square(nseg - 1, c.back() + h * dir[nseg - 1]);
    }

    // The piece of the top over the point `at` along the centre line (a bend belongs to the
    // piece after it): its plane over segment i, which starts `along_i` along, or none where
    // it is level (then the wall is open from that height up, as a low wall is).
    struct TopPiece { std::optional<Slope> slope; double level = 0; };
    auto top_piece = [&](size_t i, double along_i, double at) {
      size_t k = 0;
      while (k + 2 < brk.size() && brk[k + 1] <= at) ++k;
      const double rise = (top_z[k + 1] - top_z[k]) / (brk[k + 1] - brk[k]);
      TopPiece piece;
      if (rise == 0) piece.level = top_z[k];
      else piece.slope = Slope{c[i], rise * dir[i], floor + top_z[k] + rise * (along_i - brk[k])};
      return piece;
    };
    auto put_top = [&](Region& r, const TopPiece& piece) {
      if (piece.slope) r.top = piece.slope;
      else if (piece.level < st.height) r.open.push_back({floor + piece.level, ceiling});
    };
    std::vector<double> seg_start(nseg + 1, 0);  // distance along the centre line to each segment's start
    for (size_t i = 0; i < nseg; ++i) seg_start[i + 1] = seg_start[i] + length(c[i + 1] - c[i]);
    for (size_t i = 0; i < nseg; ++i) {
      const double len = length(c[i + 1] - c[i]), along = seg_start[i];
      // Strips of this segment along s in [0, len]: solid between openings.
      struct Strip { double s0, s1; int opening; };
      std::vector<Strip> strips;
      double s = 0;
      std::vector<int> here;
      for (int oi = 0; oi < int(w.openings.size()); ++oi) {
        double a = w.openings[size_t(oi)].at - along;
        if (a >= -1e-9 && a < len - 1e-9) here.push_back(oi);  // one starting at the segment's end belongs to the next
      }
      std::sort(here.begin(), here.end(), [&](int x, int y) {
        return w.openings[size_t(x)].at < w.openings[size_t(y)].at;
      });
      for (int oi : here) {
        const Opening& o = w.openings[size_t(oi)];
        double a = std::max(0.0, o.at - along), b = std::min(len, a + o.width);
        if (a < 1e-9) a = 0;          // at the segment's start: its mitre, not a clip a hair past it
        if (std::fabs(a - s) < 1e-9) a = s;  // touching the opening before (strips of one arched window)
        if (b > len - 1e-9) b = len;  // likewise at its end
        if (a > s) strips.push_back({s, a, -1});
        strips.push_back({a, b, oi});
        s = b;
      }
      if (s < len) strips.push_back({s, len, -1});
      // A sloped top's bends cut the strips they fall in: each part lies under one plane.
      for (size_t k = 1; sloped && k + 1 < brk.size(); ++k) {
        const double b = brk[k] - along;
        if (b <= 1e-9 || b >= len - 1e-9) continue;
        for (size_t j = 0; j < strips.size(); ++j)
          if (strips[j].s0 < b && b < strips[j].s1) {
            strips.insert(strips.begin() + std::ptrdiff_t(j) + 1, {b, strips[j].s1, strips[j].opening});
            strips[j].s1 = b;
            break;
          }
      }

      // A wall with a footprint of its own (one segment) stands on it instead of its quad.
      std::vector<Vec2> quad{start[i].right, end[i].right, end[i].left, start[i].left};
      if (!w.footprint.empty() && nseg == 1) quad = w.footprint;
      for (const Strip& sp : strips) {
        Region r;
        r.storey = w.storey;
        r.wall = wi;
        r.opening = sp.opening;
        r.open = always;
        if (sp.opening >= 0) {
          const Opening& o = w.openings[size_t(sp.opening)];
          r.open.push_back({floor + o.sill, floor + o.head});
        }
        if (sloped) put_top(r, top_piece(i, along, along + 0.5 * (sp.s0 + sp.s1)));
        r.open = unite(r.open);
        // At the segment's ends, its very corners (c[i] + len * dir[i] is not c[i + 1] in doubles).
        const Vec2 a = sp.s0 > 0 ? c[i] + sp.s0 * dir[i] : c[i], b = sp.s1 < len ? c[i] + sp.s1 * dir[i] : c[i + 1];
        if (h == 0) {
          r.sheet = true;
          r.poly = {a, b};
        } else {
          r.poly = quad;
          if (sp.s0 > 0) r.poly = clip(r.poly, a, dir[i]);
          if (sp.s1 < len) r.poly = clip(r.poly, b, -1.0 * dir[i]);
          if (r.poly.size() < 3 || signed_area(r.poly) <= 0) continue;
        }
        out.regions.push_back(std::move(r));
      }
    }
    for (size_t k = 0; k < fillers.size(); ++k) {
      Region r;
      r.storey = w.storey;
      r.wall = wi;
      r.poly = fillers[k];
      r.open = always;
      if (sloped) {
        // The top at the segment's end: the last piece of it before the joint.
        const size_t a = filler_segment[k];
        const double joint = seg_start[a + 1];
        size_t piece = 0;
        while (piece + 2 < brk.size() && brk[piece + 1] < joint) ++piece;
        put_top(r, top_piece(a, seg_start[a], 0.5 * (std::max(brk[piece], seg_start[a]) + joint)));
      }
      r.open = unite(r.open);
      out.regions.push_back(std::move(r));
    }
  }
  settle_slopes(out, plan);
  for (const FloorOpening& f : plan.floor_openings) out.holes.push_back(f.outline);
  // Snap every outline vertex to the nearest nanometre (a decimal grid, coarser only
  // where a double cannot hold nanometres, beyond 4,500 km): points meant to coincide
  // (a door jamb computed along one wall, the corner of another wall computed from its
  // own centre line) differ in their last bits, and the exact triangulation would keep
  // them apart as slivers. A decimal grid maps a coordinate typed with up to nine
  // decimals to the very double the reader parsed, so the eye placed "exactly on the
  // wall face" at x = 3.9 still is, for the exact predicates downstream.
  auto snap1 = [](double x) {
    double scale = 1e9;
    while (scale > 1 && std::fabs(x) * scale >= 4e15) scale /= 10;
    return std::nearbyint(x * scale) / scale;
  };
  auto snap = [&](Vec2& v) { v = {snap1(v.x), snap1(v.y)}; };
  for (Region& r : out.regions) {
    for (Vec2& v : r.poly) snap(v);
    // Snapping may merge neighbouring vertices of a tiny strip: drop repeats, and strips left flat.
    std::vector<Vec2> clean;
    for (Vec2 v : r.poly)
      if (clean.empty() || !(v == clean.back())) clean.push_back(v);
    while (clean.size() > 1 && clean.front() == clean.back()) clean.pop_back();
    r.poly = std::move(clean);
  }
  out.regions.erase(std::remove_if(out.regions.begin(), out.regions.end(),
                                   [](const Region& r) {
                                     return r.sheet ? r.poly.size() < 2 : (r.poly.size() < 3 || signed_area(r.poly) <= 0);
                                   }),
                    out.regions.end());
  for (auto& h : out.holes)
    for (Vec2& v : h) snap(v);
  return out;
}

}  // namespace avenues::detail
