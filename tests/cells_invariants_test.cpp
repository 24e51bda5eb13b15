// The cell complex's invariants on every bundled plan and on generated offices:
// valid (convex cells, no overlaps, convex portals in a face of each of their two
// distinct cells, faces covered by opaque pieces and portals), and point location
// agreeing with brute force on random points (inside walls and slabs too).
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "cells/build_cells.h"
#include "core/check.h"
#include "plans/generate.h"

using namespace avenues;

namespace {

void expect_invariants(const Plan& plan) {
  SCOPED_TRACE(plan.name);
  CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "");
  for (const Portal& p : c.portals) EXPECT_NE(p.cell[0], p.cell[1]);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(c.far_box.lo.x, c.far_box.hi.x), y(c.far_box.lo.y, c.far_box.hi.y),
      z(c.far_box.lo.z, c.far_box.hi.z);
  // Half the points where the building is, half anywhere in the box.
  Box3 building;
  for (const Cell& cell : c.cells)
    if (cell.kind == CellKind::Room) building.add(cell.bounds().lo), building.add(cell.bounds().hi);
  std::uniform_real_distribution<double> bx(building.lo.x, building.hi.x), by(building.lo.y, building.hi.y),
      bz(building.lo.z, building.hi.z);
  CellId hint = kNoCell;
  for (int i = 0; i < 600; ++i) {
    Vec3 q = i % 2 ? Vec3{x(rng), y(rng), z(rng)} : Vec3{bx(rng), by(rng), bz(rng)};
    bool in_some = false;
    for (const Cell& cell : c.cells) in_some |= cell.contains(q);
    Location loc = c.locate(q, hint);
    if (!in_some) {
      EXPECT_EQ(loc.what, Location::What::Solid) << q.x << "," << q.y << "," << q.z;
      EXPECT_FALSE(loc.solid.empty());
    } else {
      ASSERT_EQ(loc.what, Location::What::Cell) << q.x << "," << q.y << "," << q.z;
      EXPECT_TRUE(c.cells[size_t(loc.cell)].contains(q));
      hint = loc.cell;
    }
  }
}

}  // namespace

TEST(CellInvariants, EveryBundledPlan) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(AVENUES_SOURCE_DIR) / "plans"))
    if (e.path().extension() == ".toml") expect_invariants(read_plan(e.path().string())), ++n;
  EXPECT_GE(n, 4);
}

TEST(CellInvariants, GeneratedOffices) {
  for (auto [rows, cols] : {std::pair{1, 1}, {2, 3}, {3, 3}, {5, 5}, {10, 10}, {7, 12}})
    expect_invariants(parse_plan(generate_office_toml(rows, cols),
                                 "office-" + std::to_string(rows) + "x" + std::to_string(cols)));
}

// check_complex (core/check.h's second tier): in builds with invariant checks every
// builder and loader validates what it returns; a broken complex is an InvariantError
// naming what it was built from, never a silent wrong answer.
TEST(CellsInvariants, CheckComplexCatchesABrokenComplexInCheckedBuilds) {
  const Plan plan = read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml");
  CellComplex c = build_cells(plan);  // valid: passes the check in every build
  ASSERT_FALSE(c.portals.empty());
  c.portals[0].cell[1] = c.portals[0].cell[0];  // a portal joining a cell to itself
  ASSERT_NE(cells_are_valid(c), "");
  if (kInvariantChecks) {
    try {
      check_complex(c, "jones-house");
      FAIL() << "no InvariantError";
    } catch (const InvariantError& e) {
      EXPECT_NE(std::string(e.what()).find("jones-house"), std::string::npos) << e.what();
    }
  } else {
    EXPECT_NO_THROW(check_complex(c, "jones-house"));
  }
}
