// Tests of the architect's drawings (`avenues drawing`, render/architectural_drawing.h) and
// of `view --projection parallel`, through the real executable (run by argv, no shell:
// tests/avenues_run.h):
// every bundled plan in the four kinds and every format, each file read back by an
// independent reader (SVG by pugixml, PDF by poppler's pdfinfo and pdftotext, DXF by
// dxflib, HPGL by a parser, pictures by the raster reader); parallel rays cast through the
// frame the stats state; Jones's house in section; the two-storey house in plan against
// the plan SVG's cut walls.
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>

#include "app/plan_source.h"
#include "cells/build_cells.h"
#include "plans/generate.h"
#include "render/architectural_drawing.h"
#include "render/halftone.h"
#include "render/plan_drawing.h"
#include "render/raster.h"
#include "render/stroke_merge.h"
#include "tests/avenues_run.h"
#include "tests/drawing_readers.h"
#include "tests/ray_oracle.h"
#include "tests/test_files.h"
#include "tests/test_meshes.h"

namespace fs = std::filesystem;
using namespace avenues;
using avenues::testing::Outcome;
using avenues::testing::slurp;

namespace {

const std::string kSource = AVENUES_SOURCE_DIR;
/// Every vector format and two of the pictures'.
constexpr const char* kAllFormats[] = {".svg", ".pdf", ".eps", ".dxf", ".hpgl", ".png", ".pgm"};

class ArchitecturalDrawing : public avenues::testing::AvenuesRun {
 protected:
  nlohmann::json stats(const std::string& name) { return nlohmann::json::parse(slurp(path(name))); }
  void check_file(const std::string& file, bool cut, bool labels);
  void draw_in_every_format(const std::string& cells, const std::vector<std::string>& kind, bool cut, bool labels);
};

std::vector<std::string> bundled_plans() {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(kSource + "/plans"))
    if (e.path().extension() == ".toml") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// A section line across the middle of the plan's building, west to east (looking north).
std::string section_across(const CellComplex& c) {
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (const Cell& cell : c.cells)
    if (cell.kind == CellKind::Room)
      for (Vec2 p : cell.footprint) x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  const double y = 0.5 * (y0 + y1) + 0.013;  // off the grid of walls
  return std::to_string(x0 - 1) + "," + std::to_string(y) + "," + std::to_string(x1 + 1) + "," + std::to_string(y);
}

/// Checks one written file by its format's own reader; `cut` when the drawing has a cut layer.
void ArchitecturalDrawing::check_file(const std::string& file, bool cut, bool labels) {
  const std::string ext = fs::path(file).extension().string();
  SCOPED_TRACE(file);
  ASSERT_TRUE(fs::exists(file));
  if (ext == ".svg") {
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(file.c_str())) << "not well-formed XML";
    EXPECT_GT(doc.select_nodes("/svg/g[@id='beyond']//line").size(), 0u);
    EXPECT_EQ(bool(doc.select_node("/svg/g[@id='cut']//line")), cut);
    EXPECT_EQ(bool(doc.select_node("/svg/g[@id='cut']/path[@fill-rule='evenodd']")), cut);
    if (labels) {
      EXPECT_GT(doc.select_nodes("/svg/g[@id='annotation']/text").size(), 0u);
    }
  } else if (ext == ".pdf") {
    const Outcome info = run_argv({"pdfinfo", file});
    EXPECT_EQ(info.status, 0) << info.err;
    EXPECT_NE(info.out.find("Pages:           1"), std::string::npos) << info.out;
    if (labels) {
      const Outcome text = run_argv({"pdftotext", file, "-"});
      EXPECT_EQ(text.status, 0) << text.err;
      EXPECT_NE(text.out.find("m\xc2\xb2"), std::string::npos) << text.out;  // an area
    }
  } else if (ext == ".eps") {
    const std::string s = slurp(file);
    EXPECT_EQ(s.rfind("%!PS-Adobe-3.0 EPSF-3.0", 0), 0u);
    EXPECT_NE(s.find("%%BoundingBox:"), std::string::npos);
  } else if (ext == ".dxf") {
    avenues::testing::DxfCounter counter;
    DL_Dxf dxf;
    ASSERT_TRUE(dxf.in(file, &counter));
    EXPECT_GT(counter.lines, 0);
    EXPECT_TRUE(counter.layers_declared.count("beyond"));
    EXPECT_EQ(counter.layers_declared.count("cut"), cut ? 1u : 0u);
    EXPECT_EQ(counter.layers_used.count("cut"), cut ? 1u : 0u);
    if (labels) {
      EXPECT_TRUE(counter.layers_used.count("annotation"));
    }
  } else if (ext == ".hpgl") {
    const avenues::testing::Plot plot = avenues::testing::parse_hpgl(slurp(file));
    EXPECT_GT(plot.segments, 0);
    EXPECT_EQ(plot.segments_of_pen.count(3), cut ? 1u : 0u);  // pen 3: the cut
    if (labels) {
      EXPECT_FALSE(plot.labels.empty());
    }
  } else {
    const Image img = read_image(file);
    EXPECT_GT(img.width, 0);
    EXPECT_GT(img.height, 0);
  }
}

/// One run of `drawing` of this kind writing every format (-o repeated), each file then
/// read back by check_file.
void ArchitecturalDrawing::draw_in_every_format(const std::string& cells, const std::vector<std::string>& kind, bool cut,
                                                bool labels) {
  std::vector<std::string> args{"drawing", cells, "--scale", "1:100"};
  args.insert(args.end(), kind.begin(), kind.end());
  for (const char* ext : kAllFormats) args.insert(args.end(), {"-o", path(std::string("drawing") + ext)});
  const Outcome r = run(args);
  ASSERT_EQ(r.status, 0) << kind[0] << ": " << r.err;
  for (const char* ext : kAllFormats) {
    check_file(path(std::string("drawing") + ext), cut, labels);
    fs::remove(path(std::string("drawing") + ext));
  }
}

}  // namespace

// Every bundled plan, the four kinds, every format, read back. The plan is decomposed
// once (saved cells) so that each of the runs only loads it.
TEST_F(ArchitecturalDrawing, EveryKindOfEveryBundledPlanInEveryFormatReadsBack) {
  for (const std::string& plan : bundled_plans()) {
    SCOPED_TRACE(plan);
    const std::string cells = path("plan.cells");
    ASSERT_EQ(run({"cells", plan, "--save", cells}).status, 0);
    const CellComplex c = app::load_plan_source(cells).complex;
    struct Kind {
      std::vector<std::string> args;
      bool cut, labels;
    };
    const std::vector<Kind> kinds = {{{"--plan", "0"}, true, true},
                                     {{"--section", section_across(c)}, true, false},
                                     {{"--elevation", "south"}, false, false},
                                     {{"--axonometric", "30,35", "--cut-height", "1.2"}, true, false}};
    for (const Kind& k : kinds) {
      SCOPED_TRACE(k.args[0]);
      draw_in_every_format(cells, k.args, k.cut, k.labels);
      if (HasFatalFailure()) return;
    }
  }
}

// The same for Debian's Sweet Home 3D homes (furnished, lit, several levels).
TEST_F(ArchitecturalDrawing, EveryKindOfEverySweetHomeHomeInEveryFormatReadsBack) {
  const fs::path homes = "/usr/local/share/avenues/sweethome3d-examples";
  if (!fs::exists(homes)) GTEST_SKIP() << "no " << homes << " (.ci/install-deps installs sweethome3d)";
  int tried = 0;
  for (const auto& e : fs::directory_iterator(homes)) {
    if (e.path().extension() != ".xml") continue;
    SCOPED_TRACE(e.path().string());
    ++tried;
    const std::string cells = path("home.cells");
    ASSERT_EQ(run({"cells", e.path().string(), "--save", cells}).status, 0);
    const CellComplex c = app::load_plan_source(cells).complex;
    // The plan of the entrance storey (the floor nearest the ground: a basement may show
    // nothing beyond its cut), the axonometric cut 1.2 m above the lowest floor.
    size_t entrance = 0;
    for (size_t k = 0; k < c.storeys.size(); ++k)
      if (std::fabs(c.storeys[k].elevation) < std::fabs(c.storeys[entrance].elevation)) entrance = k;
    const std::vector<std::pair<std::vector<std::string>, bool>> kinds = {
        {{"--plan", std::to_string(entrance)}, true},
        {{"--section", section_across(c)}, true},
        {{"--elevation", "south"}, false},
        {{"--axonometric", "30,35", "--cut-height", "1.2"}, true}};
    for (const auto& [args, cut] : kinds) {
      SCOPED_TRACE(args[0]);
      draw_in_every_format(cells, args, cut, args[0] == "--plan");
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_EQ(tried, 9);
}

// An independent ray cast: parallel rays through the frame the stats state (its origin,
// right, up and direction), against every opaque polygon, cross no cell missing from
// `visible` — for a plan, a section and an axonometric with a cut, in two kernels.
TEST_F(ArchitecturalDrawing, ParallelRaysThroughTheStatedFrameFindNoCellMissing) {
  const std::string plan = kSource + "/plans/jones-house.toml";
  const CellComplex c = app::load_plan_source(plan).complex;
  for (const std::vector<std::string>& kind :
       {std::vector<std::string>{"--plan", "ground"}, {"--section", "-1,2.7,10,2.7"}, {"--section", "5,0,5,6"},
        {"--axonometric", "225,30", "--cut-height", "1.5"}, {"--elevation", "west"}})
    for (const char* kernel : {"double", "exact"}) {
      std::vector<std::string> args{"drawing", plan, "-o", path("d.svg"), "--stats-json", path("d.json"), "--kernel", kernel};
      args.insert(args.end(), kind.begin(), kind.end());
      const Outcome r = run(args);
      ASSERT_EQ(r.status, 0) << r.err;
      const nlohmann::json j = stats("d.json");
      auto vec = [&](const char* k) { return Vec3{j["frame"][k][0], j["frame"][k][1], j["frame"][k][2]}; };
      avenues::testing::ParallelFrame f{vec("origin"), vec("right"), vec("up"), vec("direction"), 0, 0};
      EXPECT_NEAR(length(f.direction), 1, 1e-12);
      f.nx = int(std::ceil(length(f.right) * 10)), f.ny = int(std::ceil(length(f.up) * 10));  // 10 rays a metre
      const std::vector<CellId> visible = j["visible"].get<std::vector<CellId>>();
      const auto res = avenues::testing::check_parallel_rays(c, f, visible);
      EXPECT_GT(res.rays, 100);
      EXPECT_EQ(res.missing, 0) << kind[0] << " " << kind[1] << " (" << kernel << ")";
      EXPECT_GT(j["cells_cut"].get<int>(), 0);
      for (const char* k : {"avenues", "visibility_us", "render_us"}) EXPECT_TRUE(j.contains(k)) << k;
    }
}

// A scene of meshes has no storeys: its plan (--plan 0) is the whole model cut --cut-height
// above its lowest point, and the parallel rays through its frame find no cell missing; a
// storey named is refused, saying why.
TEST_F(ArchitecturalDrawing, AMeshScenesPlanIsTheWholeModelCutAboveItsLowestPoint) {
  const std::string scene = avenues::testing::outside_path("meshes/CornellBox-Original.obj");
  const CellComplex c = app::load_plan_source(scene).complex;
  ASSERT_TRUE(c.storeys.empty());
  const Outcome r = run({"drawing", scene, "--plan", "0", "--cut-height", "0.5", "-o", path("p.svg"), "--stats-json",
                         path("p.json")});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = stats("p.json");
  auto vec = [&](const char* k) { return Vec3{j["frame"][k][0], j["frame"][k][1], j["frame"][k][2]}; };
  EXPECT_NEAR(vec("origin").z, building_bounds(c).lo.z + 0.5, 1e-9);
  avenues::testing::ParallelFrame f{vec("origin"), vec("right"), vec("up"), vec("direction"), 0, 0};
  f.nx = int(std::ceil(length(f.right) * 20)), f.ny = int(std::ceil(length(f.up) * 20));
  const auto res = avenues::testing::check_parallel_rays(c, f, j["visible"].get<std::vector<CellId>>());
  EXPECT_GT(res.rays, 100);
  EXPECT_EQ(res.missing, 0);
  EXPECT_GT(j["cells_cut"].get<int>(), 0);
  const Outcome bad = run({"drawing", scene, "--plan", "ground", "-o", path("q.svg")});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("has no storeys (a mesh scene); --plan 0 cuts the whole model"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("q.svg")));
}

// A drawing too large for the page at its scale is refused, and the error says which of
// the usual scales fits; where none does (a model in millimetres read as metres, say), it
// says how large the model is and that a mesh's unit can be given. Nothing is written.
TEST_F(ArchitecturalDrawing, ADrawingTooLargeForItsScaleNamesTheScaleThatFits) {
  // A closed box, as a mesh: 600 m by 10 m by 3 m, and the same in kilometres.
  auto box = [](double x, double y, double z) {
    std::ostringstream obj;
    for (int k = 0; k < 8; ++k) obj << "v " << (k & 1 ? x : 0) << " " << (k & 2 ? y : 0) << " " << (k & 4 ? z : 0) << "\n";
    obj << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    return obj.str();
  };
  const std::string long_shed = write("shed.obj", box(600, 10, 3)), far = write("far.obj", box(20000, 10, 3));
  const Outcome r = run({"drawing", long_shed, "--plan", "0", "-o", path("shed.svg")});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--scale 1:50: the drawing would be"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1:100 fits"), std::string::npos) << r.err;  // 602 m at 4 px a paper mm: 1:74 at least
  EXPECT_FALSE(fs::exists(path("shed.svg")));
  const Outcome fits = run({"drawing", long_shed, "--plan", "0", "--scale", "1:100", "-o", path("shed.svg")});
  EXPECT_EQ(fits.status, 0) << fits.err;
  EXPECT_TRUE(fs::exists(path("shed.svg")));
  const Outcome none = run({"drawing", far, "--elevation", "south", "--scale", "1:500", "-o", path("far.svg")});
  EXPECT_EQ(none.status, 2);
  EXPECT_NE(none.err.find("not even 1:500 fits"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("--unit"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(path("far.svg")));
}

// Jones's house in section along x = 4, looking east through both doors of the living
// room's east wall: the outer sheets (y = 0 and y = 6), floor and ceiling are cut, and
// the kitchen and the dining room are seen beyond. Along the wall itself (x = 5) the
// doors lie in the cut, and the same rooms are seen through them.
TEST_F(ArchitecturalDrawing, SectionOfJonesHouseThroughBothDoorsShowsTheCutSheetsAndTheRoomsBeyond) {
  const std::string plan = kSource + "/plans/jones-house.toml";
  const CellComplex c = app::load_plan_source(plan).complex;
  for (const char* line : {"4,6,4,0", "5,6,5,0"}) {
    SCOPED_TRACE(line);
    const Outcome r = run({"drawing", plan, "--section", line, "-o", path("s.svg"), "--stats-json", path("s.json")});
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json j = stats("s.json");
    std::set<std::string> rooms;
    for (CellId id : j["visible"].get<std::vector<CellId>>())
      if (c.cells[size_t(id)].room >= 0) rooms.insert(c.rooms[size_t(c.cells[size_t(id)].room)].name);
    EXPECT_TRUE(rooms.count("K"));
    EXPECT_TRUE(rooms.count("D"));
    // The frame: the picture plane is the cut, looking east.
    EXPECT_NEAR(j["frame"]["direction"][0].get<double>(), 1, 1e-12);
    EXPECT_NEAR(j["frame"]["origin"][0].get<double>(), line[0] - '0', 1e-9);
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(path("s.svg").c_str()));
    // Cut sheets: vertical cut strokes (the outer walls at y = 0 and y = 6), two at least.
    int vertical = 0;
    for (const auto& n : doc.select_nodes("/svg/g[@id='cut']//line")) {
      const double dx = n.node().attribute("x2").as_double() - n.node().attribute("x1").as_double();
      const double dy = n.node().attribute("y2").as_double() - n.node().attribute("y1").as_double();
      vertical += std::fabs(dx) < 1e-6 && std::fabs(dy) > 10;  // over 10 mm on paper (0.5 m at 1:50)
    }
    EXPECT_GE(vertical, 2);
    // Beyond: the jambs of both doors, seen from the cut (four vertical outlines at least).
    int jambs = 0;
    for (const auto& n : doc.select_nodes("/svg/g[@id='beyond']//line"))
      jambs += std::fabs(n.node().attribute("x2").as_double() - n.node().attribute("x1").as_double()) < 1e-6;
    EXPECT_GE(jambs, 4);
  }
}

// The two-storey house in plan at 1.2 m: the cut strokes are the plan SVG's cut walls
// (render/plan_drawing.h), storey by storey — every point of one lies on the other, once
// both are brought to the unit square of their common bounds.
TEST_F(ArchitecturalDrawing, PlanOfTheTwoStoreyHouseMatchesThePlanSvgWalls) {
  const std::string plan = kSource + "/plans/two-storey-house.toml";
  const CellComplex c = app::load_plan_source(plan).complex;
  pugi::xml_document plan_doc;
  ASSERT_TRUE(plan_doc.load_string(plan_svg(c).c_str()));
  const auto cut_groups = plan_doc.select_nodes("//g[@class='cut']");
  ASSERT_EQ(cut_groups.size(), c.storeys.size());
  using Seg = std::array<Vec2, 2>;
  auto lines_of = [](const pugi::xpath_node_set& nodes) {
    std::vector<Seg> out;
    for (const auto& n : nodes)
      out.push_back({Vec2{n.node().attribute("x1").as_double(), n.node().attribute("y1").as_double()},
                     Vec2{n.node().attribute("x2").as_double(), n.node().attribute("y2").as_double()}});
    return out;
  };
  auto normalised = [](std::vector<Seg> v) {
    Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
    for (const Seg& s : v)
      for (Vec2 p : s) lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)}, hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    const double k = 1 / std::max(hi.x - lo.x, hi.y - lo.y);
    for (Seg& s : v)
      for (Vec2& p : s) p = k * (p - lo);
    return v;
  };
  auto distance = [](Vec2 p, const Seg& s) {
    const Vec2 d = s[1] - s[0];
    const double t = std::clamp(dot(p - s[0], d) / std::max(dot(d, d), 1e-300), 0.0, 1.0);
    return length(p - (s[0] + t * d));
  };
  // Sample points of a's segments off every segment of b; `missed` gets those segments.
  auto covered = [&](const std::vector<Seg>& a, const std::vector<Seg>& b, std::vector<size_t>* missed = nullptr) {
    int misses = 0;
    for (size_t i = 0; i < a.size(); ++i) {
      const Seg& s = a[i];
      int here = 0;
      for (int k = 0; k <= 8; ++k) {
        const Vec2 p = s[0] + (k / 8.0) * (s[1] - s[0]);
        double best = HUGE_VAL;
        for (const Seg& t : b) best = std::min(best, distance(p, t));
        here += best > 1e-4;
      }
      misses += here;
      if (here && missed) missed->push_back(i);
    }
    return misses;
  };
  for (size_t s = 0; s < c.storeys.size(); ++s) {
    SCOPED_TRACE(c.storeys[s].name);
    // The plan SVG cuts the far box too (30 m out): leave off what lies on its outermost lines.
    std::vector<Seg> all = lines_of(cut_groups[s].node().select_nodes(".//line")), kept;
    Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
    for (const Seg& g : all)
      for (Vec2 p : g) lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)}, hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    for (const Seg& g : all) {
      auto on = [&](double a, double b, double v) { return std::fabs(a - v) < 1e-6 && std::fabs(b - v) < 1e-6; };
      if (!(on(g[0].x, g[1].x, lo.x) || on(g[0].x, g[1].x, hi.x) || on(g[0].y, g[1].y, lo.y) || on(g[0].y, g[1].y, hi.y)))
        kept.push_back(g);
    }
    ASSERT_EQ(all.size() - kept.size(), 4u);
    const std::vector<Seg> theirs = normalised(kept);
    ASSERT_GT(theirs.size(), 4u);
    const Outcome r = run({"drawing", plan, "--plan", std::to_string(s), "--cut-height", "1.2", "-o", path("p.svg")});
    ASSERT_EQ(r.status, 0) << r.err;
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(path("p.svg").c_str()));
    const std::vector<Seg> mine_mm = lines_of(doc.select_nodes("/svg/g[@id='cut']//line"));
    const std::vector<Seg> mine = normalised(mine_mm);
    ASSERT_GT(mine.size(), 4u);
    EXPECT_EQ(covered(theirs, mine), 0);
    // The other way, one difference: the upper bathroom's window has its sill at 1.2 m, in
    // the cut. The plan SVG takes only cells the cut passes through (its window cell lies
    // above), this drawing every cell the closed plane meets, so it also draws the window's
    // two jambs across the 0.3 m wall, closing the wall's outline there.
    std::vector<size_t> extra;
    covered(mine, theirs, &extra);
    EXPECT_LE(extra.size(), s == 0 ? 0u : 2u);
    for (size_t i : extra) EXPECT_NEAR(length(mine_mm[i][1] - mine_mm[i][0]) * 50 / 1000, 0.3, 1e-3);  // 1:50, mm to m
    // Room names and areas, as the plan SVG has them.
    EXPECT_GT(doc.select_nodes("/svg/g[@id='annotation']/text").size(), 0u);
  }
}

// `view --projection parallel` is the same engine: the picture plane through the eye is its cut.
TEST_F(ArchitecturalDrawing, ParallelViewFromTheEye) {
  const std::string plan = kSource + "/plans/jones-house.toml";
  const Outcome r = run({"view", plan, "--projection", "parallel", "--view-width", "12", "--size", "600x300", "-o",
                         path("v.svg"), "--stats-json", path("v.json")});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = stats("v.json");
  EXPECT_EQ(j["projection"], "parallel");
  EXPECT_GT(j["cells_cut"].get<int>(), 0);
  EXPECT_GT(j["visible_cells"].get<int>(), 1);
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(path("v.svg").c_str()));
  EXPECT_GT(doc.select_nodes("//line").size(), 10u);
  // The same view as a picture: the half-tone (not lines on white).
  const Outcome p = run({"view", plan, "--projection", "parallel", "--view-width", "12", "--size", "600x300", "-o",
                         path("v.png")});
  ASSERT_EQ(p.status, 0) << p.err;
  const Image img = read_image(path("v.png").string());
  ASSERT_EQ(img.width, 600);
  long white = 0;
  for (size_t i = 0; i + 2 < img.data.size(); i += 3) white += img.data[i] == 255 && img.data[i + 1] == 255 && img.data[i + 2] == 255;
  EXPECT_LT(white, 600 * 300 / 10);
}

// A plan large enough to be drawn in chunks (1,024 or more cut cells, avenues) on several
// threads: the same strokes, in the same order, as on one thread; and the lines beyond,
// merged once with the cut (not also before it), are each on paper once.
TEST(ArchitecturalThreads, AnyNumberOfThreadsDrawsTheSameStrokes) {
  const CellComplex c = build_cells(parse_plan(generate_office_toml(24, 24), "office 24x24"));
  const LineScene scene = prepare_line_scene(c);
  for (const ArchitecturalView& v : {plan_view(c, 0, 1.2, 8.0), axonometric_view(c, 30, 40, 1.2, 8.0)}) {
    SCOPED_TRACE(v.kind);
    const VisibleSet vs = find_visible_from_cut(c, v.camera, v.cut);
    if (v.kind == "plan") {
      ASSERT_GE(vs.cut_cells.size(), 1024u);
    }
    ASSERT_GE(vs.avenues.size(), 1024u);
    ArchitecturalOptions one = v.options, many = v.options;
    one.threads = 1;
    many.threads = 0;
    const Drawing a = draw_architectural(c, scene, v.camera, v.cut, vs, one);
    const Drawing b = draw_architectural(c, scene, v.camera, v.cut, vs, many);
    ASSERT_EQ(a.strokes.size(), b.strokes.size());
    for (size_t i = 0; i < a.strokes.size(); ++i) {
      EXPECT_EQ(a.strokes[i].a, b.strokes[i].a) << i;
      EXPECT_EQ(a.strokes[i].b, b.strokes[i].b) << i;
      EXPECT_EQ(a.strokes[i].weight, b.strokes[i].weight) << i;
      EXPECT_EQ(a.strokes[i].layer, b.strokes[i].layer) << i;
    }
    EXPECT_GT(a.strokes.size(), 1000u);
    // Merging again changes nothing: each stroke is on paper once.
    std::vector<Stroke> again = a.strokes;
    merge_collinear(again);
    EXPECT_EQ(again.size(), a.strokes.size());
  }
}

// A drawing's picture is the scanline half-tone of the same parallel view (a perspective from
// far behind the picture plane, cut where the rays start): each sample shows the face that an
// independent parallel ray from the cut plane meets first (ray_oracle.h, every opaque polygon,
// no cells), and a sample shows nothing only where its ray starts inside a solid (the poché
// goes there). Plan, section, elevation and a cut axonometric of two plans, every 3rd sample.
TEST(ArchitecturalHalftone, EachSampleShowsTheFaceARayFromTheCutMeetsFirst) {
  for (const char* name : {"two-storey-house", "jones-house"}) {
    SCOPED_TRACE(name);
    const CellComplex c = app::load_plan_source(kSource + "/plans/" + name + ".toml").complex;
    const Box3 b = building_bounds(c);
    const double z0 = c.storeys[0].elevation;
    const std::vector<ArchitecturalView> views = {
        plan_view(c, 0, 1.2, 40), section_view(c, {b.lo.x - 1, 2.2}, {b.hi.x + 1, 2.2}, 40),
        elevation_view(c, 270, 40), axonometric_view(c, 30, 35, z0 + 1.2, 40)};
    for (const ArchitecturalView& v : views)
    for (bool merge : {false, true}) {  // Jones's search, and the merged one `avenues drawing` runs
      SCOPED_TRACE(v.kind + (merge ? ", merged search" : ", Jones's search"));
      const Camera& cam = v.camera;
      TraverseParams params;
      params.merge_pieces = merge;
      const VisibleSet vs = find_visible_from_cut(c, cam, v.cut, params);
      ASSERT_TRUE(vs.cut.has_value());
      HalftoneOptions ho;
      const ScreenScene scene = screen_scene_of_view(c, {}, cam, vs, scene_options(ho));
      Image img;
      std::vector<int32_t> item;
      render_scene(scene, ho, img, nullptr, &item);
      ASSERT_EQ(item.size(), size_t(cam.width) * size_t(cam.height));
      const double along = dot(v.cut.n, cam.forward);
      int tested = 0, faces = 0, solid = 0, wrong = 0;
      for (int y = 1; y < cam.height; y += 3)
        for (int x = 1; x < cam.width; x += 3) {
          const Vec2 px{x + 0.5, y + 0.5};
          Vec3 o = cam.ray_origin_at_raster(px);
          o = o + (-v.cut.eval(o) / along) * cam.forward;  // where the ray starts: on the cut
          const double t = avenues::testing::first_hit(c, o, cam.forward);
          const int32_t shown = item[size_t(y) * size_t(cam.width) + size_t(x)];
          ++tested;
          if (shown < 0) {
            ++solid;
            wrong += c.locate(o).what == Location::What::Cell;  // free space there: a crack
            continue;
          }
          const PolygonSource& src = scene.sources[size_t(shown)];
          ASSERT_EQ(src.kind, PolygonSource::Kind::Face);
          ++faces;
          const Plane& plane = c.cells[size_t(src.cell)].faces[size_t(src.face)].plane;
          wrong += !(std::isfinite(t) && std::fabs(plane.eval(o + t * cam.forward)) < 1e-6 * length(plane.n));
        }
      EXPECT_GT(faces, tested / 2);
      if (v.kind == "plan" && std::string(name) == "two-storey-house") {
        EXPECT_GT(solid, 0) << "its cut walls";  // (Jones's walls have no thickness)
      }
      // Samples whose centre lies on an edge between two faces may take either.
      EXPECT_LE(wrong, tested / 500) << wrong << " of " << tested;
    }
  }
}

// The lines beyond are drawn over the half-tone, which shows the plan's objects: an object
// between the cut and a line hides it there, as a wall would. A room of low walls under a
// storey much higher (open above them, as a house's attic is under its roof) is covered by
// a slab given as an object, tilted toward the viewer as a roof's near half is; seen in an
// axonometric from above, no stroke of the room lies where a parallel ray from the cut meets
// the slab first (and its neighbours a pixel away do too), while the lines the slab does
// not cover are still drawn, and so is the slab's outline.
TEST(ArchitecturalDrawingObjects, AnObjectHidesTheLinesBeyondItAndIsOutlined) {
  Plan plan = parse_plan(R"(
name = "slab over low walls"
[[storey]]
name = "ground"
height = 3.5
[[wall]]
thickness = 0.2
height = 2.0
path = [[0, 0], [6, 0], [6, 4], [0, 4], [0, 0]]
[[room]]
name = "room"
at = [3, 2]
)",
                         "slab.toml");
  // 15 cm thick, over the walls and 30 cm beyond them: 3.2 m high at the south edge, 2.2 m at
  // the north one (its top turned north and up, toward a viewer in the north-east).
  const double x0 = -0.3, x1 = 6.3, ys = -0.3, yn = 4.3, zs = 3.05, zn = 2.05, t = 0.15;
  Object slab;
  slab.name = slab.mesh = "slab";
  slab.model = std::make_shared<const Mesh>(avenues::testing::mesh_from(
      {{x0, ys, zs}, {x1, ys, zs}, {x1, yn, zn}, {x0, yn, zn},
       {x0, ys, zs + t}, {x1, ys, zs + t}, {x1, yn, zn + t}, {x0, yn, zn + t}},
      {{4, 5, 6, 7}, {0, 3, 2, 1}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {3, 0, 4, 7}}));
  plan.objects = {slab};
  const CellComplex c = build_cells(plan);
  const std::vector<PlacedObject> placed = place_objects(c);
  ASSERT_EQ(placed.size(), 1u);
  const std::vector<Mesh> meshes = {placed[0].mesh};
  const LineScene scene = prepare_line_scene(c, placed);
  for (const double altitude : {30.0, 60.0}) {
    SCOPED_TRACE("altitude " + std::to_string(altitude));
    const ArchitecturalView v = axonometric_view(c, 60, altitude, std::nullopt, 40);
    const Camera& cam = v.camera;
    TraverseParams params;
    params.merge_pieces = true;  // as `avenues drawing` searches
    const VisibleSet vs = find_visible_from_cut(c, cam, v.cut, params);
    const Drawing d = draw_architectural(c, scene, cam, v.cut, vs, v.options);
    const double along = dot(v.cut.n, cam.forward);
    auto from_cut = [&](Vec2 px) {  // where the ray through raster point px starts
      const Vec3 o = cam.ray_origin_at_raster(px);
      return o + (-v.cut.eval(o) / along) * cam.forward;
    };
    // The slab nearer than every face along the ray, by more than its own thickness.
    auto slab_first = [&](Vec2 px) {
      const Vec3 o = from_cut(px);
      return avenues::testing::nearest_triangle(meshes, o, cam.forward) <
             avenues::testing::first_hit(c, o, cam.forward) - 0.2;
    };
    auto on_slab = [&](Vec2 px) {
      return std::isfinite(avenues::testing::nearest_triangle(meshes, from_cut(px), cam.forward));
    };
    int tested = 0, clear = 0, wrong = 0;
    for (const Stroke& s : d.strokes) {
      if (s.layer != Layer::Beyond) continue;
      const double len = length(s.b - s.a);
      for (double at = 1; at + 1 < len; at += 1) {  // a pixel apart, the ends left out
        const Vec2 px = s.a + (at / len) * (s.b - s.a);
        ++tested;
        if (!on_slab(px)) {
          ++clear;
          continue;
        }
        const bool inside = on_slab(px + Vec2{1, 0}) && on_slab(px - Vec2{1, 0}) && on_slab(px + Vec2{0, 1}) &&
                            on_slab(px - Vec2{0, 1});
        if (inside && slab_first(px)) {
          if (++wrong <= 5) ADD_FAILURE() << "a line beyond at " << px.x << "," << px.y << " lies behind the slab";
        }
      }
    }
    EXPECT_GT(clear, 500) << "the walls' outer lines, which the slab does not cover";
    EXPECT_EQ(wrong, 0) << wrong << " of " << tested << " points of lines beyond lie behind the slab";
    // The slab's own edges are drawn (its outline, as a roof's): every point of them lies on
    // the slab or a pixel from it, and together they run at least its near side's length.
    double edges = 0;
    for (const Stroke& s : d.strokes) {
      if (s.layer != Layer::Furniture) continue;
      edges += length(s.b - s.a);
      const Vec2 mid = 0.5 * (s.a + s.b);
      EXPECT_TRUE(on_slab(mid) || on_slab(mid + Vec2{1, 0}) || on_slab(mid - Vec2{1, 0}) || on_slab(mid + Vec2{0, 1}) ||
                  on_slab(mid - Vec2{0, 1}))
          << "an edge of the slab off it at " << mid.x << "," << mid.y;
    }
    EXPECT_GT(edges, 100) << "the slab's outline";
  }
}

// Bad input: exit status 2, a message naming the option, and no file.
TEST_F(ArchitecturalDrawing, BadOptionsAreNamedAndWriteNothing) {
  const std::string plan = kSource + "/plans/jones-house.toml";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--plan", "attic"}, "--plan"},
      {{"--scale", "1:1000", "--plan", "0"}, "--scale"},
      {{"--section", "1,2,3"}, "--section"},
      {{"--section", "1,1,1,1"}, "--section"},
      {{"--elevation", "up"}, "--elevation"},
      {{"--axonometric", "30,0"}, "--axonometric"},
      {{"--elevation", "north", "--cut-height", "1"}, "--cut-height"},
      {{"--plan", "0", "--samples", "3"}, "--samples"},
      {{}, "--plan"},
  };
  for (const auto& [extra, named] : cases) {
    std::vector<std::string> args{"drawing", plan, "-o", path("x.svg")};
    args.insert(args.end(), extra.begin(), extra.end());
    const Outcome r = run(args);
    EXPECT_EQ(r.status, 2) << named;
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("x.svg"))) << named;
  }
  const Outcome v = run({"view", plan, "--projection", "parallel", "-o", path("x.svg")});
  EXPECT_EQ(v.status, 2);
  EXPECT_NE(v.err.find("--view-width"), std::string::npos) << v.err;
  EXPECT_EQ(run({"drawing", plan, "--plan", "0", "-o", path("x.doc")}).status, 2);
  EXPECT_FALSE(fs::exists(path("x.doc")));
}

// One run writing the drawing to several files (-o repeated) writes each file as a run of its
// own would, byte for byte; the plan is read and the drawing made once. One file that cannot
// be written (an unknown format, a file named twice, a missing folder) writes none of them.
TEST_F(ArchitecturalDrawing, SeveralOutputsOfOneRunAreTheFilesOfSeparateRunsOrNoneAtAll) {
  const std::string plan = kSource + "/plans/jones-house.toml";
  const std::vector<std::string> kind{"--section", "-1,2.7,10,2.7", "--scale", "1:100"};
  std::vector<std::string> together{"drawing", plan, "--stats-json", path("s.json")};
  together.insert(together.end(), kind.begin(), kind.end());
  for (const char* ext : {".svg", ".dxf", ".hpgl", ".png", ".pbm"}) together.insert(together.end(), {"-o", path(std::string("all") + ext)});
  const Outcome all = run(together);
  ASSERT_EQ(all.status, 0) << all.err;
  EXPECT_EQ(stats("s.json")["outputs"].size(), 5u);
  for (const char* ext : {".svg", ".dxf", ".hpgl", ".png", ".pbm"}) {
    SCOPED_TRACE(ext);
    EXPECT_NE(all.out.find("wrote " + path(std::string("all") + ext).string()), std::string::npos) << all.out;
    std::vector<std::string> alone{"drawing", plan, "-o", path(std::string("one") + ext)};
    alone.insert(alone.end(), kind.begin(), kind.end());
    ASSERT_EQ(run(alone).status, 0);
    EXPECT_TRUE(slurp(path(std::string("all") + ext)) == slurp(path(std::string("one") + ext)));
  }
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
      {{"-o", path("b.svg"), "-o", path("b.doc")}, "b.doc"},
      {{"-o", path("b.svg"), "-o", path("b.png"), "-o", path("./b.svg")}, "named twice"},
      {{"-o", path("b.svg"), "-o", path("no-such-folder/b.png")}, "no-such-folder"},
      {{"-o", path("b.svg"), "-o", path("b.png"), "--stats-json", path("b.png")}, "named twice"},
  };
  for (const auto& [outs, named] : bad) {
    std::vector<std::string> args{"drawing", plan};
    args.insert(args.end(), kind.begin(), kind.end());
    args.insert(args.end(), outs.begin(), outs.end());
    const Outcome r = run(args);
    EXPECT_EQ(r.status, 2) << named;
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path("b.svg"))) << named;
    EXPECT_FALSE(fs::exists(path("b.png"))) << named;
  }
}
