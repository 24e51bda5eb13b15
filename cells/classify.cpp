// Avenues — pass 3 of build_cells: what each triangle is, band by band.
//
// The far box is cut into horizontal bands: each storey's floor-to-ceiling band, the
// slab above it, a plinth under a raised ground floor, and the sky up to the box's top.
// Within a band every triangle of the triangulation is solid or one class of free
// space: a room (a connected component of a storey's free triangles, walls of no
// thickness acting as barriers, named by the plan room whose label lies in it), a
// doorway (a strip of wall open from sill to head), a stairwell (a hole in a slab) or
// the outside. Plan mistakes found here (a label in a wall, a room open to the outside)
// are PlanErrors naming the room.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <span>
#include <tuple>

#include "cells/passes.h"

namespace avenues::detail {

namespace {


double triangle_area(const Triangulation& T, int t) {
  return std::fabs(signed_area({T.vert[size_t(T.tri[size_t(t)][0])], T.vert[size_t(T.tri[size_t(t)][1])],
                                T.vert[size_t(T.tri[size_t(t)][2])]}));
}

/// The triangle's least height over its sides [m]: how wide a strip it fills.
double triangle_width(const Triangulation& T, int t) {
  double longest = 0;
  for (int i = 0; i < 3; ++i) longest = std::max(longest, length(T.edge_to(t, i) - T.edge_from(t, i)));
  return longest > 0 ? 2 * triangle_area(T, t) / longest : 0;
}

/// Per storey, the triangles no wall of it covers that are a gap between its walls
/// (kGap): thinner than kGap, with every corner on a wall of the storey (a corner of a
/// triangle it covers, or an end of a wall of no thickness). A thin triangle in a room,
/// made by another storey's walls, has a corner away from this storey's walls and stays
/// free; so does one with two sides open to free space wider than kGap, unless its
/// longest side lies on a wall of no thickness (a wall ending a rounding short of such a
/// wall: the film lies along the wall, not across a doorway). Marks them in `gap` and
/// `covered`, and gives each the regions of the storey's walls within kGap of it
/// (`gap_regions`, its own covering, as it were): so a gap between two layers of a wall
/// is solid where they are, and a doorway where both are open. Returns how many
/// triangle-storeys it closed.
size_t close_gaps(const Outline& outline, const Triangulation& T, std::vector<std::vector<uint8_t>>& covered,
                  std::vector<std::vector<uint8_t>>& gap,
                  std::vector<std::map<int, std::vector<int32_t>>>& gap_regions) {
  const int n = T.size();
  std::vector<uint8_t> thin(size_t(n), 0);
  bool any = false;
  // (Not a triangle flat in doubles: distinct points of the exact triangulation rounded
  // together, which footprint_of reads as one point, not a gap.)
  for (int t = 0; t < n; ++t) {
    const double w = triangle_width(T, t);
    any |= (thin[size_t(t)] = w > 0 && w < kGap) != 0;
  }
  size_t closed = 0;
  gap.assign(covered.size(), std::vector<uint8_t>(size_t(n), 0));
  gap_regions.assign(covered.size(), {});
  if (!any) return 0;
  // The triangles at each corner.
  std::vector<int32_t> first_at(T.vert.size() + 1, 0), at_corner(3 * size_t(n));
  for (const auto& v : T.tri)
    for (int32_t c : v) ++first_at[size_t(c) + 1];
  for (size_t c = 0; c < T.vert.size(); ++c) first_at[c + 1] += first_at[c];
  {
    std::vector<int32_t> fill(first_at.begin(), first_at.end() - 1);
    for (int t = 0; t < n; ++t)
      for (int32_t c : T.tri[size_t(t)]) at_corner[size_t(fill[size_t(c)]++)] = t;
  }
  std::vector<uint8_t> on_wall(T.vert.size());
  for (size_t s = 0; s < covered.size(); ++s) {
    std::fill(on_wall.begin(), on_wall.end(), 0);
    for (int t = 0; t < n; ++t) {
      if (covered[s][size_t(t)])
        for (int32_t v : T.tri[size_t(t)]) on_wall[size_t(v)] = 1;
      for (int i = 0; i < 3; ++i)
        if (has_sheet_of_storey(outline, T, 3 * t + i, StoreyId(s))) {
          on_wall[size_t(T.tri[size_t(t)][size_t((i + 1) % 3)])] = 1;
          on_wall[size_t(T.tri[size_t(t)][size_t((i + 2) % 3)])] = 1;
        }
    }
    std::vector<uint8_t>& g = gap[s];
    for (int t = 0; t < n; ++t) {
      if (!thin[size_t(t)] || covered[s][size_t(t)]) continue;
      const auto& v = T.tri[size_t(t)];
      g[size_t(t)] = on_wall[size_t(v[0])] && on_wall[size_t(v[1])] && on_wall[size_t(v[2])];
    }
    // Not where two sides open onto free space: a film drawn across a doorway's face by
    // a corner beside it, not a gap (whose triangles open at most at its mouth).
    std::vector<int> open_sides;
    for (int t = 0; t < n; ++t) {
      if (!g[size_t(t)]) continue;
      int open = 0, longest = 0;
      bool on_sheet[3] = {false, false, false};
      for (int i = 0; i < 3; ++i) {
        const int32_t u = T.nbr[size_t(t)][size_t(i)];
        on_sheet[i] = has_sheet_of_storey(outline, T, 3 * t + i, StoreyId(s));
        const double len = length(T.edge_to(t, i) - T.edge_from(t, i));
        if (len > length(T.edge_to(t, longest) - T.edge_from(t, longest))) longest = i;
        open += !on_sheet[i] && !(u >= 0 && (covered[s][size_t(u)] || g[size_t(u)])) && len >= kGap;
      }
      if (open > 1 && !on_sheet[longest]) open_sides.push_back(t);
    }
    for (int t : open_sides) g[size_t(t)] = 0;
    // The walls beside each: of the storey's walls covering a triangle at one of its
    // corners, those within kGap of its middle (a jamb at a doorway's edge is further).
    auto& regions = gap_regions[s];
    for (int t = 0; t < n; ++t) {
      if (!g[size_t(t)]) continue;
      ++closed;
      const auto& v = T.tri[size_t(t)];
      const Vec2 mid = (1.0 / 3) * (T.vert[size_t(v[0])] + T.vert[size_t(v[1])] + T.vert[size_t(v[2])]);
      std::vector<int32_t>& mine = regions[t];
      for (int32_t corner : v)
        for (int32_t j = first_at[size_t(corner)]; j < first_at[size_t(corner) + 1]; ++j) {
          const int32_t u = at_corner[size_t(j)];
          if (!covered[s][size_t(u)] || g[size_t(u)]) continue;
          for (int32_t k = T.region_start[size_t(u)]; k < T.region_start[size_t(u) + 1]; ++k) {
            const int32_t r = T.region_items[size_t(k)];
            const Region& reg = outline.regions[size_t(r)];
            if (reg.storey != StoreyId(s) || reg.sheet) continue;
            double d = HUGE_VAL;
            for (size_t e = 0; e < reg.poly.size(); ++e)
              d = std::min(d, distance_to_segment(mid, reg.poly[e], reg.poly[(e + 1) % reg.poly.size()]));
            if (d < kGap) mine.push_back(r);
          }
        }
      for (int i = 0; i < 3; ++i)  // walls of no thickness along its sides
        for_each_sheet_of_storey(outline, T, 3 * t + i, StoreyId(s), [&](int32_t r) {
          const Region& reg = outline.regions[size_t(r)];
          if (distance_to_segment(mid, reg.poly[0], reg.poly[1]) < kGap) mine.push_back(r);
        });
      std::sort(mine.begin(), mine.end());
      mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    }
    for (int t = 0; t < n; ++t) covered[s][size_t(t)] |= g[size_t(t)];
  }
  return closed;
}

/// Names the spaces of storey s that no label point named by the rooms their bounding
/// walls of no thickness say lie on that side (Wall::left_room / right_room), each
/// space taking the room with the longest stretch of wall voting for it. Ties and
/// disagreements (an unclosed Doom sector bleeding into its neighbour) are warnings
/// naming both rooms and the area at stake; so are rooms left with no space, and spaces
/// that reach the far box although a wall claims them (area dropped when the outside is solid).
void name_by_wall_sides(const Plan& plan, const Outline& o, const Triangulation& T, StoreyId s,
                        const std::vector<int32_t>& comp, const std::vector<uint8_t>& outside_comp,
                        std::vector<RoomId>& room_of_comp, std::vector<std::string>& warnings) {
  bool any = false;
  for (const Room& r : plan.rooms) any |= r.storey == s && !r.label;
  if (!any) return;
  const size_t ncomp = outside_comp.size();
  std::vector<std::map<RoomId, double>> votes(ncomp);
  std::vector<double> area(ncomp, 0);
  for (int t = 0; t < T.size(); ++t) {
    const int32_t c = comp[size_t(t)];
    if (c < 0) continue;
    area[size_t(c)] += triangle_area(T, t);
    for (int i = 0; i < 3; ++i) {
      const int32_t h = 3 * t + i;
      const Vec2 a = T.edge_from(t, i), b = T.edge_to(t, i);
      for_each_sheet_of_storey(o, T, h, s, [&](int32_t r) {
        const Region& reg = o.regions[size_t(r)];
        const Wall& w = plan.walls[size_t(reg.wall)];
        // The triangle lies left of its counter-clockwise edge a -> b.
        const bool left = dot(b - a, reg.poly[1] - reg.poly[0]) > 0;
        const int room = left ? w.left_room : w.right_room;
        if (room >= 0 && !plan.rooms[size_t(room)].label) votes[size_t(c)][room] += length(b - a);
      });
    }
  }
  std::vector<double> got(plan.rooms.size(), 0);
  double dropped = 0;
  for (size_t c = 0; c < ncomp; ++c) {
    if (room_of_comp[c] >= 0 || votes[c].empty()) continue;
    auto best = std::max_element(votes[c].begin(), votes[c].end(),
                                 [](const auto& x, const auto& y) { return x.second < y.second; });
    char buf[64];
    if (outside_comp[c]) {
      if (plan.outside_solid) {
        std::snprintf(buf, sizeof buf, "%.2f", area[c]);
        warnings.push_back("room '" + plan.rooms[size_t(best->first)].name + "' (" +
                           plan.rooms[size_t(best->first)].where.str() + ") is not closed: " + buf +
                           " m² reaching the void around the map dropped");
        dropped += area[c];
      }
      continue;
    }
    if (votes[c].size() > 1) {
      std::string others;
      for (auto [r, len] : votes[c])
        if (r != best->first) others += (others.empty() ? "'" : ", '") + plan.rooms[size_t(r)].name + "'";
      std::snprintf(buf, sizeof buf, "%.2f", area[c]);
      warnings.push_back("a space of " + std::string(buf) + " m² is claimed by room '" +
                         plan.rooms[size_t(best->first)].name + "' and by " + others +
                         " (walls missing between them): given to '" + plan.rooms[size_t(best->first)].name + "'");
    }
    room_of_comp[c] = best->first;
    got[size_t(best->first)] += area[c];
  }
  for (size_t r = 0; r < plan.rooms.size(); ++r) {
    const Room& room = plan.rooms[r];
    if (room.storey != s || room.label || got[r] > 0) continue;
    warnings.push_back("room '" + room.name + "' (" + room.where.str() +
                       ") encloses no space of its own (its walls are missing or claimed by another room): dropped");
  }
  if (dropped > 0) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.2f", dropped);
    warnings.push_back("storey '" + plan.storeys[size_t(s)].name + "': " + buf + " m² of unclosed rooms dropped");
  }
}

}  // namespace

Classes classify(const Plan& plan, const Outline& outline, const Triangulation& T) {
  Classes C;
  const int n = T.size();
  const int S = int(plan.storeys.size());

  // --- bands, bottom to top; split at ground level (z = 0), below which the outside is earth.
  std::vector<Band> bands;
  const double e0 = plan.storeys.front().elevation;
  if (e0 > 0) bands.push_back({Band::Kind::Plinth, 0, e0, 0, true});
  for (int s = 0; s < S; ++s) {
    const Storey& st = plan.storeys[size_t(s)];
    bands.push_back({Band::Kind::Storey, st.elevation, st.elevation + st.height, s, true});
    double top = s + 1 < S ? plan.storeys[size_t(s) + 1].elevation : st.elevation + st.height + st.slab;
    // A slab thinner than kGap is a storey meant to meet the next: the storey reaches it.
    if (top > st.elevation + st.height + kGap) bands.push_back({Band::Kind::Slab, st.elevation + st.height, top, s, true});
    else if (top > st.elevation + st.height) bands.back().z1 = top;
  }
  bands.push_back({Band::Kind::Sky, bands.back().z1, outline.z_top, -1, true});
  for (Band b : bands) {
    // No ground to tell from air when the outside is solid (a Doom map's void): no split.
    // A band reaching less than kGap below or above the ground is not split there.
    if (b.z0 < -kGap && b.z1 > kGap && !plan.outside_solid) {
      Band lo = b, hi = b;
      lo.z1 = 0;
      hi.z0 = 0;
      lo.outside_free = false;
      C.bands.push_back(lo);
      C.bands.push_back(hi);
    } else {
      b.outside_free = b.z0 >= -kGap;
      C.bands.push_back(b);
    }
  }

  // --- per storey: rooms as connected components of the triangles no wall of the storey covers.
  // comp[s][t]: component id, -1 if covered by a wall region of s. Component 0 is the outside.
  std::vector<std::vector<int32_t>> comp(size_t(S), std::vector<int32_t>(size_t(n), -1));
  std::vector<std::vector<uint8_t>> covered(size_t(S), std::vector<uint8_t>(size_t(n), 0));
  for (int t = 0; t < n; ++t)
    for (int32_t k = T.region_start[size_t(t)]; k < T.region_start[size_t(t) + 1]; ++k)
      covered[size_t(outline.regions[size_t(T.region_items[size_t(k)])].storey)][size_t(t)] = 1;
  std::vector<std::vector<uint8_t>> gap;
  std::vector<std::map<int, std::vector<int32_t>>> gap_regions;
  if (const size_t closed = close_gaps(outline, T, covered, gap, gap_regions); closed > 0) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "free space thinner than %g mm between walls (walls drawn to meet that miss each other by a rounding) "
                  "closed in %zu place(s): the walls are joined across it",
                  kGap * 1e3, closed);
    C.warnings.push_back(buf);
  }

  // Named rooms first (RoomId = index in plan.rooms), then enclosed spaces nobody named.
  for (const Room& r : plan.rooms) C.rooms.push_back({r.name, r.storey, true, 0});
  std::vector<std::vector<RoomId>> room_of_comp(static_cast<size_t>(S));
  // Per storey and component: an enclosed space no room claims, which is solid
  // (Plan::unnamed_spaces_solid: a drawing's wall faces).
  std::vector<std::vector<uint8_t>> solid_comp(static_cast<size_t>(S));
  const bool unnamed_solid = plan.outside_solid || plan.unnamed_spaces_solid;
  std::vector<int32_t> stack;
  for (int s = 0; s < S; ++s) {
    auto& cs = comp[size_t(s)];
    std::vector<uint8_t> outside_comp;  // per component: touches the far box
    int ncomp = 0;
    for (int seed = 0; seed < n; ++seed) {
      if (covered[size_t(s)][size_t(seed)] || cs[size_t(seed)] >= 0) continue;
      bool touches = false;
      cs[size_t(seed)] = ncomp;
      stack.assign(1, seed);
      while (!stack.empty()) {
        int t = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
          int u = T.nbr[size_t(t)][size_t(i)];
          if (u < 0) { touches = true; continue; }
          if (covered[size_t(s)][size_t(u)] || cs[size_t(u)] >= 0) continue;
          if (has_sheet_of_storey(outline, T, 3 * t + i, s)) continue;
          cs[size_t(u)] = ncomp;
          stack.push_back(u);
        }
      }
      outside_comp.push_back(touches);
      ++ncomp;
    }
    auto& rc = room_of_comp[size_t(s)];
    rc.assign(size_t(ncomp), -1);
    for (int r = 0; r < int(plan.rooms.size()); ++r) {
      const Room& room = plan.rooms[size_t(r)];
      if (room.storey != s || !room.label) continue;
      int t = T.label_tri[size_t(r)];
      // A mistake: an error naming the room, or in a lenient (imported) plan a warning.
      auto mistake = [&](const std::string& what) {
        if (!plan.lenient) throw PlanError(room.where, what);
        C.warnings.push_back(room.where.str() + ": " + what + ": room dropped");
      };
      if (t < 0) { mistake("the label point of room '" + room.name + "' is outside the far box"); continue; }
      if (covered[size_t(s)][size_t(t)]) { mistake("the label point of room '" + room.name + "' is inside a wall"); continue; }
      int c = cs[size_t(t)];
      if (outside_comp[size_t(c)]) {
        mistake("room '" + room.name + "' is not enclosed by walls: its label point reaches the outside");
        continue;
      }
      if (rc[size_t(c)] >= 0) {
        const std::string what = "rooms '" + plan.rooms[size_t(rc[size_t(c)])].name + "' and '" + room.name +
                                 "' label the same enclosed space";
        if (!plan.lenient) throw PlanError(room.where, what);
        C.warnings.push_back(room.where.str() + ": " + what + " (no wall between them): one room, both names");
        C.rooms[size_t(rc[size_t(c)])].name += " + " + room.name;
        continue;
      }
      rc[size_t(c)] = r;
    }
    name_by_wall_sides(plan, outline, T, s, cs, outside_comp, rc, C.warnings);
    int unnamed = 0;
    for (int c = 0; c < ncomp; ++c) {
      if (outside_comp[size_t(c)] || rc[size_t(c)] >= 0 || unnamed_solid) continue;
      rc[size_t(c)] = RoomId(C.rooms.size());
      C.rooms.push_back({"space " + std::to_string(++unnamed) + " of " + plan.storeys[size_t(s)].name, s, false, 0});
    }
    // With a solid outside, spaces that reach the far box are solid even if named.
    if (plan.outside_solid)
      for (int c = 0; c < ncomp; ++c)
        if (outside_comp[size_t(c)]) rc[size_t(c)] = -1;
    solid_comp[size_t(s)].assign(size_t(ncomp), 0);
    if (plan.unnamed_spaces_solid && !plan.outside_solid)
      for (int c = 0; c < ncomp; ++c) solid_comp[size_t(s)][size_t(c)] = !outside_comp[size_t(c)] && rc[size_t(c)] < 0;
  }

  // --- classes. Shared ones first.
  auto add_class = [&](SpaceClass c) {
    C.classes.push_back(std::move(c));
    return int32_t(C.classes.size() - 1);
  };
  SpaceClass outside_c;
  outside_c.kind = CellKind::Outside;
  outside_c.portal = PortalKind::Open;
  const int32_t kOutside = add_class(outside_c);
  SpaceClass sky_c;
  sky_c.kind = CellKind::Sky;
  sky_c.portal = PortalKind::Open;
  const int32_t kSky = add_class(sky_c);
  std::vector<int32_t> room_class(C.rooms.size());
  for (size_t r = 0; r < C.rooms.size(); ++r) {
    SpaceClass c;
    c.kind = CellKind::Room;
    c.room = RoomId(r);
    // A room with its own floor or ceiling (a Doom sector) is free over those heights
    // only, like a doorway; a room open to the sky is free up to its storey's top.
    if (r < plan.rooms.size()) {
      const Room& room = plan.rooms[r];
      const Storey& st = plan.storeys[size_t(room.storey)];
      const double lo = st.elevation + room.floor_at;
      const double hi = room.sky || room.ceiling_at < 0 ? st.elevation + st.height : st.elevation + room.ceiling_at;
      if (room.floor_at > 0 || (room.ceiling_at >= 0 && !room.sky)) c.open = {{lo, hi}};
      if (hi <= lo + 1e-9) {  // a closed Doom door, a lift at its top: no free space at all
        room_class[r] = -1;
        continue;
      }
    }
    room_class[r] = add_class(c);
  }
  std::vector<int32_t> hole_class(plan.floor_openings.size());
  for (size_t h = 0; h < plan.floor_openings.size(); ++h) {
    SpaceClass c;
    c.kind = CellKind::Stairwell;
    c.opening = int(h);
    c.portal = PortalKind::Stairwell;
    hole_class[h] = add_class(c);
  }
  // Doorway classes, keyed by the set of wall regions covering a triangle.
  std::map<std::vector<int32_t>, int32_t> region_class;
  // Doorways alike in all but the walls they are cut through (two walls lying on one line,
  // each stepped along a slope where it overlaps the other) are one class, so that their
  // triangles merge into one cell where the union is convex. (SpaceClass::wall serves the
  // choice of opening below and nothing after.)
  // A sloped class's last interval is keyed from 0: its lower bound is the plane's.
  std::map<std::tuple<int, PortalKind, Intervals, std::optional<Slope>>, int32_t> doorway_class;

  C.of.assign(C.bands.size(), std::vector<int32_t>(size_t(n), -1));
  C.wall_of.assign(C.bands.size() * size_t(n), -1);
  std::vector<int32_t> keys;
  for (size_t b = 0; b < C.bands.size(); ++b) {
    const Band& band = C.bands[b];
    auto& of = C.of[b];
    const int32_t outside =
        band.outside_free && !plan.outside_solid ? (band.kind == Band::Kind::Sky ? kSky : kOutside) : -1;
    // Above a room open to the sky (outside_solid plans): the sky, up to the box's top.
    auto sky_over = [&](int t) {
      if (!plan.outside_solid || band.kind == Band::Kind::Storey || band.kind == Band::Kind::Plinth) return false;
      for (int st = 0; st < S; ++st) {
        if (plan.storeys[size_t(st)].elevation + plan.storeys[size_t(st)].height > band.z0 + 1e-9) continue;
        if (covered[size_t(st)][size_t(t)]) continue;
        RoomId r = room_of_comp[size_t(st)][size_t(comp[size_t(st)][size_t(t)])];
        if (r >= 0 && r < RoomId(plan.rooms.size()) && plan.rooms[size_t(r)].sky) return true;
      }
      return false;
    };
    auto footprint = [&](int s, int t) {
      if (s < 0 || s >= S) return false;
      if (covered[size_t(s)][size_t(t)]) return true;
      const int32_t c = comp[size_t(s)][size_t(t)];
      return c >= 0 && (room_of_comp[size_t(s)][size_t(c)] >= 0 || solid_comp[size_t(s)][size_t(c)]);
    };
    for (int t = 0; t < n; ++t) {
      switch (band.kind) {
        case Band::Kind::Sky: of[size_t(t)] = sky_over(t) ? kSky : outside; break;
        case Band::Kind::Plinth: of[size_t(t)] = footprint(0, t) ? -1 : outside; break;
        case Band::Kind::Slab: {
          const int s = band.storey;
          if (sky_over(t)) { of[size_t(t)] = kSky; break; }
          if (!footprint(s, t) && !footprint(s + 1, t)) { of[size_t(t)] = outside; break; }
          of[size_t(t)] = -1;
          for (int32_t k = T.hole_start[size_t(t)]; k < T.hole_start[size_t(t) + 1]; ++k) {
            int h = T.hole_items[size_t(k)];
            if (plan.floor_openings[size_t(h)].storey == s + 1) of[size_t(t)] = hole_class[size_t(h)];
          }
          break;
        }
        case Band::Kind::Storey: {
          const int s = band.storey;
          if (!covered[size_t(s)][size_t(t)]) {
            const int32_t c = comp[size_t(s)][size_t(t)];
            RoomId r = room_of_comp[size_t(s)][size_t(c)];
            of[size_t(t)] = r >= 0 ? room_class[size_t(r)] : solid_comp[size_t(s)][size_t(c)] ? -1 : outside;
            break;
          }
          // Under wall regions of this storey: free where all of them are open.
          // (A gap closed between walls: under the walls beside it.)
          keys.clear();
          Intervals open{{band.z0, band.z1}};
          const bool closed_gap = gap[size_t(s)][size_t(t)];
          const std::span<const int32_t> regions =
              closed_gap ? std::span<const int32_t>(gap_regions[size_t(s)][t])
                         : std::span<const int32_t>(T.region_items)
                               .subspan(size_t(T.region_start[size_t(t)]),
                                        size_t(T.region_start[size_t(t) + 1] - T.region_start[size_t(t)]));
          if (closed_gap && regions.empty()) open.clear();  // (a gap walled in by gaps alone)
          // A sloped wall's interval from its top up stands for the plane by its height at
          // the triangle's middle; the strips are cut so that no other height lies between
          // the plane's heights over the triangle, so the intervals come out as they would
          // at every point of it, and the one that starts at such a height is sloped.
          const auto& tv = T.tri[size_t(t)];
          const Vec2 centre = (1.0 / 3) * (T.vert[size_t(tv[0])] + T.vert[size_t(tv[1])] + T.vert[size_t(tv[2])]);
          std::optional<Slope> top;
          std::vector<std::pair<double, const Slope*>> stand_ins;
          for (const int32_t r : regions) {
            const Region& reg = outline.regions[size_t(r)];
            if (reg.storey != s) continue;
            keys.push_back(r);
            if (reg.top && !reg.open.empty()) {
              Intervals own = reg.open;
              own.back().first = std::clamp((*reg.top)(centre), own.back().first, own.back().second);
              stand_ins.push_back({own.back().first, &*reg.top});
              open = intersect(open, own);
            } else {
              open = intersect(open, reg.open);
            }
            if (C.wall_of[b * size_t(n) + size_t(t)] < 0) C.wall_of[b * size_t(n) + size_t(t)] = reg.wall;
          }
          // Open over less than kGap (a sill a rounding above the wall's top): not open.
          open.erase(std::remove_if(open.begin(), open.end(), [](auto iv) { return iv.second - iv.first < kGap; }),
                     open.end());
          if (open.empty()) { of[size_t(t)] = -1; break; }
          for (auto [z, plane] : stand_ins)
            if (open.back().first == z) top = *plane;
          bool levelled = false;  // a sloped gap stood level (below)
          if (top && closed_gap) {
            levelled = true;
            // A gap closed between walls is no wall's region, so nothing cut it where the
            // slope passes a height: it may reach past where its plane meets the ceiling. It
            // stands level at the plane's highest over it (the gap is thinner than kGap).
            double hi = -HUGE_VAL;
            for (int32_t v : tv) hi = std::max(hi, (*top)(T.vert[size_t(v)]));
            open.back().first = std::clamp(hi, open.back().first, open.back().second);
            top.reset();
            if (open.back().second - open.back().first < kGap) open.pop_back();
            if (open.empty()) { of[size_t(t)] = -1; break; }
          }
          double least = HUGE_VAL;  // the sloped top's least height over the triangle
          if (top) {
            for (int32_t v : tv) least = std::min(least, (*top)(T.vert[size_t(v)]));
            least = std::max(least, open.size() > 1 ? open[open.size() - 2].second : band.z0);
            open.back().first = 0;  // keyed from 0 (below)
          }
          // (Where an overlap leaves the top level, the same walls key another class.)
          std::vector<int32_t> key = keys;
          if (top) key.push_back(-1);
          if (levelled) {  // the same walls key one class per level
            uint64_t bits;
            std::memcpy(&bits, &open.back().first, sizeof bits);
            key.insert(key.end(), {-2, int32_t(bits >> 32), int32_t(bits & 0xffffffffu)});
          }
          auto it = region_class.find(key);
          if (it == region_class.end()) {
            SpaceClass c;
            c.kind = CellKind::Doorway;
            c.open = open;
            c.portal = PortalKind::Gap;
            // Where several walls' openings overlap (a door under a bulkhead's gap), the most
            // particular kind names the doorway: a door, then a window, a hatch, a gap.
            auto rank = [](OpeningKind k) {
              return k == OpeningKind::Door ? 3 : k == OpeningKind::Window ? 2 : k == OpeningKind::Hatch ? 1 : 0;
            };
            int best = -1;
            for (int32_t r : keys) {
              const Region& reg = outline.regions[size_t(r)];
              if (best < 0) c.wall = reg.wall;
              if (reg.opening < 0) continue;
              const OpeningKind k = plan.walls[size_t(reg.wall)].openings[size_t(reg.opening)].kind;
              if (rank(k) <= best) continue;
              best = rank(k);
              c.wall = reg.wall;
              c.opening = opening_id(outline, reg.wall, reg.opening);
              c.portal = k == OpeningKind::Door     ? PortalKind::Door
                         : k == OpeningKind::Window ? PortalKind::Window
                         : k == OpeningKind::Hatch  ? PortalKind::Hatch
                                                    : PortalKind::Gap;
            }
            c.top = top;
            auto [alike, fresh] = doorway_class.try_emplace({c.opening, c.portal, c.open, c.top}, -1);
            if (fresh) {
              if (c.top) c.open.back().first = HUGE_VAL;  // the least over its triangles, below
              alike->second = add_class(c);
            }
            it = region_class.emplace(key, alike->second).first;
          }
          of[size_t(t)] = it->second;
          if (top) {
            Intervals& iv = C.classes[size_t(it->second)].open;
            iv.back().first = std::min(iv.back().first, least);
          }
          break;
        }
      }
    }
  }
  return C;
}

}  // namespace avenues::detail
