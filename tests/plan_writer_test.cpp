// Tests of plans/plan_writer.cpp: what write_plan() writes, read_plan() reads back as
// the same plan (the bundled plans, and one imported from floor-plan annotations).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cells/build_cells.h"
#include "cells/cell_complex.h"
#include "plans/formats/floorplan_vectors.h"
#include "plans/plan.h"
#include "plans/plan_writer.h"

namespace avenues {
namespace {

namespace fs = std::filesystem;

void expect_same_plan(const Plan& a, const Plan& b) {
  ASSERT_EQ(a.storeys.size(), b.storeys.size());
  for (size_t i = 0; i < a.storeys.size(); ++i) {
    EXPECT_EQ(a.storeys[i].name, b.storeys[i].name);
    EXPECT_DOUBLE_EQ(a.storeys[i].elevation, b.storeys[i].elevation);
    EXPECT_DOUBLE_EQ(a.storeys[i].height, b.storeys[i].height);
  }
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (size_t i = 0; i < a.walls.size(); ++i) {
    const Wall &u = a.walls[i], &v = b.walls[i];
    SCOPED_TRACE(u.name);
    EXPECT_EQ(u.name, v.name);
    EXPECT_EQ(u.storey, v.storey);
    EXPECT_DOUBLE_EQ(u.thickness, v.thickness);
    EXPECT_DOUBLE_EQ(u.height, v.height);
    ASSERT_EQ(u.centre.size(), v.centre.size());
    for (size_t k = 0; k < u.centre.size(); ++k) {
      EXPECT_DOUBLE_EQ(u.centre[k].x, v.centre[k].x);
      EXPECT_DOUBLE_EQ(u.centre[k].y, v.centre[k].y);
    }
    ASSERT_EQ(u.openings.size(), v.openings.size());
    for (size_t k = 0; k < u.openings.size(); ++k) {
      EXPECT_EQ(u.openings[k].kind, v.openings[k].kind);
      EXPECT_NEAR(u.openings[k].at, v.openings[k].at, 1e-9);
      EXPECT_DOUBLE_EQ(u.openings[k].width, v.openings[k].width);
      EXPECT_DOUBLE_EQ(u.openings[k].sill, v.openings[k].sill);
      EXPECT_DOUBLE_EQ(u.openings[k].head, v.openings[k].head);
    }
  }
  ASSERT_EQ(a.rooms.size(), b.rooms.size());
  for (size_t i = 0; i < a.rooms.size(); ++i) {
    EXPECT_EQ(a.rooms[i].name, b.rooms[i].name);
    EXPECT_DOUBLE_EQ(a.rooms[i].label->x, b.rooms[i].label->x);
    EXPECT_DOUBLE_EQ(a.rooms[i].label->y, b.rooms[i].label->y);
  }
  EXPECT_EQ(a.materials.size(), b.materials.size());
  EXPECT_EQ(a.lights.size(), b.lights.size());
  EXPECT_EQ(a.view.has_value(), b.view.has_value());
}

TEST(PlanWriter, BundledPlansRoundTrip) {
  for (const char* name : {"jones-house.toml", "two-storey-house.toml", "office-corridor.toml"}) {
    SCOPED_TRACE(name);
    const Plan a = read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans" / name).string());
    const Plan b = parse_plan(plan_as_toml(a), std::string("written-") + name);
    expect_same_plan(a, b);
  }
}

TEST(PlanWriter, ImportedAnnotationsRoundTrip) {
  const fs::path dir = fs::path(AVENUES_OUTSIDE_DIR) / "floorplans";
  for (const auto& e : fs::directory_iterator(dir)) {
    const Plan a = read_floorplan_vectors(e.path().string());
    const std::string text = plan_as_toml(a);
    EXPECT_NE(text.find("# not expressible here, left out:"), std::string::npos);  // its fixtures
    const Plan b = parse_plan(text, e.path().filename().string() + ".toml");
    expect_same_plan(a, b);
    EXPECT_TRUE(b.lenient) << "the importer's leniency is kept (lenient = true)";
  }
}

// `lenient` is a plan's own setting: true reads the plan as an imported one is read; it
// must be a boolean.
TEST(PlanWriter, LenientIsABooleanSettingOfThePlan) {
  const std::string walls =
      "[[wall]]\nname = 'box'\nthickness = 0.2\npath = [[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]]\n";
  EXPECT_FALSE(parse_plan(walls, "strict.toml").lenient);
  EXPECT_TRUE(parse_plan("lenient = true\n" + walls, "lenient.toml").lenient);
  try {
    parse_plan("lenient = 'yes'\n" + walls, "bad.toml");
    ADD_FAILURE() << "a string for lenient was taken";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'lenient' must be true or false, not a string"), std::string::npos) << e.what();
  }
}

TEST(PlanWriter, UnnamedSpacesSolidIsABooleanSettingOfThePlan) {
  // A box with a closet walled off by walls of no thickness and no room label in it.
  const std::string walls =
      "[[wall]]\nname = 'box'\nthickness = 0.2\npath = [[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]]\n"
      "[[wall]]\nname = 'closet'\nthickness = 0\npath = [[3, 0.1], [3, 1], [3.9, 1]]\n"
      "[[room]]\nname = 'room'\nat = [1, 1.5]\n";
  const Plan plain = parse_plan(walls, "plain.toml");
  EXPECT_FALSE(plain.unnamed_spaces_solid);
  const Plan solid = parse_plan("unnamed_spaces_solid = true\n" + walls, "solid.toml");
  EXPECT_TRUE(solid.unnamed_spaces_solid);
  EXPECT_NE(plan_as_toml(solid).find("unnamed_spaces_solid = true"), std::string::npos);
  // The closet is a room of its own ("space 1") unless unnamed spaces are solid; the
  // outside stays free either way.
  const CellComplex a = build_cells(plain), b = build_cells(solid);
  EXPECT_EQ(a.rooms.size(), 2u);
  EXPECT_EQ(b.rooms.size(), 1u);
  EXPECT_EQ(cells_are_valid(b), "");
  int outside = 0;
  for (const Cell& c : b.cells) outside += c.kind == CellKind::Outside;
  EXPECT_GT(outside, 0);
  try {
    parse_plan("unnamed_spaces_solid = 1\n" + walls, "bad.toml");
    ADD_FAILURE() << "a number for unnamed_spaces_solid was taken";
  } catch (const PlanError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'unnamed_spaces_solid' must be true or false"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace avenues
