// Avenues — tests of the plan reader (plans/plan_reader.cpp), the bundled plans and
// the office generator (plans/generate.cpp).
//
// Three kinds of test:
//   * the bundled plans parse, with the counts and values their files say, and are
//     physically sensible (rooms enclosed, labels in their rooms, openings clear of
//     crossing walls) — checked here by an independent raster flood fill, not by cells/;
//   * the semantics of the format: arc tessellation, units, defaults;
//   * every kind of mistake gives a PlanError naming the file and the right line.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "plans/generate.h"
#include "plans/plan.h"

namespace avenues {
namespace {

const std::string kPlansDir = std::string(AVENUES_SOURCE_DIR) + "/plans/";

Plan bundled(const std::string& file) { return read_plan(kPlansDir + file); }

int opening_count(const Plan& p) {
  int n = 0;
  for (const Wall& w : p.walls) n += static_cast<int>(w.openings.size());
  return n;
}

// ---------------------------------------------------------------------------------
// Physical sanity, checked independently of cells/.

/// Distance from p to the centre line of wall w, skipping segment `skip`.
double dist_to_wall(Vec2 p, const Wall& w, int skip = -1) {
  double best = HUGE_VAL;
  for (size_t s = 0; s + 1 < w.centre.size(); ++s)
    if (static_cast<int>(s) != skip) best = std::min(best, distance_to_segment(p, w.centre[s], w.centre[s + 1]));
  return best;
}

/// A raster of one storey's walls (openings closed), flood-filled from room labels:
/// a room is enclosed if its fill never reaches the raster's border, and distinct if
/// it never reaches another room's label.
class StoreyRaster {
 public:
  static constexpr double kPixel = 0.05;  // [m]

  StoreyRaster(const Plan& plan, StoreyId storey) {
    for (const Wall& w : plan.walls)
      if (w.storey == storey) walls_.push_back(&w);
    lo_ = {HUGE_VAL, HUGE_VAL};
    Vec2 hi{-HUGE_VAL, -HUGE_VAL};
    for (const Wall* w : walls_)
      for (Vec2 p : w->centre) {
        lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
      }
    lo_ = lo_ - Vec2{1, 1};
    nx_ = static_cast<int>((hi.x + 1 - lo_.x) / kPixel) + 1;
    ny_ = static_cast<int>((hi.y + 1 - lo_.y) / kPixel) + 1;
    solid_.assign(static_cast<size_t>(nx_) * ny_, 0);
    // A pixel is solid when its centre is within half a thickness of a centre line,
    // and at least 0.04 m (> pixel/√2 / 2) so that a sheet blocks a 4-connected fill.
    for (const Wall* w : walls_) {
      const double r = std::max(w->thickness / 2, 0.04);
      for (size_t s = 0; s + 1 < w->centre.size(); ++s) {
        const Vec2 a = w->centre[s], b = w->centre[s + 1];
        const int i0 = px(std::min(a.x, b.x) - r) - 1, i1 = px(std::max(a.x, b.x) + r) + 1;
        const int j0 = py(std::min(a.y, b.y) - r) - 1, j1 = py(std::max(a.y, b.y) + r) + 1;
        for (int j = std::max(j0, 0); j <= std::min(j1, ny_ - 1); ++j)
          for (int i = std::max(i0, 0); i <= std::min(i1, nx_ - 1); ++i)
            if (distance_to_segment(centre(i, j), a, b) <= r) solid_[idx(i, j)] = 1;
      }
    }
  }

  /// Fills from p; returns the region (pixel flags), or empty if p is solid.
  /// `leaks` tells whether the fill reached the border.
  std::vector<char> fill(Vec2 p, bool& leaks) const {
    std::vector<char> in(solid_.size(), 0);
    leaks = false;
    const int i = px(p.x), j = py(p.y);
    if (solid_[idx(i, j)]) return {};
    std::deque<std::pair<int, int>> todo{{i, j}};
    in[idx(i, j)] = 1;
    while (!todo.empty()) {
      auto [a, b] = todo.front();
      todo.pop_front();
      if (a == 0 || b == 0 || a == nx_ - 1 || b == ny_ - 1) leaks = true;
      const int d[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
      for (auto& e : d) {
        const int u = a + e[0], v = b + e[1];
        if (u < 0 || v < 0 || u >= nx_ || v >= ny_) continue;
        const size_t k = idx(u, v);
        if (solid_[k] || in[k]) continue;
        in[k] = 1;
        todo.push_back({u, v});
      }
    }
    return in;
  }
  bool inside(const std::vector<char>& region, Vec2 p) const {
    const int i = px(p.x), j = py(p.y);
    return i >= 0 && j >= 0 && i < nx_ && j < ny_ && !region.empty() && region[idx(i, j)];
  }
  const std::vector<const Wall*>& walls() const { return walls_; }

 private:
  int px(double x) const { return static_cast<int>(std::floor((x - lo_.x) / kPixel)); }
  int py(double y) const { return static_cast<int>(std::floor((y - lo_.y) / kPixel)); }
  Vec2 centre(int i, int j) const { return {lo_.x + (i + 0.5) * kPixel, lo_.y + (j + 0.5) * kPixel}; }
  size_t idx(int i, int j) const { return static_cast<size_t>(j) * nx_ + i; }

  std::vector<const Wall*> walls_;
  Vec2 lo_;
  int nx_ = 0, ny_ = 0;
  std::vector<char> solid_;
};

/// Checks that a plan is physically sensible; adds a gtest failure per problem.
void expect_sensible(const Plan& plan) {
  std::vector<std::vector<std::vector<char>>> regions(plan.storeys.size());  // per storey, per room
  for (StoreyId s = 0; s < static_cast<StoreyId>(plan.storeys.size()); ++s) {
    StoreyRaster raster(plan, s);
    // Wall ends meet another wall (or close on themselves), except free-standing low walls.
    for (const Wall* w : raster.walls()) {
      if (w->height >= 0 || w->centre.front() == w->centre.back()) continue;
      for (Vec2 end : {w->centre.front(), w->centre.back()}) {
        double best = HUGE_VAL;
        for (const Wall* o : raster.walls())
          if (o != w) best = std::min(best, dist_to_wall(end, *o) - o->thickness / 2);
        EXPECT_LE(best, 1e-6) << w->where.str() << ": an end at (" << end.x << ", " << end.y
                              << ") meets no wall";
      }
    }
    // Openings stay clear of every other wall's thickness (and of their own wall's
    // other segments, i.e. its corners): sample the opening's footprint.
    for (const Wall* w : raster.walls()) {
      std::vector<double> seg_start{0};
      for (size_t k = 0; k + 1 < w->centre.size(); ++k)
        seg_start.push_back(seg_start.back() + length(w->centre[k + 1] - w->centre[k]));
      for (const Opening& o : w->openings) {
        const int seg = static_cast<int>(std::upper_bound(seg_start.begin(), seg_start.end(), o.at + 1e-9) -
                                         seg_start.begin()) - 1;
        const Vec2 a = w->centre[seg], b = w->centre[seg + 1];
        const Vec2 u = (1 / length(b - a)) * (b - a), n{-u.y, u.x};
        // The least clearance over samples of the opening's footprint, and where.
        double worst = HUGE_VAL;
        const Wall* hit = nullptr;
        Vec2 at;
        for (double t = 0; t <= o.width + 1e-9; t += 0.01)
          for (double side : {-0.5, 0.0, 0.5}) {
            const Vec2 p = a + (o.at - seg_start[seg] + t) * u + (side * w->thickness) * n;
            for (const Wall* other : raster.walls()) {
              const double d = (other == w ? dist_to_wall(p, *w, seg) : dist_to_wall(p, *other)) - other->thickness / 2;
              if (d < worst) worst = d, hit = other, at = p;
            }
          }
        if (hit) {
          EXPECT_GT(worst, 0.005) << o.where.str() << " runs into " << hit->where.str() << " at (" << at.x << ", "
                                  << at.y << ")";
        }
      }
    }
    // Rooms: label clear of walls, region enclosed, one label per region.
    std::vector<const Room*> rooms;
    for (const Room& r : plan.rooms)
      if (r.storey == s) rooms.push_back(&r);
    for (const Room* r : rooms) {
      for (const Wall* w : raster.walls())
        EXPECT_GT(dist_to_wall(*r->label, *w), w->thickness / 2 + 0.05) << r->where.str() << " label in " << w->where.str();
      bool leaks = false;
      regions[s].push_back(raster.fill(*r->label, leaks));
      EXPECT_FALSE(regions[s].back().empty()) << r->where.str() << ": label in a wall";
      EXPECT_FALSE(leaks) << r->where.str() << ": room is not enclosed";
      for (const Room* q : rooms)
        if (q != r) {
          EXPECT_FALSE(raster.inside(regions[s].back(), *q->label)) << r->where.str() << " contains " << q->where.str();
        }
    }
    // Floor openings: inside a room of their storey and of the one below.
    for (const FloorOpening& f : plan.floor_openings) {
      if (f.storey != s) continue;
      for (StoreyId t : {s, s - 1}) {
        StoreyRaster rt(plan, t);
        bool in_some = false;
        for (const Room& r : plan.rooms) {
          if (r.storey != t) continue;
          bool leaks = false;
          auto region = rt.fill(*r.label, leaks);
          bool all = true;
          for (Vec2 p : f.outline) all = all && rt.inside(region, p);
          in_some = in_some || all;
        }
        EXPECT_TRUE(in_some) << f.where.str() << " is not inside one room of storey " << t;
      }
    }
  }
  // The default view's eye is in a room.
  if (plan.view) {
    const Vec3 e = plan.view->eye;
    bool found = false;
    for (StoreyId s = 0; s < static_cast<StoreyId>(plan.storeys.size()); ++s) {
      const Storey& st = plan.storeys[s];
      if (e.z <= st.elevation || e.z >= st.elevation + st.height) continue;
      StoreyRaster raster(plan, s);
      for (const auto& region : regions[s]) found = found || raster.inside(region, {e.x, e.y});
    }
    EXPECT_TRUE(found) << plan.name << ": the view's eye is in no room";
  }
}

// The checker itself must catch what it is meant to catch: its failures, collected.
std::string sensible_failures(const std::string& text) {
  const Plan plan = parse_plan(text, "check.toml");
  ::testing::TestPartResultArray results;
  {
    ::testing::ScopedFakeTestPartResultReporter reporter(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    expect_sensible(plan);
  }
  std::string all;
  for (int i = 0; i < results.size(); ++i) all += std::string(results.GetTestPartResult(i).message()) + "\n";
  return all;
}

TEST(SensibleCheck, CatchesLeaksLooseEndsAndOpeningsAtCorners) {
  const std::string room = "[[room]]\nname = \"r\"\nat = [2, 2]\n";
  EXPECT_EQ(sensible_failures("[[wall]]\npath = [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]\n" + room), "");
  const std::string gap = sensible_failures("[[wall]]\npath = [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0.5]]\n" + room);
  EXPECT_NE(gap.find("room is not enclosed"), std::string::npos) << gap;
  EXPECT_NE(gap.find("meets no wall"), std::string::npos) << gap;
  const std::string corner = sensible_failures(
      "[[wall]]\npath = [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]\nopening = [{at = 0.05, width = 1}]\n" + room);
  EXPECT_NE(corner.find("runs into"), std::string::npos) << corner;
  const std::string label = sensible_failures("[[wall]]\npath = [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]\n"
                                              "[[wall]]\npath = [[0, 2], [4, 2]]\n" + room);
  EXPECT_NE(label.find("label in"), std::string::npos) << label;
}

// ---------------------------------------------------------------------------------
// The bundled plans.

TEST(BundledPlans, JonesHouse) {
  const Plan p = bundled("jones-house.toml");
  EXPECT_EQ(p.name, "Jones's house");
  ASSERT_EQ(p.storeys.size(), 1u);
  EXPECT_DOUBLE_EQ(p.storeys[0].height, 2.5);
  EXPECT_DOUBLE_EQ(p.storeys[0].slab, 0.3);
  ASSERT_EQ(p.walls.size(), 3u);
  for (const Wall& w : p.walls) EXPECT_EQ(w.thickness, 0.0) << w.name;  // Jones's walls of no thickness
  EXPECT_EQ(opening_count(p), 8);
  ASSERT_EQ(p.rooms.size(), 3u);
  EXPECT_EQ(p.rooms[0].name, "L");
  EXPECT_EQ(p.rooms[1].name, "K");
  EXPECT_EQ(p.rooms[2].name, "D");
  const Opening& hatch = p.walls[2].openings.at(0);
  EXPECT_EQ(hatch.kind, OpeningKind::Hatch);
  EXPECT_DOUBLE_EQ(hatch.sill, 0.9);
  EXPECT_DOUBLE_EQ(hatch.head, 1.5);
  EXPECT_EQ(p.walls[1].openings.size(), 2u);  // living → dining, living → kitchen
  for (const Opening& o : p.walls[1].openings) EXPECT_EQ(o.kind, OpeningKind::Door);
  ASSERT_TRUE(p.view.has_value());
  EXPECT_GE(p.ground, 0);
  EXPECT_GE(p.sky, 0);
  EXPECT_GE(p.roof, 0);
  EXPECT_EQ(p.walls[0].where.line > 0, true);
  expect_sensible(p);
}

TEST(BundledPlans, TwoStoreyHouse) {
  const Plan p = bundled("two-storey-house.toml");
  ASSERT_EQ(p.storeys.size(), 2u);
  EXPECT_DOUBLE_EQ(p.storeys[1].elevation, 2.9);
  EXPECT_EQ(p.walls.size(), 8u);
  EXPECT_EQ(p.rooms.size(), 8u);
  EXPECT_EQ(opening_count(p), 7 + 1 + 1 + 1 + 7 + 2 + 1);
  for (const Wall& w : p.walls) {
    EXPECT_GE(w.thickness, 0.2);
    EXPECT_LE(w.thickness, 0.3);
  }
  ASSERT_EQ(p.floor_openings.size(), 1u);
  EXPECT_EQ(p.floor_openings[0].storey, 1);
  EXPECT_EQ(p.lights.size(), 2u);
  // Windows on every side of each storey's outer wall (its four segments).
  for (const Wall& w : p.walls) {
    if (w.name != "outside") continue;
    std::vector<bool> side(4, false);
    for (const Opening& o : w.openings)
      if (o.kind == OpeningKind::Window) side[static_cast<int>(o.at / 10 >= 1) + static_cast<int>(o.at >= 18) + static_cast<int>(o.at >= 28)] = true;
    for (int s = 0; s < 4; ++s) EXPECT_TRUE(side[s]) << "storey " << w.storey << " side " << s;
  }
  expect_sensible(p);
}

TEST(BundledPlans, OfficeCorridor) {
  const Plan p = bundled("office-corridor.toml");
  EXPECT_EQ(p.walls.size(), 1u + 2u + 22u);
  EXPECT_EQ(p.rooms.size(), 25u);
  // Twelve doors on each side of the corridor, facing each other.
  const Wall& south = p.walls[1];
  const Wall& north = p.walls[2];
  ASSERT_EQ(south.openings.size(), 12u);
  ASSERT_EQ(north.openings.size(), 12u);
  for (size_t i = 0; i < 12; ++i) EXPECT_DOUBLE_EQ(south.openings[i].at, north.openings[i].at);
  for (const Wall& w : p.walls) EXPECT_GE(w.thickness, 0.15);
  expect_sensible(p);
}

TEST(BundledPlans, CurvedWalls) {
  const Plan p = bundled("curved-walls.toml");
  ASSERT_EQ(p.walls.size(), 4u);
  EXPECT_EQ(p.rooms.size(), 3u);
  const Wall& hall = p.walls[0];
  // Five straight segments, then the bay's pieces.
  ASSERT_GT(hall.from_arc.size(), 5u + 2u);
  for (size_t s = 0; s < hall.from_arc.size(); ++s) EXPECT_EQ(hall.from_arc[s], s >= 5) << s;
  EXPECT_EQ(hall.centre.front(), hall.centre.back());  // closed
  // The wing's first segment is at 30°.
  const Wall& wing = p.walls[2];
  const Vec2 d = wing.centre[1] - wing.centre[0];
  EXPECT_NEAR(std::atan2(d.y, d.x) * 180 / std::numbers::pi, 30.0, 1e-4);
  EXPECT_DOUBLE_EQ(p.walls[3].height, 1.0);  // the low garden wall
  EXPECT_LT(hall.height, 0);
  expect_sensible(p);
}

// The complete example in the format's documentation parses and makes sense.
TEST(BundledPlans, DocumentationExample) {
  std::ifstream in(std::string(AVENUES_SOURCE_DIR) + "/docs/PLAN_FORMAT.md");
  ASSERT_TRUE(in) << "docs/PLAN_FORMAT.md";
  std::stringstream doc;
  doc << in.rdbuf();
  const std::string md = doc.str();
  const size_t begin = md.find("```toml\n");
  ASSERT_NE(begin, std::string::npos);
  const size_t end = md.find("```", begin + 8);
  const Plan p = parse_plan(md.substr(begin + 8, end - begin - 8), "PLAN_FORMAT.md");
  EXPECT_EQ(p.name, "Cottage");
  EXPECT_EQ(p.walls.size(), 2u);
  EXPECT_EQ(p.rooms.size(), 2u);
  EXPECT_EQ(opening_count(p), 3);
  expect_sensible(p);
}

TEST(BundledPlans, GeneratedOfficeIsSensible) {
  for (auto [rows, cols] : {std::pair{1, 1}, {3, 4}, {4, 3}, {2, 1}}) {
    SCOPED_TRACE(std::to_string(rows) + "x" + std::to_string(cols));
    const Plan p = parse_plan(generate_office_toml(rows, cols), "office.toml");
    const int corridors = (rows + 1) / 2;
    EXPECT_EQ(p.rooms.size(), static_cast<size_t>(rows * cols + corridors + 1));
    int doors = 0;
    for (const Wall& w : p.walls)
      for (const Opening& o : w.openings) doors += o.kind == OpeningKind::Door;
    EXPECT_EQ(doors, rows * cols + corridors + 1);  // one per room, one per corridor, the entrance
    std::string last = "r";  // (built by +=: GCC 12's -Wrestrict misfires on "r" + std::string at -O3)
    last += std::to_string(rows - 1) + "_" + std::to_string(cols - 1);
    EXPECT_EQ(p.rooms.back().name, last);
    expect_sensible(p);
  }
  EXPECT_THROW(generate_office_toml(0, 3), std::invalid_argument);
}

TEST(BundledPlans, GeneratedOfficeScales) {
  const std::string text = generate_office_toml(100, 100);
  EXPECT_LT(text.size(), 2u << 20);  // small: long walls with many openings
  const auto t0 = std::chrono::steady_clock::now();
  const Plan p = parse_plan(text, "office-100x100.toml");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(p.rooms.size(), 10000u + 50u + 1u);
  EXPECT_LT(p.walls.size(), 6000u);
  // Its speed is the benchmarks' (bench/cells_bench.cpp), recorded here, not asserted.
  RecordProperty("parse_seconds", std::to_string(seconds));
}

// ---------------------------------------------------------------------------------
// Semantics.

const Wall& only_wall(const Plan& p) { return p.walls.at(0); }

TEST(PlanReader, ArcIsTessellatedWithinTolerance) {
  // The circle through (0,0), (5,5), (10,0) has centre (5,0) and radius 5; since
  // (0,0)→(5,5)→(10,0) turns right, the arc runs clockwise over the top half.
  for (double tol : {0.01, 0.001, 0.3, 20.0}) {
    SCOPED_TRACE(tol);
    const Plan p = parse_plan("arc_tolerance = " + std::to_string(tol) +
                                  "\n[[wall]]\npath = [[-3, 0], [0, 0], {through = [5, 5], to = [10, 0]}, [13, 0]]\n",
                              "arc.toml");
    const Wall& w = only_wall(p);
    ASSERT_EQ(w.from_arc.size() + 1, w.centre.size());
    EXPECT_FALSE(w.from_arc.front());
    EXPECT_FALSE(w.from_arc.back());
    const size_t pieces = w.from_arc.size() - 2;
    EXPECT_GE(pieces, 2u);
    EXPECT_EQ(w.centre[1], (Vec2{0, 0}));                    // endpoints exact
    EXPECT_EQ(w.centre[w.centre.size() - 2], (Vec2{10, 0}));
    const Vec2 c{5, 0};
    for (size_t k = 1; k + 1 < w.centre.size(); ++k) {
      EXPECT_NEAR(length(w.centre[k] - c), 5.0, 1e-9);  // on the circle
      EXPECT_GE(w.centre[k].y, -1e-12);                  // the upper half
    }
    double max_sagitta = 0;
    for (size_t s = 1; s + 1 < w.from_arc.size(); ++s) {
      ASSERT_TRUE(w.from_arc[s]);
      const double half = length(w.centre[s + 1] - w.centre[s]) / 2;
      max_sagitta = std::max(max_sagitta, 5.0 - std::sqrt(25.0 - half * half));
    }
    EXPECT_LE(max_sagitta, std::min(tol, 5.0) + 1e-12);
    if (tol == 0.01) {
      // Fewest pieces: one fewer would break the tolerance.
      const double theta = std::numbers::pi / static_cast<double>(pieces - 1);
      EXPECT_GT(5.0 * (1 - std::cos(theta / 2)), tol);
    }
  }
}

TEST(PlanReader, ArcDirectionAndFullCircle) {
  // Counter-clockwise: (0,0)→(5,-5)→(10,0) turns left; the arc dips below.
  const Plan p = parse_plan("[[wall]]\npath = [[0, 0], {through = [5, -5], to = [10, 0]}]\n", "a.toml");
  for (Vec2 q : only_wall(p).centre) EXPECT_LE(q.y, 1e-12);
  // A round room from two arcs: closed, not self-crossing.
  const Plan c = parse_plan(
      "[[wall]]\npath = [[0, 0], {through = [3, 3], to = [6, 0]}, {through = [3, -3], to = [0, 0]}]\n", "c.toml");
  EXPECT_EQ(only_wall(c).centre.front(), only_wall(c).centre.back());
  for (bool a : only_wall(c).from_arc) EXPECT_TRUE(a);
}

TEST(PlanReader, OpeningAfterAnArcIsPlacedByTrueLength) {
  // A quarter circle of radius 2 (true length π) between two straight 4 m segments.
  const Plan p = parse_plan(R"(arc_tolerance = 0.05
[[wall]]
path = [[0, 0], [4, 0], {through = [5.414213562373095, 0.585786437626905], to = [6, 2]}, [6, 6]]
[[wall.opening]]
at = 8.141592653589793
width = 1
)",
                            "q.toml");
  const Wall& w = only_wall(p);
  // Tessellated length up to the last straight segment, then 1 m along it.
  double tess = 0;
  for (size_t s = 0; s + 2 < w.centre.size(); ++s) tess += length(w.centre[s + 1] - w.centre[s]);
  EXPECT_LT(tess, 4 + std::numbers::pi);  // chords are shorter than the arc
  EXPECT_NEAR(w.openings.at(0).at, tess + 1.0, 1e-9);
}

TEST(PlanReader, UnitsAreConvertedToMetres) {
  const Plan p = parse_plan(R"(units = "cm"
arc_tolerance = 2
far_margin = 1000
[[storey]]
height = 300
slab = 25
[[wall]]
thickness = 20
height = 110
path = [[0, 0], [400, 0]]
[[wall.opening]]
kind = "window"
at = 100
width = 150
[[room]]
name = "r"
at = [200, 100]
[view]
eye = [100, 100, 160]
look = [300, 100, 160]
[[light]]
position = [200, 100, 250]
)",
                            "cm.toml");
  EXPECT_DOUBLE_EQ(p.arc_tolerance, 0.02);
  EXPECT_DOUBLE_EQ(p.far_margin, 10);
  EXPECT_DOUBLE_EQ(p.storeys[0].height, 3.0);
  EXPECT_DOUBLE_EQ(p.storeys[0].slab, 0.25);
  const Wall& w = only_wall(p);
  EXPECT_DOUBLE_EQ(w.thickness, 0.2);
  EXPECT_DOUBLE_EQ(w.height, 1.1);
  EXPECT_DOUBLE_EQ(w.centre[1].x, 4.0);
  EXPECT_DOUBLE_EQ(w.openings[0].at, 1.0);
  EXPECT_DOUBLE_EQ(w.openings[0].width, 1.5);
  EXPECT_DOUBLE_EQ(w.openings[0].sill, 0.9);  // defaults are in metres, whatever the units
  EXPECT_DOUBLE_EQ(w.openings[0].head, 2.1);
  EXPECT_DOUBLE_EQ(p.rooms[0].label->x, 2.0);
  EXPECT_DOUBLE_EQ(p.view->eye.z, 1.6);
  EXPECT_DOUBLE_EQ(p.lights[0].position.z, 2.5);

  const Plan f = parse_plan("units = \"ft\"\n[[wall]]\npath = [[0, 0], [10, 0]]\n", "ft.toml");
  EXPECT_DOUBLE_EQ(only_wall(f).centre[1].x, 3.048);
  const Plan i = parse_plan("units = \"in\"\n[[wall]]\npath = [[0, 0], [10, 0]]\n", "in.toml");
  EXPECT_DOUBLE_EQ(only_wall(i).centre[1].x, 0.254);
  const Plan mm = parse_plan("units = \"mm\"\n[[wall]]\npath = [[0, 0], [10, 0]]\n", "mm.toml");
  EXPECT_DOUBLE_EQ(only_wall(mm).centre[1].x, 0.01);
}

TEST(PlanReader, Defaults) {
  const Plan p = parse_plan(R"([materials.plain]
[materials.hex]
colour = "#808080"
[[wall]]
storey = "ground"
path = [[0, 0], [6, 0]]
[[wall.opening]]
at = 0.5
width = 0.9
[[wall.opening]]
kind = "window"
at = 2
width = 1
[[wall.opening]]
kind = "hatch"
at = 4
width = 1
[[wall]]
name = "second"
storey = "ground"
path = [[0, 0], [0, 6]]
[[floor_opening]]
storey = "upper"
outline = [[1, 1], [1, 2], [2, 2], [2, 1], [1, 1]]
[[object]]
storey = "upper"
mesh = "meshes/chair.off"
rotation = 45
scale = 2
[view]
eye = [1, 1, 1.6]
look = [2, 1, 1.6]
[[storey]]
name = "ground"
[[storey]]
name = "upper"
)",
                            "some/dir/house.toml");
  EXPECT_EQ(p.name, "house");  // the file's stem
  EXPECT_EQ(p.source, "some/dir/house.toml");
  EXPECT_DOUBLE_EQ(p.arc_tolerance, 0.01);
  EXPECT_DOUBLE_EQ(p.far_margin, 30);
  EXPECT_EQ(p.ground, -1);
  ASSERT_EQ(p.storeys.size(), 2u);
  EXPECT_DOUBLE_EQ(p.storeys[0].elevation, 0);
  EXPECT_DOUBLE_EQ(p.storeys[0].height, 2.5);
  EXPECT_DOUBLE_EQ(p.storeys[0].slab, 0.3);
  EXPECT_DOUBLE_EQ(p.storeys[1].elevation, 2.8);  // stacked on the first
  ASSERT_EQ(p.materials.size(), 2u);
  const Material& plain = p.materials[p.materials[0].name == "plain" ? 0 : 1];
  const Material& hex = p.materials[p.materials[0].name == "hex" ? 0 : 1];
  EXPECT_DOUBLE_EQ(plain.reflectance, 0.7);
  EXPECT_DOUBLE_EQ(plain.colour[0], 0.8);
  EXPECT_NEAR(hex.colour[0], 0.2158605, 1e-6);  // sRGB 128/255 → linear
  const Wall& w = p.walls[0];
  EXPECT_EQ(w.name, "wall 1");
  EXPECT_EQ(w.where.element, "wall 1");
  EXPECT_EQ(w.where.line, 4);
  EXPECT_EQ(w.where.file, "some/dir/house.toml");
  EXPECT_EQ(w.storey, 0);
  EXPECT_EQ(p.objects.at(0).storey, 1);
  EXPECT_DOUBLE_EQ(w.thickness, 0.2);
  EXPECT_LT(w.height, 0);
  EXPECT_EQ(w.material, -1);
  EXPECT_EQ(p.walls[1].where.element, "wall 'second'");
  ASSERT_EQ(w.openings.size(), 3u);
  EXPECT_EQ(w.openings[0].kind, OpeningKind::Door);
  EXPECT_EQ(w.openings[0].name, "opening 1");
  EXPECT_EQ(w.openings[0].where.element, "opening 1 of wall 1");
  EXPECT_DOUBLE_EQ(w.openings[0].sill, 0);
  EXPECT_DOUBLE_EQ(w.openings[0].head, 2.1);
  EXPECT_DOUBLE_EQ(w.openings[1].sill, 0.9);
  EXPECT_DOUBLE_EQ(w.openings[1].head, 2.1);
  EXPECT_DOUBLE_EQ(w.openings[2].sill, 1.0);
  EXPECT_DOUBLE_EQ(w.openings[2].head, 1.5);
  // The clockwise outline, with its closing point dropped, is stored counter-clockwise.
  const auto& o = p.floor_openings.at(0).outline;
  ASSERT_EQ(o.size(), 4u);
  double area2 = 0;
  for (size_t k = 0; k < o.size(); ++k) area2 += cross(o[k], o[(k + 1) % o.size()]);
  EXPECT_NEAR(area2, 2.0, 1e-12);
  const Object& obj = p.objects.at(0);
  EXPECT_EQ(obj.mesh, "some/dir/meshes/chair.off");
  EXPECT_DOUBLE_EQ(obj.rotation_deg.z, 45);
  EXPECT_DOUBLE_EQ(obj.scale.y, 2);
  EXPECT_DOUBLE_EQ(p.view->fov_deg, 60);
  EXPECT_EQ(p.rooms.size(), 0u);
}

TEST(PlanReader, SourceLocPrinting) {
  EXPECT_EQ((SourceLoc{"a.toml", 3, 7, "wall 'x'"}).str(), "a.toml:3:7 (wall 'x')");
  EXPECT_EQ((SourceLoc{"a.toml", 3, 0, ""}).str(), "a.toml:3");
  EXPECT_EQ((SourceLoc{"", 0, 0, "room 'k'"}).str(), "room 'k'");
  EXPECT_EQ((SourceLoc{"a.toml", 0, 0, "room 'k'"}).str(), "a.toml (room 'k')");
  EXPECT_STREQ(to_string(OpeningKind::Hatch), "hatch");
}

TEST(PlanReader, ReadPlanMissingFile) {
  try {
    read_plan("/nonexistent/plan.toml");
    FAIL() << "no error";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/plan.toml"), std::string::npos);
  }
}

// ---------------------------------------------------------------------------------
// Mistakes: each must name the file and the line, and say what is wrong.

void expect_error(const std::string& text, int line, const std::string& needle) {
  SCOPED_TRACE("expecting line " + std::to_string(line) + ": " + needle + "\n--- plan ---\n" + text);
  try {
    parse_plan(text, "bad.toml");
    ADD_FAILURE() << "no PlanError";
  } catch (const PlanError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.where().file, "bad.toml") << msg;
    EXPECT_EQ(e.where().line, line) << msg;
    EXPECT_EQ(msg.rfind("bad.toml:" + std::to_string(line) + ":", 0), 0u) << msg;
    EXPECT_NE(msg.find(needle), std::string::npos) << msg;
  }
}

const std::string kWall = "[[wall]]\npath = [[0, 0], [4, 0]]\n";  // two lines

TEST(PlanErrors, Syntax) { expect_error("name = \"x\"\nwall = [1,,2]\n", 2, "TOML syntax error"); }

TEST(PlanErrors, UnknownKeys) {
  expect_error("nmae = \"x\"\n" + kWall, 1, "unknown key 'nmae' in plan (did you mean 'name'?)");
  expect_error("[[wall]]\npath = [[0, 0], [1, 0]]\nthicknes = 0.2\n", 3,
               "unknown key 'thicknes' in wall 1 (did you mean 'thickness'?)");
  expect_error(kWall + "[[wall.opening]]\nat = 1\nwidth = 1\nsil = 0.5\n", 6, "unknown key 'sil' in opening 1 of wall 1");
  expect_error("[[wall]]\npath = [[0, 0], {through = [1, 1], to = [2, 0], via = 3}]\n", 2, "unknown key 'via'");
  expect_error("[materials.oak]\ncolor = [1, 1, 1]\n" + kWall, 2, "did you mean 'colour'?");
  expect_error(kWall + "[view]\neye = [0, 1, 1]\nlook = [1, 1, 1]\nfov_deg = 50\n", 6, "unknown key 'fov_deg' in view");
  expect_error("[[storey]]\nname = \"g\"\nhieght = 3\n" + kWall, 3, "did you mean 'height'?");
  expect_error(kWall + "[[room]]\nname = \"r\"\nat = [1, 1]\nlabel = \"x\"\n", 6, "unknown key 'label' in room 'r'");
  expect_error(kWall + "[[light]]\nposition = [1, 1, 1]\ncolor = [1, 1, 1]\n", 5, "in light 1");
  expect_error(kWall + "[[object]]\nmesh = \"m.off\"\nrotaton = 3\n", 5, "did you mean 'rotation'?");
  expect_error(kWall + "[[opening]]\nat = 1\n", 3, "unknown key 'opening' in plan");
  // The first one written is reported, not the first in alphabetical order.
  expect_error("[[wall]]\npath = [[0, 0], [1, 0]]\nzzz = 1\naaa = 2\n", 3, "unknown key 'zzz'");
}

TEST(PlanErrors, WrongTypes) {
  expect_error("[[wall]]\npath = [[0, 0], [1, 0]]\nthickness = \"thick\"\n", 3, "'thickness' must be a number, not a string");
  expect_error("[[wall]]\npath = [[0, 0],\n  [1, \"a\"]]\n", 3, "must be a number, not a string");
  expect_error("[[wall]]\npath = [[0, 0], [1, 0, 2]]\n", 2, "must be an array of 2 numbers");
  expect_error("wall = 3\n", 1, "must be an array of tables");
  expect_error("name = 7\n" + kWall, 1, "'name' must be a string, not an integer");
  expect_error(kWall + "[[wall.opening]]\nkind = \"portal\"\nat = 1\nwidth = 1\n", 4, "unknown opening kind 'portal'");
  expect_error("units = \"furlong\"\n" + kWall, 1, "unknown units 'furlong'");
  expect_error("[materials.oak]\ncolour = \"#12345\"\n" + kWall, 2, "#rrggbb");
  expect_error("[materials.oak]\ncolour = [1.5, 0, 0]\n" + kWall, 2, "must be in [0, 1]");
  expect_error("[[wall]]\npath = [{through = [1, 1], to = [2, 0]}, [3, 0]]\n", 2, "must start with a point");
}

TEST(PlanErrors, NonFiniteNumbers) {
  expect_error("[[wall]]\npath = [[0, 0], [1, 0]]\nthickness = nan\n", 3, "must be a finite number");
  expect_error("[[wall]]\npath = [[0, 0],\n [inf, 0]]\n", 3, "must be a finite number, not inf");
  expect_error(kWall + "[[wall.opening]]\nat = 1\nwidth = -inf\n", 5, "finite");
  expect_error("arc_tolerance = nan\n" + kWall, 1, "finite");
  expect_error(kWall + "[[light]]\nposition = [1, 1, 1]\nintensity = +inf\n", 5, "finite");
}

TEST(PlanErrors, AbsurdNumbers) {
  expect_error("[[wall]]\npath = [[0, 0], [2e8, 0]]\n", 2, "beyond");
  expect_error("units = \"mm\"\n[[wall]]\npath = [[0, 0], [1e12, 0]]\n", 3, "beyond");
  expect_error(kWall + "[[room]]\nname = \"r\"\nat = [-1e9, 0]\n", 5, "beyond");
  expect_error("[[wall]]\npath = [[0, 0], [1, 0]]\nthickness = -0.1\n", 3, "'thickness' must be >= 0");
  expect_error("[[storey]]\nheight = 0\n" + kWall, 2, "'height' (floor to ceiling) must be > 0");
  expect_error("[[storey]]\nheight = -2\n" + kWall, 2, "must be > 0");
  expect_error("[[storey]]\nslab = -0.1\n" + kWall, 2, "'slab' must be >= 0");
  expect_error("[[wall]]\npath = [[0, 0], [1, 0]]\nheight = 0\n", 3, "'height' must be > 0");
  expect_error("[[wall]]\npath = [[0, 0], [1, 0]]\nheight = 3\n", 3, "above the ceiling");
  expect_error("arc_tolerance = 0\n" + kWall, 1, "'arc_tolerance' must be > 0");
  expect_error("far_margin = -5\n" + kWall, 1, "'far_margin' must be > 0");
  expect_error(kWall + "[[wall.opening]]\nat = 1\nwidth = 0\n", 5, "'width' must be > 0");
  expect_error(kWall + "[[wall.opening]]\nat = -1\nwidth = 1\n", 4, "'at' must be >= 0");
  expect_error(kWall + "[view]\neye = [1, 1, 1]\nlook = [2, 1, 1]\nfov = 180\n", 6, "'fov' must be in (0, 179]");
  expect_error(kWall + "[[light]]\nposition = [1, 1, 1]\nintensity = 0\n", 5, "'intensity' must be > 0");
  expect_error("[materials.m]\nreflectance = 1.2\n" + kWall, 2, "'reflectance' must be in [0, 1]");
  expect_error(kWall + "[[object]]\nmesh = \"m.off\"\nscale = [1, 0, 1]\n", 5, "'scale' factors must be > 0");
}

TEST(PlanErrors, OpeningsMustFitTheirSegment) {
  const std::string corner = "[[wall]]\npath = [[0, 0], [2, 0], [2, 5]]\n";
  expect_error(corner + "[[wall.opening]]\nat = 0\nwidth = 3\n", 5, "3 m wide but its wall segment is only 2 m long");
  expect_error(corner + "[[wall.opening]]\nat = 1.5\nwidth = 1\n", 4, "runs across a corner");
  expect_error(kWall + "[[wall.opening]]\nat = 3.5\nwidth = 1\n", 4, "runs past the end of the wall");
  expect_error(kWall + "[[wall.opening]]\nat = 4\nwidth = 1\n", 4, "past the end of wall 1");
  const std::string arc = "[[wall]]\npath = [[0, 0], [4, 0], {through = [5, 1], to = [4, 2]}, [0, 2]]\n";
  expect_error(arc + "[[wall.opening]]\nat = 3.5\nwidth = 1\n", 4, "runs onto an arc");
  expect_error(arc + "[[wall.opening]]\nat = 4.5\nwidth = 0.2\n", 4, "lies on an arc");
  // At the segment's very start and very end is fine.
  EXPECT_NO_THROW(parse_plan(corner + "[[wall.opening]]\nat = 0\nwidth = 2\n[[wall.opening]]\nat = 2\nwidth = 5\n", "ok.toml"));
}

TEST(PlanErrors, OverlappingOpenings) {
  expect_error(kWall + "[[wall.opening]]\nname = \"a\"\nat = 1\nwidth = 1\n\n[[wall.opening]]\nname = \"b\"\nat = 1.5\nwidth = 1\n",
               8, "opening 'b' of wall 1 overlaps opening 'a' of wall 1");
  // Reported at the later one in the file, even when it lies first along the wall.
  expect_error(kWall + "opening = [{at = 2.5, width = 1},\n  {at = 2, width = 1}]\n", 4, "overlaps");
  EXPECT_NO_THROW(parse_plan(kWall + "opening = [{at = 1, width = 1}, {at = 2, width = 1}]\n", "ok.toml"));  // touching
}

TEST(PlanErrors, SillAndHead) {
  expect_error(kWall + "[[wall.opening]]\nkind = \"window\"\nat = 1\nwidth = 1\nsill = 2.0\nhead = 1.5\n", 7,
               "'sill' (2 m) must be below 'head' (1.5 m)");
  expect_error(kWall + "[[wall.opening]]\nat = 1\nwidth = 1\nhead = 0\n", 6, "must be below 'head'");
  expect_error(kWall + "[[wall.opening]]\nat = 1\nwidth = 1\nhead = 2.6\n", 6, "'head' 2.6 m is above the ceiling");
  expect_error("[[storey]]\nheight = 2\n" + kWall + "[[wall.opening]]\nat = 1\nwidth = 1\n", 5, "above the ceiling");
  expect_error(kWall + "[[wall.opening]]\nat = 1\nwidth = 1\nsill = -0.5\n", 6, "'sill' must be >= 0");
}

TEST(PlanErrors, SelfIntersectingWall) {
  expect_error("[[wall]]\npath = [\n  [0, 0],\n  [4, 0],\n  [4, 4],\n  [2, -2],\n]\n", 6, "crosses itself");
  expect_error("[[wall]]\npath = [[0, 0], [4, 0], [2, 0]]\n", 2, "crosses itself");           // doubles back
  expect_error("[[wall]]\npath = [[0, 0], [4, 0], [4, 4], [0, 4], [2, 0]]\n", 2, "crosses itself");  // touches
  expect_error("[[wall]]\npath = [[0, 0], [4, 0], [4, 0]]\n", 2, "repeats the point before it");
  // An arc bulging back across the wall's own first segment.
  expect_error("[[wall]]\npath = [[0, 0], [4, 0],\n {through = [2, 3], to = [2, -1]}]\n", 3, "crosses itself");
  EXPECT_NO_THROW(parse_plan("[[wall]]\npath = [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]\n", "ok.toml"));  // closed
}

TEST(PlanErrors, UnknownNames) {
  const std::string storeys = "[[storey]]\nname = \"first\"\n[[storey]]\nname = \"second\"\n";
  expect_error(storeys + "[[wall]]\nstorey = \"frist\"\npath = [[0, 0], [1, 0]]\n", 6,
               "unknown storey 'frist' (did you mean 'first'?)");
  expect_error(storeys + "[[wall]]\npath = [[0, 0], [1, 0]]\n", 5, "wall 1 needs 'storey' (the plan has 2 storeys)");
  expect_error("[materials.oak]\n[[wall]]\nmaterial = \"oka\"\npath = [[0, 0], [1, 0]]\n", 3,
               "unknown material 'oka' (did you mean 'oak'?)");
  expect_error("ground = \"grass\"\n" + kWall, 1, "unknown material 'grass' (the plan defines no [materials])");
  expect_error(kWall + "[[room]]\nname = \"r\"\nat = [1, 1]\nfloor = \"tiles\"\n", 6, "unknown material 'tiles'");
}

TEST(PlanErrors, DuplicateNames) {
  expect_error(kWall + "[[room]]\nname = \"k\"\nat = [1, 1]\n[[room]]\nname = \"k\"\nat = [2, 1]\n", 7,
               "duplicate room name 'k'");
  expect_error("[[wall]]\nname = \"w\"\npath = [[0, 0], [1, 0]]\n[[wall]]\nname = \"w\"\npath = [[0, 1], [1, 1]]\n", 5,
               "duplicate wall name 'w'");
  expect_error("[[storey]]\nname = \"a\"\n[[storey]]\nname = \"a\"\n" + kWall, 4, "duplicate storey name 'a'");
  expect_error(kWall + "opening = [{name = \"d\", at = 0, width = 1},\n {name = \"d\", at = 2, width = 1}]\n", 4,
               "duplicate opening name 'd'");
  expect_error(kWall + "[[light]]\nname = \"l\"\nposition = [1, 1, 1]\n[[light]]\nname = \"l\"\nposition = [1, 1, 1]\n",
               7, "duplicate light name 'l'");
  // The same room name on two storeys is fine.
  EXPECT_NO_THROW(parse_plan(
      "[[storey]]\nname = \"a\"\n[[storey]]\nname = \"b\"\n[[wall]]\nstorey = \"a\"\npath = [[0, 0], [1, 0]]\n"
      "[[room]]\nname = \"k\"\nstorey = \"a\"\nat = [1, 1]\n[[room]]\nname = \"k\"\nstorey = \"b\"\nat = [1, 1]\n",
      "ok.toml"));
}

TEST(PlanErrors, EmptyPlan) {
  expect_error("", 1, "the plan has no walls");
  expect_error("name = \"x\"\n[[room]]\nname = \"r\"\nat = [1, 1]\n", 1, "no walls");
}

TEST(PlanErrors, DegenerateArc) {
  expect_error("[[wall]]\npath = [[0, 0],\n  {through = [1, 0], to = [2, 0]}]\n", 3, "collinear");
  expect_error("[[wall]]\npath = [[0, 0], {through = [0, 0], to = [2, 0]}]\n", 2, "collinear");
  expect_error("[[wall]]\npath = [[0, 0], {through = [1, 1], to = [0, 0]}]\n", 2, "collinear");
  expect_error("[[wall]]\npath = [[0, 0], {through = [1, 1]}]\n", 2, "needs 'to'");
  expect_error("arc_tolerance = 1e-12\n[[wall]]\npath = [[0, 0], {through = [1000, 1000], to = [2000, 0]}]\n", 3,
               "more than");
}

TEST(PlanErrors, FloorOpenings) {
  expect_error(kWall + "[[floor_opening]]\noutline = [[1, 1], [2, 1], [2, 2]]\n", 3, "'ground' is the lowest storey");
  const std::string two = "[[storey]]\nname = \"a\"\n[[storey]]\nname = \"b\"\n[[wall]]\nstorey = \"a\"\npath = [[0, 0], [1, 0]]\n";
  expect_error(two + "[[floor_opening]]\nstorey = \"a\"\noutline = [[1, 1], [2, 1], [2, 2]]\n", 9, "lowest storey");
  expect_error(two + "[[floor_opening]]\nstorey = \"b\"\noutline = [[0, 0], [2, 2], [2, 0], [0, 2]]\n", 10,
               "not a simple polygon");
  expect_error(two + "[[floor_opening]]\nstorey = \"b\"\noutline = [[0, 0], [1, 0], [2, 0]]\n", 10, "not a simple polygon");
  expect_error(two + "[[floor_opening]]\nstorey = \"b\"\noutline = [[0, 0], [1, 0]]\n", 10, "at least 3");
  expect_error(two + "[[floor_opening]]\nstorey = \"b\"\noutline = [[0, 0], [2, 0], [2, 2], [1, 0]]\n", 10,
               "not a simple polygon");
}

TEST(PlanErrors, StoreysStack) {
  expect_error("[[storey]]\nheight = 2.5\nslab = 0.3\n[[storey]]\nelevation = 3.0\n" + kWall, 5,
               "'elevation' is 3 m but storey 'storey 1' below ends (elevation + height + slab) at 2.8 m");
  EXPECT_NO_THROW(parse_plan("[[storey]]\nelevation = -3\n[[storey]]\nelevation = -0.2\n[[wall]]\nstorey = \"storey 1\"\n"
                             "path = [[0, 0], [1, 0]]\n",
                             "ok.toml"));
}

TEST(PlanErrors, MissingRequiredKeys) {
  expect_error("[[wall]]\nthickness = 0.1\n", 1, "wall 1 needs 'path'");
  expect_error(kWall + "\n[[room]]\nat = [1, 1]\n", 4, "room 1 needs a 'name'");
  expect_error(kWall + "[[wall.opening]]\nwidth = 1\n", 3, "needs 'at'");
  expect_error(kWall + "[view]\neye = [1, 1, 1]\n", 3, "view needs 'look'");
  expect_error(kWall + "[[object]]\nname = \"chair\"\n", 3, "object 'chair' needs 'mesh'");
}

}  // namespace
}  // namespace avenues
