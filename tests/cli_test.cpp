// Avenues — the `avenues` executable, run as a person would run it.
//
// Each test runs the real binary (AVENUES_BINARY, by its argument vector) in a fresh
// temporary directory (tests/avenues_run.h) with no display, and checks its exit status,
// what it prints and the files it writes (or must not write).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "cells/build_cells.h"
#include "plans/plan.h"
#include "tests/avenues_run.h"
#include "tests/test_files.h"

namespace fs = std::filesystem;
using nlohmann::json;

using avenues::testing::Outcome;
using avenues::testing::RunOptions;
using avenues::testing::slurp;

namespace {

const std::string kPlan = std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml";

class Cli : public avenues::testing::AvenuesRun {};

json parse_json(const Outcome& r) {
  try {
    return json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\n" << r.out;
    return json::object();
  }
}

// A plan that is not even TOML: the mistake is on line 3.
const char* kBrokenToml =
    "# a broken plan\n"
    "name = \"broken\"\n"
    "storeys = [ { name = \"ground\", height = 2.5 \n"
    "walls = 3\n";

}  // namespace

TEST_F(Cli, HelpWorksForEverySubcommand) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"--help"}, {"cells", "--help"}, {"export", "--help"}, {"generate", "--help"},
           {"generate", "office", "--help"}, {"view", "--help"}}) {
    Outcome r = run(args);
    EXPECT_EQ(r.status, 0) << ::testing::PrintToString(args) << "\n" << r.err;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << ::testing::PrintToString(args) << "\n" << r.out;
  }
  Outcome r = run({"--help"});
  for (const char* sub : {"cells", "export", "generate", "view"})
    EXPECT_NE(r.out.find(sub), std::string::npos) << "--help does not mention " << sub;
}

TEST_F(Cli, TheProgramsMallocIsJemallocKeepingTheFreedPages) {
  // app/allocator.cpp: jemalloc replaces glibc's malloc in `avenues`, set never to hand
  // freed pages back (docs/PERFORMANCE.md, "The allocator"). Its own statistics say so.
  RunOptions o;
  o.set_env = {"MALLOC_CONF=stats_print:true"};
  const Outcome r = run({"--version"}, o);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("jemalloc statistics"), std::string::npos) << r.err.substr(0, 400);
  EXPECT_NE(r.err.find("opt.dirty_decay_ms: -1"), std::string::npos) << r.err.substr(0, 2000);
  EXPECT_NE(r.err.find("opt.muzzy_decay_ms: -1"), std::string::npos) << r.err.substr(0, 2000);
}

TEST_F(Cli, BadCommandLinesExitWithStatus2) {
  const std::vector<std::vector<std::string>> bad = {
      {"--no-such-option"}, {"cells"}, {"cells", "--json"}, {"export", kPlan}, {"generate"},
      {"generate", "office", "-o", "x.toml"}, {"frobnicate", "extra", "words"}};
  for (const std::vector<std::string>& args : bad) {
    Outcome r = run(args);
    EXPECT_EQ(r.status, 2) << ::testing::PrintToString(args) << "\n" << r.out << r.err;
    EXPECT_FALSE(r.err.empty()) << ::testing::PrintToString(args);
  }
  EXPECT_FALSE(fs::exists(path("x.toml")));
}

TEST_F(Cli, CellsJsonHasTheCounts) {
  Outcome r = run({"cells", kPlan, "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  json j = parse_json(r);
  for (const char* key : {"cells", "portals", "rooms", "storeys", "seconds", "stages", "cells_by_kind",
                          "portals_by_kind", "opaque_faces", "lines", "cells_per_room"})
    EXPECT_TRUE(j.contains(key)) << "missing key " << key << "\n" << r.out;
  EXPECT_GT(j.value("cells", 0), 0);
  EXPECT_GT(j.value("portals", 0), 0);
  EXPECT_GT(j.value("rooms", 0), 0);
  EXPECT_GE(j.value("storeys", 0), 1);
  EXPECT_GT(j.value("opaque_faces", 0), 0);
  EXPECT_TRUE(j["stages"].is_object());
  EXPECT_FALSE(j["stages"].empty());
  EXPECT_GE(j.value("seconds", -1.0), 0.0);
  int by_kind = 0;
  for (const auto& [kind, n] : j["cells_by_kind"].items()) by_kind += n.get<int>();
  EXPECT_EQ(by_kind, j.value("cells", -1));
  int portals_by_kind = 0;
  for (const auto& [kind, n] : j["portals_by_kind"].items()) portals_by_kind += n.get<int>();
  EXPECT_EQ(portals_by_kind, j.value("portals", -1));
}

TEST_F(Cli, CellsTextSummary) {
  Outcome r = run({"cells", kPlan});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* word : {"storeys", "rooms", "cells", "portals", "opaque", "lines", "per room", "total"})
    EXPECT_NE(r.out.find(word), std::string::npos) << "summary lacks '" << word << "':\n" << r.out;
}

TEST_F(Cli, MalformedPlanNamesFileAndLineAndWritesNothing) {
  write("bad.toml", kBrokenToml);
  Outcome r = run({"cells", "bad.toml", "--svg", "out.svg", "--save", "out.cells"});
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("avenues: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("bad.toml:3"), std::string::npos) << "message should name file and line:\n" << r.err;

  r = run({"export", "bad.toml", "-o", "out.obj"});
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("bad.toml:3"), std::string::npos) << r.err;

  r = run({"bad.toml"});  // the main job
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("bad.toml:3"), std::string::npos) << r.err;

  EXPECT_EQ(files(), std::set<std::string>{"bad.toml"}) << "no output (nor temporary) file may be left";
}

TEST_F(Cli, PlanMistakeFoundByTheDecomposerNamesTheElement) {
  // Valid TOML, a valid plan to the reader, but the room is open to the outside:
  // only the decomposition finds it, and must still name the room and its line.
  write("leaky.toml",
        "name = \"leaky\"\n"
        "\n"
        "[[storey]]\n"
        "name = \"ground\"\n"
        "height = 2.5\n"
        "\n"
        "[[wall]]\n"
        "name = \"box\"\n"
        "thickness = 0.2\n"
        "path = [[0, 0], [4, 0], [4, 4], [0, 4]]\n"
        "\n"
        "[[room]]\n"
        "name = \"hall\"\n"
        "at = [2, 2]\n");
  Outcome r = run({"cells", "leaky.toml", "--svg", "out.svg", "--save", "out.cells"});
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("leaky.toml:12"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("hall"), std::string::npos) << r.err;
  r = run({"export", "leaky.toml", "-o", "out.obj"});
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_EQ(files(), std::set<std::string>{"leaky.toml"});
}

TEST_F(Cli, MissingPlanFileIsNamed) {
  Outcome r = run({"cells", "no-such-plan.toml"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("no-such-plan.toml"), std::string::npos) << r.err;
}

TEST_F(Cli, OutputThatCannotBeWrittenIsAnError) {
  Outcome r = run({"export", kPlan, "-o", "no-such-dir/out.obj"});
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("no-such-dir/out.obj"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("no-such-dir")));
}

TEST_F(Cli, GeneratedOfficeIsAcceptedByCells) {
  Outcome r = run({"generate", "office", "--rooms", "3x4", "-o", "office.toml"});
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(fs::exists(path("office.toml")));
  r = run({"cells", "office.toml", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  json j = parse_json(r);
  EXPECT_GE(j.value("rooms", 0), 12);
  EXPECT_GT(j.value("cells", 0), 12);
}

TEST_F(Cli, GenerateRejectsBadRooms) {
  for (const char* rooms : {"3by4", "x", "3x", "0x4", "3x4x5", "-3x4", "3x100000"}) {
    Outcome r = run({"generate", "office", "--rooms", rooms, "-o", "office.toml"});
    EXPECT_EQ(r.status, 2) << rooms << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find("ROWSxCOLS"), std::string::npos) << rooms << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(path("office.toml")));
}

TEST_F(Cli, ExportWritesOneGroupPerCellAndEveryOpaqueTriangle) {
  Outcome r = run({"cells", kPlan, "--save", "house.cells"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = run({"export", kPlan, "-o", "house.obj"});
  ASSERT_EQ(r.status, 0) << r.err;
  avenues::CellComplex c = avenues::load_cells(path("house.cells").string());

  size_t expected_faces = 0;
  for (const avenues::Cell& cell : c.cells)
    for (const avenues::Face& f : cell.faces)
      for (const avenues::OpaquePoly& op : f.opaque)
        if (op.poly.size() >= 3) expected_faces += op.poly.size() - 2;

  std::ifstream obj(path("house.obj"));
  std::string line;
  std::vector<std::string> groups;
  size_t vertices = 0, faces = 0;
  bool indices_ok = true;
  while (std::getline(obj, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      double x, y, z;
      EXPECT_TRUE(static_cast<bool>(ls >> x >> y >> z)) << line;
      ++vertices;
    } else if (tag == "g") {
      std::string name;
      ls >> name;
      groups.push_back(name);
    } else if (tag == "f") {
      ++faces;
      size_t idx, n = 0;
      while (ls >> idx) {
        ++n;
        if (idx < 1 || idx > vertices) indices_ok = false;
      }
      if (n != 3) indices_ok = false;
    }
  }
  ASSERT_EQ(groups.size(), c.cells.size());
  for (size_t i = 0; i < groups.size(); ++i) EXPECT_EQ(groups[i], "cell" + std::to_string(i));
  EXPECT_EQ(faces, expected_faces);
  EXPECT_GT(faces, 0u);
  EXPECT_TRUE(indices_ok) << "every face is a triangle of vertices defined before it";
}

TEST_F(Cli, SavedCellsLoadWithEqualCounts) {
  Outcome built = run({"cells", kPlan, "--save", "house.cells", "--json"});
  ASSERT_EQ(built.status, 0) << built.err;
  ASSERT_TRUE(fs::exists(path("house.cells")));
  Outcome loaded = run({"cells", "house.cells", "--json"});
  ASSERT_EQ(loaded.status, 0) << loaded.err;
  json a = parse_json(built), b = parse_json(loaded);
  for (const char* key : {"cells", "portals", "rooms", "storeys", "opaque_faces", "lines", "cells_by_kind",
                          "portals_by_kind", "cells_per_room", "plan"})
    EXPECT_EQ(a[key], b[key]) << key;
}

TEST_F(Cli, CorruptCellsFileIsAnError) {
  ASSERT_EQ(run({"cells", kPlan, "--save", "house.cells"}).status, 0);
  std::string bytes = slurp(path("house.cells"));
  write("short.cells", bytes.substr(0, bytes.size() / 2));
  write("junk.cells", "AVCELLS");
  std::string flipped = bytes;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x5a);
  write("flipped.cells", flipped);
  for (const char* name : {"short.cells", "junk.cells", "flipped.cells"}) {
    Outcome r = run({"cells", name, "--json"});
    EXPECT_EQ(r.status, 2) << name << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << name << ": " << r.out;
  }
}

TEST_F(Cli, PlanDrawingIsWellFormedSvg) {
  Outcome r = run({"cells", kPlan, "--svg", "plan.svg"});
  ASSERT_EQ(r.status, 0) << r.err;
  pugi::xml_document doc;
  pugi::xml_parse_result ok = doc.load_file(path("plan.svg").c_str());
  ASSERT_TRUE(ok) << ok.description() << " at byte " << ok.offset;
  pugi::xml_node svg = doc.child("svg");
  ASSERT_TRUE(svg);
  EXPECT_TRUE(svg.attribute("viewBox"));
  EXPECT_NE(std::string(svg.attribute("width").value()).find("mm"), std::string::npos);
  EXPECT_NE(std::string(svg.attribute("height").value()).find("mm"), std::string::npos);

  // Every storey is drawn and titled; there are cells and walls in the drawing.
  avenues::Plan plan = avenues::read_plan(kPlan);
  std::string text;
  size_t polygons = 0, lines = 0;
  for (pugi::xpath_node n : doc.select_nodes("//text")) text += std::string(n.node().child_value()) + "\n";
  polygons = doc.select_nodes("//polygon").size();
  lines = doc.select_nodes("//line").size();
  for (const avenues::Storey& s : plan.storeys)
    EXPECT_NE(text.find(s.name), std::string::npos) << "storey '" << s.name << "' is not titled";
  for (const avenues::Room& room : plan.rooms)
    EXPECT_NE(text.find(room.name), std::string::npos) << "room '" << room.name << "' is not labelled";
  EXPECT_EQ(doc.select_nodes("//g[starts-with(@id,'storey-')]").size(), plan.storeys.size());
  EXPECT_GT(polygons, plan.rooms.size());
  EXPECT_GT(lines, 0u);
}

TEST_F(Cli, MainJobWritesThePlanDrawing) {
  Outcome r = run({});
  ASSERT_EQ(r.status, 0) << r.err;
  const fs::path svg = path("avenues-out/jones-house-plan.svg");
  EXPECT_TRUE(fs::exists(svg));
  EXPECT_NE(r.out.find("avenues-out/jones-house-plan.svg"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cells"), std::string::npos) << r.out;
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_file(svg.c_str()));
  // The default view's avenues of sight, too.
  const fs::path avenues = path("avenues-out/jones-house-avenues.svg");
  EXPECT_TRUE(doc.load_file(avenues.c_str()));
  EXPECT_NE(r.out.find("default view"), std::string::npos) << r.out;
}

// --- avenues view -------------------------------------------------------------------

TEST_F(Cli, ViewWritesStatsWithTheSameIdsAsExportAndAnOverlay) {
  Outcome r = run({"view", kPlan, "--eye", "1.0,0.5,1.2", "--look", "6,3,1.2", "--fov", "100", "--size", "640x400",
                   "--stats-json", "s.json", "--overlay", "o.svg"});
  ASSERT_EQ(r.status, 0) << r.err;
  json j = json::parse(slurp(path("s.json")));
  for (const char* key : {"visible_cells", "visible", "avenues", "portals_tested", "max_depth", "visibility_us", "eye",
                          "look", "fov", "kernel"})
    EXPECT_TRUE(j.contains(key)) << "missing key " << key;
  EXPECT_EQ(j["visible"].size(), j["visible_cells"].get<size_t>());
  EXPECT_EQ(j["eye"], json({1.0, 0.5, 1.2}));
  EXPECT_EQ(j["fov"].get<double>(), 100.0);
  // Jones's kitchen through the door and the hatch: more avenues than cells.
  EXPECT_GT(j["avenues"].get<int>(), j["visible_cells"].get<int>());
  // The ids are those of `avenues export`'s groups.
  ASSERT_EQ(run({"export", kPlan, "-o", "b.obj"}).status, 0);
  const std::string obj = slurp(path("b.obj"));
  for (int id : j["visible"]) EXPECT_NE(obj.find("g cell" + std::to_string(id) + "\n"), std::string::npos) << id;
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file(path("o.svg").c_str())) << "overlay is not XML";
  EXPECT_TRUE(doc.child("svg").find_child_by_attribute("g", "id", "avenue-tree"));
}

TEST_F(Cli, ViewWithoutAnEyeUsesThePlansViewpoint) {
  Outcome r = run({"view", kPlan, "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  json j = json::parse(slurp(path("s.json")));
  EXPECT_EQ(j["eye"], json({1.5, 3.0, 1.6}));  // the [view] of jones-house.toml
  EXPECT_EQ(j["eye_room"], "L");
}

TEST_F(Cli, ViewKernelsAgreeOnTheDefaultView) {
  std::map<std::string, json> visible;
  for (const char* k : {"float", "double", "filtered", "exact"}) {
    Outcome r = run({"view", kPlan, "--kernel", k, "--stats-json", std::string(k) + ".json"});
    ASSERT_EQ(r.status, 0) << k << r.err;
    visible[k] = json::parse(slurp(path(std::string(k) + ".json")))["visible"];
  }
  EXPECT_EQ(visible["double"], visible["exact"]);
  EXPECT_EQ(visible["filtered"], visible["exact"]);
}

TEST_F(Cli, ViewRefusesAnEyeInsideAWallAndWritesNothing) {
  write("thick.toml",
        "[[wall]]\nname = \"box\"\nthickness = 0.3\npath = [[0,0],[6,0],[6,4],[0,4],[0,0]]\n"
        "[[room]]\nname = \"only\"\nat = [3, 2]\n");
  Outcome r =
      run({"view", "thick.toml", "--eye", "3,0.05,1.2", "--look", "3,2,1.2", "--stats-json", "s.json", "--overlay", "o.svg"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("inside wall 'box'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("thick.toml"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("s.json")));
  EXPECT_FALSE(fs::exists(path("o.svg")));
  // In the room it is fine.
  EXPECT_EQ(run({"view", "thick.toml", "--eye", "3,2,1.2", "--look", "6,2,1.2", "--stats-json", "s.json"}).status, 0);
}

TEST_F(Cli, ViewRejectsBadOptions) {
  for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
           {"--kernel", "quad"}, {"--size", "10by10"}, {"--eye", "1,2"}, {"--fov", "180"},
           {"--eye", "1,2,3", "--look", "1,2,3"}}) {
    std::vector<std::string> argv = {"view", kPlan};
    argv.insert(argv.end(), args.begin(), args.end());
    argv.insert(argv.end(), {"--stats-json", "s.json"});
    Outcome r = run(argv);
    EXPECT_EQ(r.status, 2) << ::testing::PrintToString(args) << "\n" << r.err;
    EXPECT_FALSE(fs::exists(path("s.json"))) << ::testing::PrintToString(args);
  }
}

// --search: the merged search (the default) and Jones's tree see the same cells; the
// statistics say which ran, and the merged one follows no more avenues.
TEST_F(Cli, ViewSearchesMergedByDefaultAndJonesOnRequestSeeingTheSameCells) {
  const std::string plan = std::string(AVENUES_SOURCE_DIR) + "/plans/curved-walls.toml";
  ASSERT_EQ(run({"view", plan, "--stats-json", "merged.json"}).status, 0);
  ASSERT_EQ(run({"view", plan, "--search", "jones", "--stats-json", "jones.json"}).status, 0);
  const json m = json::parse(slurp(path("merged.json")));
  const json j = json::parse(slurp(path("jones.json")));
  EXPECT_EQ(m["search"], "merged");
  EXPECT_EQ(j["search"], "jones");
  EXPECT_EQ(m["visible"], j["visible"]);
  EXPECT_LE(m["avenues"].get<int>(), j["avenues"].get<int>());
  EXPECT_TRUE(m.contains("avenues_merged"));
  EXPECT_FALSE(j.contains("avenues_merged"));
}

// --search hull: a superset of the merged search's cells, said in the statistics; its
// hidden-line drawing is the merged search's (lines need exact masks), and a drawing
// command asked for it is refused (exit 2, naming the option) before anything is written.
TEST_F(Cli, TheHullSearchDrawsLinesByTheMergedSearchAndDrawingsRefuseIt) {
  const std::string plan = std::string(AVENUES_SOURCE_DIR) + "/plans/curved-walls.toml";
  ASSERT_EQ(run({"view", plan, "--stats-json", "merged.json", "-o", "merged.svg"}).status, 0);
  ASSERT_EQ(run({"view", plan, "--search", "hull", "--stats-json", "hull.json", "-o", "hull.svg"}).status, 0);
  const json m = json::parse(slurp(path("merged.json")));
  const json h = json::parse(slurp(path("hull.json")));
  EXPECT_EQ(h["search"], "hull");
  for (const auto& cell : m["visible"])
    EXPECT_NE(std::find(h["visible"].begin(), h["visible"].end(), cell), h["visible"].end()) << "cell " << cell;
  EXPECT_EQ(slurp(path("hull.svg")), slurp(path("merged.svg")));
  const Outcome r = run({"drawing", plan, "--plan", "0", "--search", "hull", "-o", "plan.svg"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("--search hull"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("plan.svg")));
}

TEST_F(Cli, ViewExplainSaysWhichEffectsTheSceneCallsForAndWhy) {
  // A line per effect, on or off and why, for scenes with and without each effect.
  auto effects = [&](const std::string& plan, const std::vector<std::string>& args) {
    std::vector<std::string> argv = {"view", plan, "--explain"};
    argv.insert(argv.end(), args.begin(), args.end());
    Outcome r = run(argv);
    EXPECT_EQ(r.status, 0) << r.err;
    std::map<std::string, std::string> on;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
      const size_t colon = line.find(": o");
      if (colon == std::string::npos || line.rfind("eye in", 0) == 0) continue;
      on[line.substr(0, colon)] = line.substr(colon + 2, line.substr(colon + 2, 3) == "on " ? 2 : 3);
    }
    return on;
  };
  // Jones's house: no objects, one coloured lamp away from the eye.
  auto house = effects(kPlan, {});
  EXPECT_EQ(house["depth"], "off");
  EXPECT_EQ(house["implicit lines"], "off");
  EXPECT_EQ(house["shadows"], "on");
  EXPECT_EQ(house["object shadows"], "off");
  EXPECT_EQ(house["smooth shading"], "off");
  EXPECT_EQ(house["distance falloff"], "off");
  EXPECT_EQ(house["coloured light"], "on");
  EXPECT_EQ(house.size(), 7u);
  // The same lit from the eye, smooth: no shadows, no colour; the distance law only while asked.
  auto eye = effects(kPlan, {"--lights", "eye", "--shading", "smooth"});
  EXPECT_EQ(eye["shadows"], "off");
  EXPECT_EQ(eye["coloured light"], "off");
  EXPECT_EQ(eye["smooth shading"], "on");
  EXPECT_EQ(eye["distance falloff"], "on");
  EXPECT_EQ(effects(kPlan, {"--lights", "eye", "--shading", "smooth", "--falloff", "0"})["distance falloff"], "off");
  // A table: depth in its cell, but nothing crosses.
  const std::string room = std::string(AVENUES_SOURCE_DIR) + "/plans/furnished-room.toml";
  auto furnished = effects(room, {});
  EXPECT_EQ(furnished["depth"], "on");
  EXPECT_EQ(furnished["implicit lines"], "off");
  EXPECT_EQ(furnished["shadows"], "off");
  // Two tables pushed through each other, and a curved mesh with auto shading.
  std::string plan = slurp(room);
  const std::string table = std::string(AVENUES_SOURCE_DIR) + "/plans/meshes/table.off";
  const std::string torus = std::string(AVENUES_SOURCE_DIR) + "/plans/scenes/torus.off";
  size_t at = plan.find("mesh = \"meshes/table.off\"");
  ASSERT_NE(at, std::string::npos);
  plan.replace(at, std::string("mesh = \"meshes/table.off\"").size(), "mesh = \"" + table + "\"");
  write("crossing.toml", plan + "\n[[object]]\nname = \"second table\"\nmesh = \"" + table +
                             "\"\nposition = [2.9, 2.4, 0.02]\nrotation = 40\n");
  auto crossing = effects(path("crossing.toml").string(), {});
  EXPECT_EQ(crossing["depth"], "on");
  EXPECT_EQ(crossing["implicit lines"], "on");
  write("torus.toml", plan + "\n[[object]]\nname = \"ring\"\nmesh = \"" + torus +
                          "\"\nposition = [1.2, 3.0, 0.5]\nscale = 0.3\n");
  EXPECT_EQ(effects(path("torus.toml").string(), {"--shading", "auto"})["smooth shading"], "on");
  EXPECT_EQ(effects(path("torus.toml").string(), {"--shading", "flat"})["smooth shading"], "off");
  EXPECT_EQ(effects(room, {"--shading", "auto"})["smooth shading"], "off");
  // A drawing says whether the shadow outlines are drawn.
  Outcome r = run({"view", kPlan, "--explain", "--shadow-lines", "-o", "d.svg"});
  EXPECT_NE(r.out.find("shadow outlines: on"), std::string::npos) << r.out;
  EXPECT_NE(slurp(path("d.svg")).find("shadow"), std::string::npos);
  EXPECT_EQ(run({"view", kPlan, "--lights", "sun"}).status, 2);
}

TEST_F(Cli, ViewWritesTheDrawingInEveryFormatWithItsStats) {
  for (const char* name : {"v.svg", "v.pdf", "v.eps", "v.dxf", "v.hpgl"}) {
    Outcome r = run({"view", kPlan, "-o", name, "--stats-json", "s.json"});
    ASSERT_EQ(r.status, 0) << name << r.err;
    EXPECT_GT(fs::file_size(path(name)), 100u) << name;
    json j = json::parse(slurp(path("s.json")));
    EXPECT_GT(j["lines"].get<int>(), 0) << name;
    EXPECT_TRUE(j.contains("render_us")) << name;
    if (std::string(name) == "v.hpgl") {
      EXPECT_LE(j["penup_mm"]["after"].get<double>(), j["penup_mm"]["before"].get<double>());
    }
  }
  Outcome bad = run({"view", kPlan, "-o", "v.xyz"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find(".svg"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("v.xyz")));
}

TEST_F(Cli, SeveralOutputsOfOneViewAreTheFilesOfSeparateRunsOrNoneAtAll) {
  const std::vector<std::string> exts{".svg", ".dxf", ".png", ".pgm", ".pdf", ".eps"};  // PDF and EPS carry no date
  std::vector<std::string> together{"view", kPlan, "--size", "320x200", "--stats-json", "s.json"};
  for (const std::string& ext : exts) together.insert(together.end(), {"-o", "all" + ext});
  const Outcome all = run(together);
  ASSERT_EQ(all.status, 0) << all.err;
  const json j = json::parse(slurp(path("s.json")));
  ASSERT_EQ(j["outputs"].size(), exts.size());
  EXPECT_GT(j["outputs"][0]["lines"].get<int>(), 0);  // each file's own figures
  EXPECT_TRUE(j["outputs"][2].contains("polygons"));
  for (size_t k = 0; k < exts.size(); ++k) {
    SCOPED_TRACE(exts[k]);
    EXPECT_EQ(j["outputs"][k]["file"], "all" + exts[k]);
    EXPECT_NE(all.out.find("wrote all" + exts[k]), std::string::npos) << all.out;
    ASSERT_EQ(run({"view", kPlan, "--size", "320x200", "-o", "one" + exts[k]}).status, 0);
    EXPECT_TRUE(slurp(path("all" + exts[k])) == slurp(path("one" + exts[k])));
  }
  // Runs a second apart would differ by the date Cairo puts in: none is there.
  EXPECT_EQ(slurp(path("all.pdf")).find("/CreationDate"), std::string::npos);
  EXPECT_EQ(slurp(path("all.eps")).find("%%CreationDate"), std::string::npos);
  EXPECT_EQ(slurp(path("all.eps")).rfind("%!PS-Adobe-3.0 EPSF-3.0", 0), 0u);
  // Walk frames, one numbered set per file asked for (each frame rendered and drawn once),
  // each file the one a separate run writes.
  const std::vector<std::string> walk{"--size", "160x100", "--frames", "2", "--to-eye", "7,4.5,1.6", "--to-look", "8,5,1.5"};
  auto view_walk = [&](std::vector<std::string> files) {
    std::vector<std::string> args{"view", kPlan};
    for (const std::string& f : files) args.insert(args.end(), {"-o", f});
    args.insert(args.end(), walk.begin(), walk.end());
    return run(args).status;
  };
  ASSERT_EQ(view_walk({"w.svg", "w.png", "w2.png"}), 0);
  ASSERT_EQ(view_walk({"alone.svg"}), 0);
  ASSERT_EQ(view_walk({"alone.png"}), 0);
  for (const char* k : {"-0001", "-0002"}) {
    EXPECT_TRUE(slurp(path(std::string("w") + k + ".svg")) == slurp(path(std::string("alone") + k + ".svg"))) << k;
    EXPECT_TRUE(slurp(path(std::string("w") + k + ".png")) == slurp(path(std::string("alone") + k + ".png"))) << k;
    EXPECT_TRUE(slurp(path(std::string("w2") + k + ".png")) == slurp(path(std::string("alone") + k + ".png"))) << k;
  }
  // A stereo pair (side by side suits both kinds), made once for the files of each kind.
  ASSERT_EQ(run({"view", kPlan, "--size", "160x100", "--stereo", "parallel", "-o", "p.svg", "-o", "p.png", "-o", "p2.png"}).status, 0);
  for (const char* ext : {".svg", ".png"}) {
    ASSERT_EQ(run({"view", kPlan, "--size", "160x100", "--stereo", "parallel", "-o", std::string("pa") + ext}).status, 0);
    EXPECT_TRUE(slurp(path(std::string("p") + ext)) == slurp(path(std::string("pa") + ext))) << ext;
  }
  EXPECT_TRUE(slurp(path("p2.png")) == slurp(path("pa.png")));
  // Every file is checked before any is written: a bad one anywhere writes none.
  const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
      {{"-o", "b.svg", "-o", "b.doc"}, "b.doc"},
      {{"-o", "b.svg", "-o", "b.png", "-o", "./b.svg"}, "named twice"},
      {{"-o", "b.svg", "-o", "no-such-folder/b.png"}, "no-such-folder"},
      {{"-o", "b.svg", "-o", "b.png", "--stereo", "pair"}, "b.png"},
      {{"-o", "b.svg", "-o", "b.png", "--stats-json", "b.png"}, "named twice"},
  };
  for (const auto& [outs, named] : bad) {
    std::vector<std::string> args{"view", kPlan, "--size", "160x100"};
    args.insert(args.end(), outs.begin(), outs.end());
    const Outcome r = run(args);
    EXPECT_EQ(r.status, 2) << named;
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
    for (const char* f : {"b.svg", "b.png", "b-left.svg", "b-right.svg"}) EXPECT_FALSE(fs::exists(path(f))) << named << ": " << f;
  }
}

TEST_F(Cli, ViewStereoAndWalkFrames) {
  ASSERT_EQ(run({"view", kPlan, "-o", "s.svg", "--stereo", "cross", "--stats-json", "s.json"}).status, 0);
  EXPECT_TRUE(json::parse(slurp(path("s.json"))).contains("stereo"));
  ASSERT_EQ(run({"view", kPlan, "-o", "p.dxf", "--stereo", "pair"}).status, 0);
  EXPECT_TRUE(fs::exists(path("p-left.dxf")) && fs::exists(path("p-right.dxf")));
  Outcome walk = run({"view", kPlan, "-o", "w.svg", "--frames", "4", "--to-eye", "7,4.5,1.6", "--to-look", "8,5,1.5"});
  ASSERT_EQ(walk.status, 0) << walk.err;
  for (int k = 1; k <= 4; ++k) EXPECT_TRUE(fs::exists(path("w-000" + std::to_string(k) + ".svg"))) << k;
  // A walk whose last eye is outside the far box writes nothing at all.
  Outcome bad = run({"view", kPlan, "-o", "x.svg", "--frames", "3", "--to-eye", "7,4.5,60", "--to-look", "8,5,1.5"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("frame 3 of 3"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("x-0001.svg")));
}

TEST_F(Cli, ViewWritesHalftonePicturesStereoAndThePapersTable) {
  Outcome r = run({"view", kPlan, "-o", "h.png", "--size", "320x180", "--samples", "4", "--stats-json", "s.json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string png = slurp(path("h.png"));
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  json j = json::parse(slurp(path("s.json")));
  EXPECT_GT(j["spans"].get<double>(), 0);
  EXPECT_TRUE(j.contains("render_us"));
  EXPECT_EQ(run({"view", kPlan, "-o", "g.pgm", "--size", "160x90", "--dither", "bayer"}).status, 0);
  EXPECT_EQ(slurp(path("g.pgm")).substr(0, 2), "P5");
  EXPECT_EQ(run({"view", kPlan, "-o", "a.png", "--size", "160x90", "--stereo", "anaglyph"}).status, 0);
  EXPECT_TRUE(fs::exists(path("a.png")));
  for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
           {"--samples", "3"}, {"--shading", "glossy"}, {"--dither", "dots"}, {"--stereo", "pair"}}) {
    std::vector<std::string> argv = {"view", kPlan, "-o", "x.png", "--size", "160x90"};
    argv.insert(argv.end(), bad.begin(), bad.end());
    Outcome b = run(argv);
    EXPECT_EQ(b.status, 2) << ::testing::PrintToString(bad) << "\n" << b.err;
    EXPECT_FALSE(fs::exists(path("x.png"))) << ::testing::PrintToString(bad);
  }
  Outcome papers = run({"bench", "papers", "--repeats", "1"});
  ASSERT_EQ(papers.status, 0) << papers.err;
  for (const char* scene : {"cottage", "ripple-torus", "cubes", "wylie-cube", "crow-object"})
    EXPECT_NE(papers.out.find(scene), std::string::npos) << scene;
}

TEST_F(Cli, AMissingObjectMeshNamesThePlanLineAndWritesNothing) {
  write("furnished.toml",
        "[[wall]]\nname = \"box\"\nthickness = 0.2\npath = [[0,0],[5,0],[5,4],[0,4],[0,0]]\n"
        "[[room]]\nname = \"room\"\nat = [2.5, 2]\n"
        "[[object]]\nname = \"table\"\nmesh = \"missing.off\"\nposition = [2, 2, 0]\n");
  for (const char* out : {"v.png", "v.svg"}) {
    Outcome r = run({"view", "furnished.toml", "--eye", "1,1,1.6", "--look", "4,3,1.2", "-o", out});
    EXPECT_EQ(r.status, 2) << out;
    EXPECT_NE(r.err.find("furnished.toml:8"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("object 'table'"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("missing.off"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(path(out)));
  }
}

TEST_F(Cli, PathWalksThroughTheNamedRoomsAndWritesFrames) {
  Outcome r = run({"path", kPlan, "--through", "L,K,D", "-o", "walk", "--size", "160x90", "--step", "0.5"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> frames;
  for (const auto& e : fs::directory_iterator(path("walk")))
    if (e.path().extension() == ".png") frames.push_back(e.path().filename().string());
  std::sort(frames.begin(), frames.end());
  ASSERT_GE(frames.size(), 10u);
  EXPECT_EQ(frames.front(), "frame-0001.png");
  EXPECT_EQ(slurp(path("walk") / frames.back()).substr(1, 3), "PNG");
  EXPECT_EQ(run({"path", kPlan, "--through", "L,D", "--format", "svg", "-o", "drawn", "--size", "160x90"}).status, 0);
  EXPECT_TRUE(fs::exists(path("drawn/frame-0001.svg")));
  Outcome bad = run({"path", kPlan, "--through", "L,Attic", "-o", "none"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("no room 'Attic'"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("'K'"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("none")));
}

// The film of a walk: path_test.cpp.

TEST_F(Cli, PathFollowsRecordedKeyframes) {
  write("keys.txt", "# eye, then the point looked at\n1.5 3 1.6  5 3 1.4\n\n3.0 2 1.6  5 1.6 1.4\n4.5 1.6 1.6  8 1.5 1.4\n");
  Outcome r =
      run({"path", kPlan, "--keys", "keys.txt", "-o", "keyed", "--format", "svg", "--size", "160x90", "--step", "0.5"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("keyed/frame-0001.svg")));
  write("bad.txt", "1.5 3 1.6  5 3 1.4\n1 2 3\n");
  Outcome bad = run({"path", kPlan, "--keys", "bad.txt", "-o", "none"});
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("bad.txt:2"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(path("none")));
  write("wall.txt", "1.5 3 1.6  5 3 1.4\n1.5 3 60  5 3 1.4\n");
  Outcome out = run({"path", kPlan, "--keys", "wall.txt", "-o", "none"});
  EXPECT_EQ(out.status, 2);
  EXPECT_NE(out.err.find("is inside the slab above storey"), std::string::npos) << out.err;  // it walks up through the ceiling
  EXPECT_FALSE(fs::exists(path("none")));
  EXPECT_EQ(run({"path", kPlan, "-o", "none"}).status, 2);
}

// --- plans from elsewhere: every PLAN argument takes them (app/plan_source.h) -------

namespace {
const std::string kSource = AVENUES_SOURCE_DIR;
const std::string kSeedWad = kSource + "/tests/fuzz/corpus/wad/two-sectors.wad";


}  // namespace

TEST_F(Cli, ADoomMapNamedInsideItsWadIsAPlanForEveryCommand) {
  Outcome r = run({"cells", kSeedWad + ":MAP01", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  json j = parse_json(r);
  EXPECT_EQ(j["rooms"], 2);
  EXPECT_GE(j["cells"].get<int>(), 2);
  EXPECT_TRUE(j["warnings"].empty()) << j["warnings"].dump();
  r = run({"view", kSeedWad + ":MAP01", "-o", "map.svg", "--size", "320x200"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("map.svg")));
  // With no map named, the first one, and the command says so.
  r = run({"cells", kSeedWad});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("reading MAP01, the first of its 1 maps"), std::string::npos) << r.err;
}

TEST_F(Cli, AMapTheWadDoesNotHoldIsAnErrorListingTheMapsItDoes) {
  Outcome r = run({"view", kSeedWad + ":MAP07", "-o", "map.svg"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("MAP07"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("MAP01"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("map.svg")));
}

TEST_F(Cli, ABrokenHomeIsAnErrorNamingItsLineAndWritesNothing) {
  write("home.xml", "<?xml version='1.0'?>\n<home wallHeight='250'>\n  <wall id='w0' xStart='0' yStart='0' xEnd='100'\n</home>\n");
  Outcome r = run({"view", "home.xml", "-o", "home.png"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("home.xml"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("home.png")));
  write("home.sh3d", "PK this is not a zip");
  r = run({"cells", "home.sh3d"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("home.sh3d"), std::string::npos) << r.err;
}

TEST_F(Cli, AMeshIsAWholeSceneAndACrowObjectToo) {
  Outcome r = run({"cells", kSource + "/plans/scenes/crow-table-1b.crow", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GE(parse_json(r)["cells"].get<int>(), 2);
  r = run({"view", kSource + "/plans/scenes/wylie-cube.off", "--eye", "2.5,-2,1.5", "--look", "0,0,0", "-o",
           "cube.svg"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("cube.svg")));
  write("broken.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n-1 1 1\n");
  r = run({"cells", "broken.off"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("broken.off"), std::string::npos) << r.err;
}

// An OBJ says nothing of its up axis. One that stands on y = 0 with its z either side of
// zero (a hut 3 m high, 4 m deep, as Blender exports Y-up) is taken as Y-up, with a warning
// saying so and how to say otherwise; --up z keeps it as written; the Viking room, whose
// lowest point is below zero, stays z-up.
TEST_F(Cli, AnObjStandingOnYZeroIsTakenAsDrawnYUpSayingSo) {
  write("hut.obj", "v -1 0 -2\nv 1 0 -2\nv 1 0 2\nv -1 0 2\nv -1 3 -2\nv 1 3 -2\nv 1 3 2\nv -1 3 2\n"
                   "f 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 2 6 7 3\nf 4 3 7 8\n");
  auto extent = [&](const std::string& obj, int axis) {  // of the exported surfaces, far box and all
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    std::istringstream in(slurp(path(obj)));
    for (std::string l; std::getline(in, l);) {
      if (!l.starts_with("v ")) continue;
      std::istringstream v(l.substr(2));
      double c[3];
      v >> c[0] >> c[1] >> c[2];
      lo = std::min(lo, c[axis]), hi = std::max(hi, c[axis]);
    }
    return hi - lo;
  };
  Outcome r = run({"export", "hut.obj", "-o", "guessed.obj"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("hut.obj: warning: the file does not say which axis is up: taken as y"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--up z"), std::string::npos) << r.err;
  r = run({"export", "hut.obj", "--up", "z", "-o", "as-written.obj"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("which axis is up"), std::string::npos) << r.err;
  // The far box's margin is the same either way: the heights differ by the hut's 3 m and 4 m.
  EXPECT_NEAR(extent("guessed.obj", 2) - extent("as-written.obj", 2), 3.0 - 4.0, 1e-9);
  const std::string viking = std::string(AVENUES_OUTSIDE_DIR) + "/meshes/viking-room/viking_room.obj";
  r = run({"cells", viking});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("which axis is up"), std::string::npos) << r.err;
}

// Every broken file of Assimp's own test models (and one cut short) is refused with exit 2
// and a message naming it, never a crash or a hang. Two OBJ files are read, as OBJ's own
// tools read them: malformed2.obj, whose only fault is a stray line, and malformed.obj,
// whose faces naming vertices that are not there are dropped with a warning naming the line
// (never silently: issue 13).
TEST_F(Cli, AssimpsInvalidModelsAreClearErrorsNamingTheFile) {
  const fs::path invalid = "/usr/share/assimp/models/invalid";
  if (!fs::exists(invalid)) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(invalid)) files.push_back(e.path().string());
  write("cut.glb", slurp("/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb").substr(0, 300));
  files.push_back(path("cut.glb").string());
  for (const std::string& f : files) {
    SCOPED_TRACE(f);
    const Outcome r = run({"cells", f});
    if (f.ends_with("malformed2.obj")) {
      EXPECT_EQ(r.status, 0) << r.err;
      continue;
    }
    if (f.ends_with("malformed.obj")) {
      EXPECT_EQ(r.status, 0) << r.err;
      EXPECT_NE(r.err.find("line 23: face corner '12' names no vertex"), std::string::npos) << r.err;
      continue;
    }
    EXPECT_EQ(r.status, 2) << r.out << r.err;
    EXPECT_NE(r.err.find(f), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("terminate"), std::string::npos) << r.err;
  }
}

TEST_F(Cli, IfcModelIsABuildingAndBadUpOrUnitIsRefused) {
  const std::string model = "/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc";
  if (!fs::exists(model)) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  const Outcome r = run({"cells", model, "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json j = parse_json(r);
  EXPECT_EQ(j["storeys"].get<int>(), 2);
  EXPECT_GE(j["named_rooms"].get<int>(), 5);
  EXPECT_EQ(run({"cells", model, "--up", "w"}).status, 2);
  EXPECT_EQ(run({"cells", model, "--unit", "furlong"}).status, 2);
}

// An .xml file that is no Sweet Home home but a model in XML (COLLADA, XGL) opens as a
// mesh scene; XML that nothing reads names its root element, and an Irrlicht mesh with no
// triangle (Assimp's invalid/emptyIrrMesh.xml), taken by its content, says so.
TEST_F(Cli, ModelsInXmlOpenAndOtherXmlNamesItsRoot) {
  const fs::path models = "/usr/share/assimp/models";
  if (!fs::exists(models / "Collada/AsXML.xml")) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  for (const char* f : {"Collada/AsXML.xml", "XGL/sample_official_asxml.xml"}) {
    const Outcome r = run({"cells", (models / f).string(), "--json"});
    ASSERT_EQ(r.status, 0) << f << ": " << r.err;
    EXPECT_GT(parse_json(r)["cells"].get<int>(), 1) << f;
  }
  write("drawing.xml", "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\"/>\n");
  const Outcome svg = run({"cells", path("drawing.xml").string()});
  EXPECT_EQ(svg.status, 2);
  EXPECT_NE(svg.err.find("root element is <svg>, not <home>"), std::string::npos) << svg.err;
  const Outcome irr = run({"cells", (models / "invalid/emptyIrrMesh.xml").string()});
  EXPECT_EQ(irr.status, 2);
  EXPECT_NE(irr.err.find("it is XML with no <home> element"), std::string::npos) << irr.err;
  EXPECT_NE(irr.err.find("Avenues' Irrlicht mesh reader took it by its content but could not read it"), std::string::npos)
      << irr.err;
  EXPECT_NE(irr.err.find("it holds no triangle Avenues can draw"), std::string::npos) << irr.err;
}

// A 3D model saved as DXF (no wall layer, 3D faces) opens as a mesh scene, not as a
// floor plan refused for its layers.
TEST_F(Cli, DxfThatIsA3dModelOpensAsAMeshScene) {
  const std::string model = "/usr/share/assimp/models/DXF/wuson.dxf";
  if (!fs::exists(model)) GTEST_SKIP() << "assimp-testmodels not installed (.ci/install-deps)";
  const Outcome r = run({"cells", model, "--up", "y", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("a 3D model"), std::string::npos) << r.err;
  const json j = parse_json(r);
  EXPECT_GT(j["cells"].get<int>(), 100);
  // Naming a wall layer asks for a floor plan, which it is not: refused, its layers listed.
  const Outcome plan = run({"cells", model, "--layers", "walls=1"});
  EXPECT_EQ(plan.status, 2);
  EXPECT_NE(plan.err.find("wuson.dxf"), std::string::npos) << plan.err;
}

// An IFC model with nothing to walk between (a structural model's members, equipment) is
// shown as a scene of its elements' faces rather than refused.
TEST_F(Cli, IfcModelWithoutWallsOpensAsAMeshScene) {
  std::string ifc = slurp(std::string(AVENUES_SOURCE_DIR) + "/tests/fuzz/corpus/ifc/l-walled-room.ifc");
  for (size_t at = ifc.find("IFCWALL("); at != std::string::npos; at = ifc.find("IFCWALL(", at))
    ifc.replace(at, 8, "IFCMEMBER(");  // the same solids, as members: no wall left
  write("members.ifc", ifc);
  const Outcome r = run({"cells", path("members.ifc").string(), "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("no walls or columns to walk between"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("read as a mesh scene"), std::string::npos) << r.err;
  const json j = parse_json(r);
  EXPECT_GT(j["cells"].get<int>(), 4);
  EXPECT_EQ(j["storeys"].get<int>(), 0);  // a scene, not a building
}

// --save-plan asks for a plan; a mesh scene (an OBJ, a DXF that is a 3D model) has none.
TEST_F(Cli, SavePlanOfAMeshSceneIsRefusedBeforeTheWork) {
  const std::string torus = std::string(AVENUES_SOURCE_DIR) + "/plans/scenes/torus.off";
  const Outcome r = run({"cells", torus, "--save-plan", "torus.toml"});
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--save-plan"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("torus.off"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(path("torus.toml")));
}

// --- 2D plans from elsewhere (issue 19): what was understood, refusals, --save-plan.

TEST_F(Cli, DxfPlanSaysWhatItUnderstoodAndSavesItAsToml) {
  const std::string dxf = std::string(AVENUES_OUTSIDE_DIR) + "/dxf/anandkothartrdl-plan.dxf";
  const Outcome r = run({"cells", dxf, "--save-plan", "house.toml"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("Ext Walls', 'Walls'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" doors, "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("is in no wall gap: not placed"), std::string::npos) << r.err;
  const Outcome back = run({"cells", "house.toml"});
  EXPECT_EQ(back.status, 0) << back.err;
}

TEST_F(Cli, DxfPlanDrawingShowsWhatWasUnderstoodOverTheDrawingsOwnLines) {
  const std::string dxf = std::string(AVENUES_OUTSIDE_DIR) + "/dxf/two-rooms.dxf";
  const Outcome r = run({"cells", dxf, "--svg", "plan.svg"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string svg = slurp(path("plan.svg"));
  // The drawing's lines first, in light blue, then the walls cut, the door and the rooms.
  const size_t drawing = svg.find("<g class=\"drawing\""), cut = svg.find("<g class=\"cut\"");
  ASSERT_NE(drawing, std::string::npos);
  ASSERT_NE(cut, std::string::npos);
  EXPECT_LT(drawing, cut);
  const std::string lines = svg.substr(drawing, svg.find("</g>", drawing) - drawing);
  size_t n = 0;
  for (size_t at = lines.find("<line"); at != std::string::npos; at = lines.find("<line", at + 1)) ++n;
  EXPECT_GT(n, 500u);  // the furniture, the door block and the walls, as drawn
  EXPECT_NE(svg.find("2 rooms"), std::string::npos);
  // A plan not read from a drawing has no such layer.
  ASSERT_EQ(run({"cells", kPlan, "--svg", "own.svg"}).status, 0);
  EXPECT_EQ(slurp(path("own.svg")).find("class=\"drawing\""), std::string::npos);
}

TEST_F(Cli, DxfWithoutAWallLayerOpensSayingWhichLayerItTookAsWalls) {
  const std::string dxf = std::string(AVENUES_OUTSIDE_DIR) + "/dxf/evil-spirit-house.dxf";
  const Outcome r = run({"cells", dxf, "--save-plan", "guessed.toml"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("the lines of layer(s) 's001-#def-active-grp' are taken as walls"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--layers"), std::string::npos) << r.err;
  EXPECT_EQ(files().count("guessed.toml"), 1u);
  const Outcome named = run({"cells", dxf, "--layers", "walls=nosuch", "--save-plan", "never.toml"});
  EXPECT_EQ(named.status, 2);
  EXPECT_NE(named.err.find("no layer 'nosuch'"), std::string::npos) << named.err;
  EXPECT_EQ(files().count("never.toml"), 0u);
}

// A warning that names its own place in the file (a Sweet Home element's line) is printed
// with that place in front and the file named once, as a compiler would print it.
TEST_F(Cli, WarningsNameTheirFileOnceWithTheirPlaceInIt) {
  const std::string home = std::string(AVENUES_OUTSIDE_DIR) + "/sweethome/casa-both-formats.sh3d";
  const Outcome r = run({"cells", home});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find(home + ":Home.xml:26:3 (level 'Seminterrato'): warning: level 'Seminterrato'"), std::string::npos)
      << r.err;
  std::istringstream lines(r.err);
  int warnings = 0;
  for (std::string l; std::getline(lines, l);) {
    if (l.find("warning: ") == std::string::npos) continue;
    ++warnings;
    EXPECT_EQ(l.find(home, 1), std::string::npos) << l;
    EXPECT_EQ(l.rfind(home, 0), 0u) << l;
  }
  EXPECT_GE(warnings, 10);
}

// An IFC model's plan as understood, stairwells and bulkheads' gaps and all, is saved as for
// any import, and reads back as the same cells.
TEST_F(Cli, IfcModelSavesItsPlanAndItReadsBackTheSame) {
  auto line = [](const std::string& out, const std::string& head) {
    const size_t at = out.find("\n" + head);
    return at == std::string::npos ? std::string() : out.substr(at + 1, out.find('\n', at + 1) - at - 1);
  };
  for (const char* model : {"duplex", "Office_A_20110811"}) {
    SCOPED_TRACE(model);
    const std::string ifc = std::string(AVENUES_OUTSIDE_DIR) + "/ifc/" + model + ".ifc";
    const Outcome r = run({"cells", ifc, "--save-plan", "saved.toml"});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string toml = slurp(path("saved.toml"));
    EXPECT_NE(toml.find("[[floor_opening]]"), std::string::npos);
    if (std::string(model) == "Office_A_20110811") {
      EXPECT_NE(toml.find("name = 'beneath "), std::string::npos);
    }
    const Outcome back = run({"cells", "saved.toml"});
    ASSERT_EQ(back.status, 0) << back.err;
    EXPECT_NE(line(r.out, "cells "), "");
    EXPECT_EQ(line(back.out, "cells "), line(r.out, "cells "));
    EXPECT_EQ(line(back.out, "portals "), line(r.out, "portals "));
    EXPECT_NE(line(r.out, "cells ").find("stairwell"), std::string::npos) << r.out;
  }
}

TEST_F(Cli, FloorPlanAnnotationsOpenWithTheirScale) {
  const std::string txt = std::string(AVENUES_OUTSIDE_DIR) + "/floorplans/00_e9_f85ba733b3769c159604debc08c6_0001.txt";
  const Outcome r = run({"cells", txt, "--scale", "0.05"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("rooms"), std::string::npos);
  EXPECT_EQ(run({"cells", txt, "--scale", "-1"}).status, 2);
}

