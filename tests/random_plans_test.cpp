// Property tests on random plans (issue 8, item 3): random walls — axis-aligned and
// oblique, straight and curved, of random thickness including none, some low, some with a
// sloped top — with random doors,
// windows and hatches in them, a few room labels where a label clearly stands in free
// space, on a third of the plans an upper storey (its own walls over the ground's
// perimeter or part of it, one or two stairwells in its floor), and random eyes in the
// free cells, each view checked against brute-force rays (tests/ray_oracle.h) in the
// double and exact kernels.
//
// What must hold, for every plan:
//   - the plan text reads (the generator keeps to the reader's rules), and build_cells
//     gives a valid complex (cells_are_valid) or a PlanError naming an element — never a
//     crash, a logic_error or any other exception;
//   - every eye's visible set, in Kernel::Double and Kernel::Exact, misses no cell a ray
//     crosses and holds no avenue the rays never enter (check_visible_set).
// Each plan comes from one seed through a generator that uses only the raw output of
// std::mt19937 (whose sequence the standard fixes), so a seed names the same plan on every
// platform. A failing case prints its seed and writes its plan to the test's temporary
// directory; a seed that once failed is kept below as a named regression test, its plan
// stored in tests/hard_cases/random-plan-SEED.toml (so that it survives changes to the
// generator; the seed still picks the eyes).
//
// Environment, for searching further: AVENUES_RANDOM_PLANS="FIRST:COUNT" runs seeds FIRST
// to FIRST+COUNT-1 instead of the default 1..50; AVENUES_RANDOM_PLANS_VERBOSE=1 prints each
// seed before its plan is built (to find the seed of a crash).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "cells/build_cells.h"
#include "ray_oracle.h"
#include "visibility/visible_set.h"

using namespace avenues;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Uniform numbers from the raw output of mt19937 only (the standard's distributions differ
/// between libraries; the engine's sequence does not).
class Dice {
 public:
  explicit Dice(uint32_t seed) : rng_(seed) {}
  /// In [a, b).
  double real(double a, double b) { return a + (b - a) * (double(rng_()) / 4294967296.0); }
  /// In [0, n).
  int below(int n) { return int(rng_() % uint32_t(n)); }
  bool chance(double p) { return real(0, 1) < p; }
  /// A length rounded to the centimetre most of the time (plans are typed that way, and
  /// round figures make walls meet exactly), else any double.
  double length(double a, double b) {
    const double x = real(a, b);
    return chance(0.8) ? std::round(x * 100) / 100 : x;
  }

 private:
  std::mt19937 rng_;
};

/// A wall as the generator sees it: its centre line (straight pieces; an arc is kept as
/// its through point) and thickness, for placing labels away from it.
struct GenWall {
  std::vector<Vec2> path;
  std::vector<int> arc_through;  ///< per segment: index into `through`, or -1 for a straight one
  std::vector<Vec2> through;
  double thickness = 0;
  double height = -1;
  std::string openings;  ///< TOML of its [[wall.opening]] tables
  bool upper = false;     ///< on the upper storey (when the plan has one)
};

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string point(Vec2 p) {
  char buf[90];
  std::snprintf(buf, sizeof buf, "[%.17g, %.17g]", p.x, p.y);
  return buf;
}

/// Openings along a straight segment starting `along` metres down its wall: up to two,
/// not overlapping, of random kind, width and heights within the storey.
void add_openings(Dice& dice, GenWall& w, double along, double seg_len, double storey_height, int& count) {
  const int n = dice.below(3);
  double from = 0;  // along the segment: the next opening starts at or after this
  for (int k = 0; k < n; ++k) {
    const double room = seg_len - from;
    if (room < 0.3) return;
    const double width = dice.length(0.2, std::min(1.6, room));
    if (width <= 0 || width > room) return;
    const double at = from + dice.length(0, room - width);
    if (at < from || at + width > seg_len) return;
    std::string kind = "door";
    double sill = 0, head = dice.length(1.8, storey_height);
    switch (dice.below(4)) {
      case 0: break;  // a door
      case 1: kind = "window", sill = dice.length(0.3, 1.2), head = dice.length(sill + 0.3, storey_height); break;
      case 2: kind = "hatch", sill = dice.length(0.8, 1.2), head = dice.length(sill + 0.2, sill + 0.8); break;
      case 3: head = storey_height; break;  // a door up to the ceiling: a gap in the wall
    }
    head = std::min(head, storey_height);
    if (!(sill < head)) continue;
    w.openings += "[[wall.opening]]\nname = \"o" + std::to_string(++count) + "\"\nkind = \"" + kind +
                  "\"\nat = " + num(along + at) + "\nwidth = " + num(width) + "\nsill = " + num(sill) +
                  "\nhead = " + num(head) + "\n";
    from = at + width + dice.length(0, 0.5);
  }
}

/// A closed wall around `ring`, with openings on about half its sides.
GenWall perimeter_wall(Dice& dice, const std::vector<Vec2>& ring, double thickness, double storey_height, int& openings) {
  GenWall w;
  w.path = ring;
  w.path.push_back(ring.front());
  w.arc_through.assign(ring.size(), -1);
  w.thickness = thickness;
  double along = 0;
  for (size_t i = 0; i + 1 < w.path.size(); ++i) {
    const double len = length(w.path[i + 1] - w.path[i]);
    if (dice.chance(0.5)) add_openings(dice, w, along, len, storey_height, openings);
    along += len;
  }
  return w;
}

/// The plan of `seed`, as TOML.
std::string random_plan(uint32_t seed) {
  Dice dice(seed);
  const double W = dice.length(4, 14), H = dice.length(3.5, 11);
  const double storey_height = dice.chance(0.7) ? 2.5 : dice.length(2.2, 3.5);
  std::vector<GenWall> walls;
  int openings = 0;

  // The perimeter: a rectangle, one corner perhaps cut off obliquely, closed on itself.
  std::vector<Vec2> outline{{0, 0}, {W, 0}, {W, H}, {0, H}};
  if (dice.chance(0.5)) {
    const double cx = dice.length(0.5, W / 2), cy = dice.length(0.5, H / 2);
    outline = {{0, 0}, {W, 0}, {W, H - cy}, {W - cx, H}, {0, H}};
  }
  {
    const double t[] = {0, 0.1, 0.2, 0.35};
    const double thickness = t[dice.below(4)];
    walls.push_back(perimeter_wall(dice, outline, thickness, storey_height, openings));
  }

  // A random point on the perimeter's side k (0: south, then anticlockwise).
  auto on_side = [&](size_t k, double lo, double hi) {
    const Vec2 a = outline[k], b = outline[(k + 1) % outline.size()];
    const double t = dice.real(lo, hi);
    Vec2 p = a + t * (b - a);
    if (dice.chance(0.7)) p = {std::round(p.x * 100) / 100, std::round(p.y * 100) / 100};
    return p;
  };
  const double thick[] = {0, 0, 0.001, 0.05, 0.1, 0.15, 0.2, 0.3};
  const int interior = 1 + dice.below(5);
  for (int i = 0; i < interior; ++i) {
    GenWall w;
    w.thickness = thick[dice.below(8)];
    switch (dice.below(6)) {
      case 0: {  // wall to wall, north–south
        const double x = dice.length(0.4, W - 0.4);
        w.path = {{x, 0}, {x, H}};
        break;
      }
      case 1: {  // wall to wall, east–west
        const double y = dice.length(0.4, H - 0.4);
        w.path = {{0, y}, {W, y}};
        break;
      }
      case 2: {  // a stub from the perimeter into the room, free at its end
        const size_t k = size_t(dice.below(int(outline.size())));
        const Vec2 a = on_side(k, 0.1, 0.9), e = outline[(k + 1) % outline.size()] - outline[k];
        const Vec2 inward = (1 / length(e)) * Vec2{-e.y, e.x};
        w.path = {a, a + dice.length(0.5, std::min(W, H) * 0.7) * inward};
        break;
      }
      case 3: {  // oblique, from one side of the perimeter to another
        const size_t k = size_t(dice.below(int(outline.size())));
        const size_t m = (k + 1 + size_t(dice.below(int(outline.size()) - 1))) % outline.size();
        w.path = {on_side(k, 0.05, 0.95), on_side(m, 0.05, 0.95)};
        break;
      }
      case 4: {  // free-standing, bent once at a random angle
        const Vec2 a{dice.length(0.5, W - 0.5), dice.length(0.5, H - 0.5)};
        const double h0 = dice.real(0, 2 * kPi), turn = dice.real(-170, 170) * kPi / 180;
        const double l0 = dice.length(0.5, 3), l1 = dice.length(0.5, 3);
        const Vec2 b = a + l0 * Vec2{std::cos(h0), std::sin(h0)};
        w.path = {a, b, b + l1 * Vec2{std::cos(h0 + turn), std::sin(h0 + turn)}};
        break;
      }
      case 5: {  // curved: an arc between two points of the room
        const Vec2 a{dice.length(0.5, W - 0.5), dice.length(0.5, H - 0.5)};
        const Vec2 b{dice.length(0.5, W - 0.5), dice.length(0.5, H - 0.5)};
        const Vec2 d = b - a;
        if (length(d) < 0.5) {
          w.path = {a, a + Vec2{0.5, 0}};
          break;
        }
        const Vec2 mid = a + 0.5 * d, n = (1 / length(d)) * Vec2{-d.y, d.x};
        w.through = {mid + dice.real(-0.45, 0.45) * length(d) * n};
        if (std::fabs(cross(w.through[0] - a, d)) < 1e-3 * dot(d, d)) w.through[0] = mid + 0.2 * length(d) * n;
        w.path = {a, b};
        w.arc_through = {0};
        break;
      }
    }
    if (w.arc_through.empty()) w.arc_through.assign(w.path.size() - 1, -1);
    if (dice.chance(0.15)) w.height = dice.length(0.6, storey_height - 0.1);
    // Openings on straight segments only (the reader's rule); the arc's length is not ours to know.
    double along = 0;
    for (size_t s = 0; s + 1 < w.path.size(); ++s) {
      const double len = length(w.path[s + 1] - w.path[s]);
      if (w.arc_through[s] >= 0) break;
      if (len < 1e-6) break;
      add_openings(dice, w, along, len, w.height > 0 ? w.height : storey_height, openings);
      along += len;
    }
    // A path the reader rejects (a segment of length 0) is dropped here: the generator's
    // business is plans the reader takes.
    bool degenerate = false;
    for (size_t s = 0; s + 1 < w.path.size(); ++s) degenerate |= w.path[s + 1] == w.path[s];
    if (!degenerate) walls.push_back(w);
  }

  // Labels only where they clearly stand in free space: inside the perimeter, 0.3 m clear
  // of every wall. Two of them may still share a space (the plan error then names them).
  std::vector<Vec2> labels;
  const int tries = dice.below(4);
  for (int k = 0; k < tries; ++k) {
    const Vec2 p{dice.length(0.3, W - 0.3), dice.length(0.3, H - 0.3)};
    bool clear = inside_polygon(outline, p);
    for (const GenWall& w : walls)
      for (size_t s = 0; s + 1 < w.path.size() && clear; ++s) {
        const double reach = w.arc_through[s] >= 0 ? length(w.path[s + 1] - w.path[s]) : 0;  // arcs: keep well away
        const Vec2 a = w.path[s], b = w.path[s + 1];
        clear = distance_to_segment(p, a, b) > w.thickness / 2 + 0.3 + reach;
      }
    if (clear) labels.push_back(p);
  }

  const double far_margin = dice.length(1, 6);
  const double slab = dice.chance(0.3) ? 0.0 : dice.length(0.1, 0.4);

  // An upper storey on a third of the plans, from dice of its own (so that the ground
  // storey of every seed is what it was before upper storeys came): its perimeter the
  // ground's or a part of it, a few walls, and a stairwell or two in its floor.
  Dice up(seed * 2654435761u + 0x5bd1e995u);
  const bool two_storeys = up.chance(1.0 / 3);
  double upper_height = 0;
  std::vector<std::vector<Vec2>> stairwells;
  if (two_storeys) {
    upper_height = up.chance(0.6) ? 2.5 : up.length(2.2, 3.2);
    const double uw = up.chance(0.5) ? W : up.length(std::min(2.0, W), W);
    const double uh = up.chance(0.5) ? H : up.length(std::min(2.0, H), H);
    const std::vector<Vec2> top = uw == W && uh == H ? outline : std::vector<Vec2>{{0, 0}, {uw, 0}, {uw, uh}, {0, uh}};
    const double thickness = thick[up.below(8)];
    walls.push_back(perimeter_wall(up, top, thickness, upper_height, openings));
    walls.back().upper = true;
    const int inner = up.below(4);
    for (int i = 0; i < inner; ++i) {
      GenWall w;
      w.upper = true;
      w.thickness = thick[up.below(8)];
      const double x = up.length(0.3, uw - 0.3), y = up.length(0.3, uh - 0.3);
      switch (up.below(3)) {
        case 0: w.path = {{x, 0}, {x, uh}}; break;  // wall to wall
        case 1: w.path = {{0, y}, {uw, y}}; break;
        default: w.path = {{x, y}, {up.length(0.3, uw - 0.3), up.length(0.3, uh - 0.3)}}; break;  // free-standing
      }
      if (w.path[0] == w.path[1]) continue;
      w.arc_through.assign(1, -1);
      if (up.chance(0.15)) w.height = up.length(0.6, upper_height - 0.1);
      add_openings(up, w, 0, length(w.path[1] - w.path[0]), w.height > 0 ? w.height : upper_height, openings);
      walls.push_back(w);
    }
    // Stairwells: rectangles, or a triangle, inside the upper perimeter; two at most, one
    // in each half so that they do not overlap.
    const int holes = 1 + up.below(2);
    for (int k = 0; k < holes; ++k) {
      const double x0 = holes == 1 ? 0.2 : k * uw / 2 + 0.1, x1 = holes == 1 ? uw - 0.2 : (k + 1) * uw / 2 - 0.1;
      if (x1 - x0 < 0.6 || uh < 1.0) continue;
      const double a = up.length(x0, x1 - 0.5), b = up.length(a + 0.3, x1);
      const double c = up.length(0.2, uh - 0.7), d = up.length(c + 0.3, uh - 0.2);
      if (!(a < b && c < d)) continue;
      if (up.chance(0.25)) stairwells.push_back({{a, c}, {b, c}, {a, d}});
      else stairwells.push_back({{a, c}, {b, c}, {b, d}, {a, d}});
    }
  }

  std::ostringstream t;
  t << "# random plan, seed " << seed << " (tests/random_plans_test.cpp)\n";
  t << "name = \"random " << seed << "\"\nunits = \"m\"\nfar_margin = " << num(far_margin) << "\n\n";
  t << "[[storey]]\nname = \"ground\"\nelevation = 0\nheight = " << num(storey_height) << "\nslab = " << num(slab) << "\n";
  if (two_storeys)
    t << "\n[[storey]]\nname = \"upper\"\nelevation = " << num(storey_height + slab) << "\nheight = " << num(upper_height)
      << "\nslab = " << num(up.chance(0.3) ? 0.0 : up.length(0.1, 0.4)) << "\n";
  Dice tilt(seed * 2654435761u + 0x9e3779b9u);
  Dice bend(seed * 40503u + 0x7f4a7c15u);  // (dice of their own: the plans before bends stay as they were)
  for (size_t i = 0; i < walls.size(); ++i) {
    const GenWall& w = walls[i];
    t << "\n[[wall]]\nname = \"w" << i << "\"\nthickness = " << num(w.thickness) << "\n";
    if (two_storeys) t << "storey = \"" << (w.upper ? "upper" : "ground") << "\"\n";
    // Now and then a thick wall's top sloped (a gable), from dice of their own: from the
    // floor to above the ceiling at either end, over its openings' heads or under them.
    const double top = w.upper ? upper_height : storey_height;
    if (w.thickness > 0 && tilt.chance(0.2)) {
      const double h0 = w.height > 0 ? w.height : tilt.length(0, top + 0.5), h1 = tilt.length(0, top + 0.8);
      if (h0 > 0 || h1 > 0) {
        t << "height = " << num(h0) << "\nheight_at_end = " << num(h1) << "\n";
        // Half of them bend once or twice between their ends (a gable's ridge), inside the
        // path's chords (no longer than its arcs).
        double chords = 0;
        for (size_t s = 0; s + 1 < w.path.size(); ++s) chords += length(w.path[s + 1] - w.path[s]);
        if (bend.chance(0.5) && chords > 0.4) {
          const int n = 1 + bend.below(2);
          double at = 0;
          t << "top_bends = [";
          for (int k = 0; k < n; ++k) {
            at = bend.length(at + 0.1, at + 0.1 + (chords - 0.1 - at - 0.1) / double(n - k));
            t << (k ? ", [" : "[") << num(at) << ", " << num(bend.length(0, top + 0.8)) << "]";
          }
          t << "]\n";
        }
      } else if (w.height > 0) {
        t << "height = " << num(w.height) << "\n";
      }
    } else if (w.height > 0) {
      t << "height = " << num(w.height) << "\n";
    }
    t << "path = [" << point(w.path[0]);
    for (size_t s = 0; s + 1 < w.path.size(); ++s) {
      if (w.arc_through[s] >= 0)
        t << ", {through = " << point(w.through[size_t(w.arc_through[s])]) << ", to = " << point(w.path[s + 1]) << "}";
      else
        t << ", " << point(w.path[s + 1]);
    }
    t << "]\n" << w.openings;
  }
  for (size_t k = 0; k < stairwells.size(); ++k) {
    t << "\n[[floor_opening]]\nname = \"stair" << k << "\"\nstorey = \"upper\"\noutline = [" << point(stairwells[k][0]);
    for (size_t v = 1; v < stairwells[k].size(); ++v) t << ", " << point(stairwells[k][v]);
    t << "]\n";
  }
  // Now and then a room's own floor raised, or its ceiling lowered (a platform, a
  // suspended ceiling), from dice of their own like the upper storey's.
  Dice raise(seed * 2246822519u + 0x27d4eb2fu);
  for (size_t r = 0; r < labels.size(); ++r) {
    t << "\n[[room]]\nname = \"r" << r << "\"\nat = " << point(labels[r]) << "\n";
    if (two_storeys) t << "storey = \"ground\"\n";
    double floor_at = 0;
    if (raise.chance(0.2)) t << "floor_at = " << num(floor_at = raise.length(0.05, 0.6)) << "\n";
    if (raise.chance(0.2)) t << "ceiling_at = " << num(raise.length(floor_at + 1.5, storey_height - 0.02)) << "\n";
  }
  return t.str();
}

/// Removes the [[room]] tables (everything after the first one: the generator writes them last).
std::string without_rooms(const std::string& toml) {
  const size_t at = toml.find("\n[[room]]");
  return at == std::string::npos ? toml : toml.substr(0, at + 1);
}

/// A point strictly inside the free cell, at random.
Vec3 eye_in(Dice& dice, const Cell& cell) {
  Vec2 p{0, 0};
  double sum = 0;
  std::vector<double> w(cell.footprint.size());
  for (double& x : w) sum += (x = dice.real(0.05, 1));
  for (size_t i = 0; i < w.size(); ++i) p = p + (w[i] / sum) * cell.footprint[i];
  // Between the cell's floor and ceiling over p: its faces that are not upright bound it
  // (a cell over a sloped wall has the wall's top for a floor).
  double lo = cell.z0, hi = cell.z1;
  for (const Face& f : cell.faces) {
    if (std::fabs(f.plane.n.z) < 1e-12) continue;
    const double z = -(f.plane.n.x * p.x + f.plane.n.y * p.y + f.plane.d) / f.plane.n.z;
    if (f.plane.n.z < 0) lo = std::max(lo, z);
    else hi = std::min(hi, z);
  }
  return {p.x, p.y, lo + dice.real(0.05, 0.95) * (hi - lo)};
}

/// What one plan did, for the summary line.
struct Tally {
  int plans = 0, plan_errors = 0, views = 0, cells = 0;
};

/// Writes a failing plan where it can be looked at, and says how to replay it.
void report(uint32_t seed, const std::string& toml, const std::string& what) {
  const std::string path = ::testing::TempDir() + "random-plan-" + std::to_string(seed) + ".toml";
  std::ofstream(path) << toml;
  ADD_FAILURE() << "random plan seed " << seed << ": " << what << "\n  plan written to " << path
                << "\n  replay: AVENUES_RANDOM_PLANS=" << seed << ":1 avenues_tests --gtest_filter=RandomPlans.AgreeWithTheOracle";
}

/// Builds the plan `toml` and checks it and `eyes` random views of it (chosen by `seed`)
/// against the oracle.
void check_plan(uint32_t seed, const std::string& toml, int eyes, Tally& tally) {
  Plan plan;
  try {
    plan = parse_plan(toml, "random-" + std::to_string(seed) + ".toml");
  } catch (const PlanError& e) {
    return report(seed, toml, std::string("the generator wrote a plan the reader refuses: ") + e.what());
  }
  ++tally.plans;
  CellComplex c;
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      c = build_cells(plan);
      break;
    } catch (const PlanError& e) {
      // Allowed — two labels in one space, say — if it names the element at fault.
      ++tally.plan_errors;
      if (e.where().element.empty()) return report(seed, toml, std::string("a PlanError naming no element: ") + e.what());
      if (attempt == 1 || plan.rooms.empty()) return report(seed, toml, std::string("a PlanError without rooms: ") + e.what());
      plan = parse_plan(without_rooms(toml), "random-" + std::to_string(seed) + ".toml");  // the walls alone, then
    } catch (const std::exception& e) {
      return report(seed, toml, std::string("build_cells threw ") + typeid(e).name() + ": " + e.what());
    }
  }
  if (const std::string why = cells_are_valid(c); !why.empty()) return report(seed, toml, "invalid cells: " + why);
  tally.cells += int(c.cells.size());

  Dice dice(seed ^ 0x9e3779b9u);
  std::vector<CellId> free;
  for (CellId id = 0; id < CellId(c.cells.size()); ++id)
    if (c.cells[size_t(id)].kind != CellKind::Sky || dice.chance(0.2)) free.push_back(id);
  if (free.empty()) return report(seed, toml, "no free cell");
  for (int v = 0; v < eyes; ++v) {
    // Rooms mostly; a doorway or the outside now and then.
    CellId cell = free[size_t(dice.below(int(free.size())))];
    for (int k = 0; k < 3 && c.cells[size_t(cell)].kind != CellKind::Room; ++k)
      cell = free[size_t(dice.below(int(free.size())))];
    const Vec3 eye = eye_in(dice, c.cells[size_t(cell)]);
    Camera cam;
    const double fov = dice.real(20, 130);
    if (dice.chance(0.5) && !c.portals.empty()) {  // look at a portal: views through openings
      const Portal& p = c.portals[size_t(dice.below(int(c.portals.size())))];
      Vec3 centre{0, 0, 0};
      for (Vec3 q : p.poly) centre = centre + (1.0 / double(p.poly.size())) * q;
      if (length(centre - eye) < 1e-3) centre = centre + Vec3{1, 0, 0};
      cam = Camera::look_at(eye, centre, fov, 40, 30);
    } else {
      cam = Camera::yaw_pitch(eye, dice.real(0, 360), dice.real(-45, 45), fov, 40, 30);
    }
    ++tally.views;
    for (Kernel k : {Kernel::Double, Kernel::Exact}) {
      const VisibleSet vs = find_visible(c, cam, cell, k);
      const avenues::testing::OracleResult r = avenues::testing::check_visible_set(c, cam, vs);
      if (!r.ok()) {
        char buf[400];
        std::snprintf(buf, sizeof buf,
                      "kernel %s, view %d: eye (%.17g, %.17g, %.17g) in cell %d (%s), forward (%.6f, %.6f, %.6f), fov "
                      "%.3f: %d (ray, cell) pairs missing, %d avenues extra",
                      to_string(k), v, eye.x, eye.y, eye.z, cell, to_string(c.cells[size_t(cell)].kind),
                      cam.forward.x, cam.forward.y, cam.forward.z, cam.fov_deg, r.missing, r.extra);
        report(seed, toml, buf);
      }
    }
  }
}

/// Runs seeds [first, first + count), or what AVENUES_RANDOM_PLANS says.
Tally check_seeds(uint32_t first, int count, int eyes) {
  if (const char* s = std::getenv("AVENUES_RANDOM_PLANS")) {
    unsigned long f = 0, n = 0;
    if (std::sscanf(s, "%lu:%lu", &f, &n) == 2) first = uint32_t(f), count = int(n);
  }
  const bool verbose = std::getenv("AVENUES_RANDOM_PLANS_VERBOSE") != nullptr;
  Tally tally;
  for (int i = 0; i < count; ++i) {
    const uint32_t seed = first + uint32_t(i);
    if (verbose) std::fprintf(stderr, "[random plans] seed %u\n", seed), std::fflush(stderr);
    check_plan(seed, random_plan(seed), eyes, tally);
  }
  std::printf("[random plans] seeds %u..%u: %d plans, %d plan errors (then built without labels), %d cells, %d views\n",
              first, first + uint32_t(count) - 1, tally.plans, tally.plan_errors, tally.cells, tally.views);
  return tally;
}

}  // namespace

// Fifty random plans, four eyes each, double and exact kernels against the rays.
TEST(RandomPlans, AgreeWithTheOracle) {
  const Tally t = check_seeds(1, 50, 4);
  // The generator must mostly make plans that build (else the test tests little).
  EXPECT_GE(t.views, 3 * t.plans);
}

// The generator is a function of the seed alone: the same plan twice, different plans for different seeds.
TEST(RandomPlans, ASeedNamesOnePlan) {
  EXPECT_EQ(random_plan(7), random_plan(7));
  EXPECT_NE(random_plan(7), random_plan(8));
}

// --- seeds that once failed, their plans kept as they were generated ----------------------

namespace {

/// Checks the stored plan of a seed that once failed, with the eyes that seed picks.
void check_stored(uint32_t seed) {
  const std::string path = std::string(AVENUES_SOURCE_DIR) + "/tests/hard_cases/random-plan-" + std::to_string(seed) + ".toml";
  std::ifstream in(path);
  ASSERT_TRUE(in) << "cannot read " << path;
  std::stringstream text;
  text << in.rdbuf();
  Tally tally;
  check_plan(seed, text.str(), 4, tally);
  EXPECT_EQ(tally.plans, 1);
}

}  // namespace

// The top of a wall, seen from the sky, was left neither opaque nor a portal: two vertices of
// the exact triangulation (where a door's jamb meets a mitred corner) rounded to one point,
// and footprint_of in cells/extrude.cpp, finding each collinear with the other, dropped
// both — and with them the whole piece. cells_are_valid: "face 4 of cell 17 has area 134.665
// but opaque + portals cover 134.351". Seeds 693, 1022, 1520, 2660 and 2925 likewise.
TEST(RandomPlans, Seed1570WallTopWithTwoVerticesRoundedToOne) { check_stored(1570); }
TEST(RandomPlans, Seed693WallTopWithTwoVerticesRoundedToOne) { check_stored(693); }
TEST(RandomPlans, Seed1022WallTopWithTwoVerticesRoundedToOne) { check_stored(1022); }
TEST(RandomPlans, Seed1520WallTopWithTwoVerticesRoundedToOne) { check_stored(1520); }
TEST(RandomPlans, Seed2660WallTopWithTwoVerticesRoundedToOne) { check_stored(2660); }
TEST(RandomPlans, Seed2925WallTopWithTwoVerticesRoundedToOne) { check_stored(2925); }

// The exact and filtered kernels missed a doorway the double kernel saw (7 rays): the exact
// mask of the cell before it held two vertices a rounding apart (two nearly parallel edge
// planes, both kept in exact arithmetic), and the double-precision cull in
// visibility/traverse.h (cone_planes, then surely_outside) built a plane through those two
// nearly equal directions — rounding noise — that cut the portal away.
TEST(RandomPlans, Seed2667ExactMaskWithNearlyEqualVertices) { check_stored(2667); }

// A wall bent back sharply (a bevelled joint at 15° to 27°): near its bend, vertices distinct
// in the exact triangulation round to one point — four of them at (2.7664644, 5.69757897)
// in seed 5714 — or to points a rounding apart, and leave triangles of no area. Then:
//  - merge_convex (cells/merge.cpp), deciding convexity on the rounded points, where such a
//    point makes no turn at all, merges pieces into one whose boundary passes twice through
//    that point (two lobes joined there): "face 4 of cell 43 has area 132.945 but opaque +
//    portals cover 132.938" (5714; 6006 likewise once footprint_of keeps such points);
TEST(RandomPlans, Seed5714PinchedPiece) { check_stored(5714); }
TEST(RandomPlans, Seed6006PinchedPiece) { check_stored(6006); }
//  - real_lines (cells/real_lines.cpp) makes a line of no length along the edge between two
//    such points: "cell 24 has a bad line part" (7455, once footprint_of keeps them);
TEST(RandomPlans, Seed7455LineOfNoLength) { check_stored(7455); }
//  - a cell's footprint keeps three vertices a few ulps apart (distinct points of the exact
//    triangulation, rounded), whose turns are noise, and its own portal falls outside it:
//    "portal 38 does not lie in a face of cell 18" (7322; its walls alone, the labels
//    taken out because two of them share a space). footprint_of treats such points as one.
TEST(RandomPlans, Seed7322FootprintVerticesARoundingApart) { check_stored(7322); }
//  - merging judged a corner against a side between two points a rounding apart, whose
//    direction is noise, and found it convex; footprint_of, taking the two as one, then
//    had a corner turning right and its cell folded over a portal: "portal 4 does not lie
//    in a face of cell 8" (30396: one wall 1 mm thick bent back at 24°; 32739: one 10 cm
//    thick bent back at 24°; each with that wall alone). Both now judge corners alike
//    (cells/corners.cpp), and a merged piece must wind once.
TEST(RandomPlans, Seed30396CornerJudgedAgainstRoundingNoise) { check_stored(30396); }
TEST(RandomPlans, Seed32739CornerJudgedAgainstRoundingNoise) { check_stored(32739); }

// A wall of no thickness ended on another, as drawn, but a tenth of a nanometre off it once
// its ends were rounded; the sliver of free space between them was a cell 1e-10 m wide, an
// eye placed in it stood on the far side of the wall within rounding, and every avenue it
// saw through the wall was one the rays never enter (30249, 30518). Such a gap between
// walls of no thickness is now closed, as between thick ones (close_gaps, cells/classify.cpp).
TEST(RandomPlans, Seed30249WallOfNoThicknessEndingARoundingShort) { check_stored(30249); }
TEST(RandomPlans, Seed30518WallOfNoThicknessEndingARoundingShort) { check_stored(30518); }

// Two storeys (the generator's upper storeys found it at once, in 7 of the first 300
// seeds): a corner of the upper storey's wall and a point of the ground storey's walls
// below it rounded to points a rounding apart, and the edge between them made a piece of
// real line 1e-16 m long at the end of a 3.3 m line, whose two ends have one parameter:
// "cell 17 has a bad line part" (9, its walls that keep the failure). real_lines now
// takes such an edge as no line, as footprint_of takes its ends as one point.
TEST(RandomPlans, Seed9LinePieceARoundingLong) { check_stored(9); }

// An eye in a cell 3e-11 m wide between an upper storey's wall of no thickness and a point
// of the ground storey's walls a rounding off it (the storeys share one triangulation)
// stands within a nanometre of that wall. The search takes it as on the wall, seeing both
// sides (kOnBoundary, visibility/visible_set.h); the rays stopped at the wall 2e-11 m away
// and found 18 avenues extra (5556). The oracle now takes such an eye as the search does.
TEST(RandomPlans, Seed5556EyeANanometreFromAWall) { check_stored(5556); }

// The double kernel missed five outside cells (432 rays) seen up through a room's open top
// and out of the cell above it: the mask of that cell kept, beside an edge, a half-plane
// nearly parallel to it that bounded nothing, whose vertex lay at (-5.7, -1.6) in a window
// 0.51 wide; cone_planes (visibility/traverse.h) turned each plane by the mask's centroid,
// which that vertex had pulled outside the mask, and a plane turned the wrong way culled
// the portals beyond (8836). A plane with a mask vertex clearly outside it now culls nothing.
TEST(RandomPlans, Seed8836ConeTurnedByAFarMaskVertex) { check_stored(8836); }

// Walls with sloped tops (Wall::height_at_end), their first random plans:
//  - a horizontal line where a sloped top passed the line's height along the edge, judged
//    at the edge's middle as a whole: "a line of cell 4 leaves the cell" (20). An edge is now
//    judged in parts between the points where a sloped top beside it passes the height;
TEST(RandomPlans, Seed20HorizontalLineWhereASlopedTopPassesItsHeight) { check_stored(20); }
//  - a portal under a neighbour's lower ceiling, its bottom the rising top, kept on past the
//    point where the top rises above that ceiling: "face 1 of cell 24 has area 1.87694 but
//    opaque + portals cover 1.99492" (235). Sides are walked in pieces between the points
//    where any floor or ceiling of the two cells overtakes another;
TEST(RandomPlans, Seed235PortalUnderACeilingASlopedTopRisesAbove) { check_stored(235); }
//  - an eye placed between a cell's lowest and highest point, below its sloped floor, inside
//    the wall (the test's own eyes; the views were right): 37 avenues "extra" (332);
TEST(RandomPlans, Seed332EyeAboveASlopedFloor) { check_stored(332); }
//  - a vertical line at a point on a sloped cell's side where a neighbour's edge ends, cut
//    at heights taken from its corners only: "a line of cell 14 leaves the cell" (928);
TEST(RandomPlans, Seed928VerticalLineAtAPointOnASlopedSide) { check_stored(928); }
//  - the rising edge of a sliver over a sloped wall, whose two long sides are nearly one
//    plane, given the portals of the other side: "a line of cell 2 leaves the cell" (1869,
//    its walls alone).
TEST(RandomPlans, Seed1869SlopedEdgeOfASliver) { check_stored(1869); }

// Sloped tops that bend (Wall::top_bends), their first random plans: a gap closed between
// two pieces of one curved wall's top (a sliver between nearly collinear cuts, thinner
// than kGap) took a neighbouring piece's plane, which passes the ceiling within it: its
// cell's floor left its plane at the ceiling, "cell 87 face 2 is not planar" (1191), or
// turned, "cell 66 face 3 is not convex" (3179). A sloped gap now stands level at its
// plane's highest over it.
TEST(RandomPlans, Seed1191GapClosedPastWhereItsSlopeMeetsTheCeiling) { check_stored(1191); }
TEST(RandomPlans, Seed3179GapClosedUnderASlopeTurnsItsFloor) { check_stored(3179); }
// An eye 1.7 nm inside three faces of a sliver over a bent sloped top stands on them; the
// search roots the cells on their other sides, and a ray leaving between the planes ran
// 13 µm inside the sliver (the ray oracle now holds the eye's own cell seen, as it does for
// its avenues) (5743).
TEST(RandomPlans, Seed5743EyeOnThreeFacesOfASliver) { check_stored(5743); }

// Each band's free space cut afresh (cells/band_cuts.cpp), its first random plans: two
// corners of a sloped wall's side, each reflex by its rounding (2.5e-9 rad), were joined by
// a diagonal along the side, which parted two slivers 0.1 nm wide off the room; a ray from
// an eye in one crossed the other for 2 µm, which no avenue reached (3668). A diagonal now
// makes at least a milliradian with the sides at its ends.
TEST(RandomPlans, Seed3668DiagonalAlongASlopedWallsSide) { check_stored(3668); }
