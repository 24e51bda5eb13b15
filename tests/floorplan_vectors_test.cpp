// Tests of the Raster-to-Vector annotation reader (plans/formats/floorplan_vectors.cpp):
// the four samples in ../shared/outside/floorplans open as valid, walkable plans whose
// views agree with ray casting; hand-made annotations show the conventions (pixels, y
// down, doors on walls, labels, fixtures) and malformed lines are errors naming the line.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "plan_import_oracle.h"
#include "plans/formats/floorplan_vectors.h"

namespace avenues {
namespace {

namespace fs = std::filesystem;
const fs::path kSamples = fs::path(AVENUES_OUTSIDE_DIR) / "floorplans";

TEST(FloorplanVectors, TheFourSamplesOpenAsWalkablePlans) {
  ASSERT_TRUE(fs::is_directory(kSamples)) << kSamples;
  int files = 0;
  for (const auto& e : fs::directory_iterator(kSamples)) {
    if (e.path().extension() != ".txt") continue;
    SCOPED_TRACE(e.path().filename().string());
    const Plan plan = read_floorplan_vectors(e.path().string());
    const CellComplex c = build_cells(plan);
    EXPECT_EQ(cells_are_valid(c), "");
    EXPECT_GE(plan.walls.size(), 10u);
    EXPECT_GE(plan.rooms.size(), 5u);
    int rooms_with_cells = 0;
    for (size_t r = 0; r < plan.rooms.size(); ++r) {
      bool has = false;
      for (const Cell& cell : c.cells) has = has || cell.room == RoomId(r);
      rooms_with_cells += has;
    }
    EXPECT_GE(rooms_with_cells, 5);
    EXPECT_GE(avenues::testing::door_portals(c), 5);
    EXPECT_GE(avenues::testing::check_views_from_rooms(plan, c), 16);
    ++files;
  }
  EXPECT_EQ(files, 4);
}

TEST(FloorplanVectors, TwoRoomsAndADoorByHand) {
  // A 100 x 50 pixel box split at x = 50, a door of 20 px in the partition, a bed label
  // each side and a toilet; 0.05 m per pixel: 5 m by 2.5 m.
  const std::string text =
      "0\t0\t100\t0\twall\t1\t1\n"
      "100\t0\t100\t50\twall\t1\t1\n"
      "100\t50\t0\t50\twall\t1\t1\n"
      "0\t50\t0\t0\twall\t1\t1\n"
      "50\t0\t50\t50\twall\t1\t1\n"
      "50\t15\t50\t35\tdoor\t1\t1\n"
      "10\t10\t30\t20\tbedroom\t1\t1\n"
      "60\t10\t90\t20\tbedroom\t1\t1\n"
      "70\t30\t80\t45\ttoilet\t1\t1\n";
  FloorplanVectorOptions o;
  o.metres_per_pixel = 0.05;
  const Plan plan = parse_floorplan_vectors(text, "hand.txt", o);
  ASSERT_EQ(plan.walls.size(), 5u);
  ASSERT_EQ(plan.rooms.size(), 2u);
  EXPECT_EQ(plan.rooms[0].name, "bedroom");
  EXPECT_EQ(plan.rooms[1].name, "bedroom 2");
  EXPECT_NEAR(plan.rooms[0].label->x, 1.0, 1e-12);
  EXPECT_NEAR(plan.rooms[0].label->y, -0.75, 1e-12);  // y down in pixels, up in metres
  ASSERT_EQ(plan.walls[4].openings.size(), 1u);
  const Opening& d = plan.walls[4].openings[0];
  // The partition runs from y = 0 down to y = -2.5 m, lengthened by half a wall at each end.
  EXPECT_NEAR(d.at, 0.75 + o.wall_thickness / 2, 1e-9);
  EXPECT_NEAR(d.width, 1.0, 1e-9);
  ASSERT_EQ(plan.objects.size(), 1u);
  EXPECT_NEAR(plan.objects[0].box.x, 0.5, 1e-12);
  const CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_EQ(avenues::testing::door_portals(c), 2);  // the doorway cell's two faces
  EXPECT_TRUE(c.warnings.empty());
}

TEST(FloorplanVectors, ContentIsToldFromOtherText) {
  EXPECT_TRUE(looks_like_floorplan_vectors("\n12\t3\t40\t3\twall\t1\t1\n"));
  EXPECT_FALSE(looks_like_floorplan_vectors("name = \"house\"\n"));
  EXPECT_FALSE(looks_like_floorplan_vectors("1 2 3 4\n"));
}

TEST(FloorplanVectors, MalformedLinesNameTheLine) {
  try {
    parse_floorplan_vectors("0 0 10 0 wall 1 1\n0 x 10 0 wall 1 1\n", "bad.txt");
    FAIL() << "no error";
  } catch (const PlanError& e) {
    EXPECT_EQ(e.where().line, 2);
    EXPECT_NE(std::string(e.what()).find("'x' is not a number"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_floorplan_vectors("0 0 10 0 wall\n1 2 3\n", "bad.txt"), PlanError);
  EXPECT_THROW(parse_floorplan_vectors("0 0 10 10 bedroom 1 1\n", "nowalls.txt"), PlanError);
  FloorplanVectorOptions o;
  o.metres_per_pixel = 0;
  EXPECT_THROW(parse_floorplan_vectors("0 0 10 0 wall 1 1\n", "scale.txt", o), PlanError);
  // Lenient about what it cannot use: a door on no wall and an unknown category warn.
  const Plan p = parse_floorplan_vectors("0 0 10 0 wall 1 1\n0 5 10 5 door 1 1\n0 0 1 1 spaceship 1 1\n", "odd.txt");
  EXPECT_EQ(p.warnings.size(), 2u);
}

}  // namespace
}  // namespace avenues
