// The ray oracle's box trees (tests/ray_oracle.h, OracleIndex) against its brute-force
// loops: on a plan and on soups, rays from random eyes in random directions, and from
// eyes standing on faces, find the same first hit, to the bit, and the same cells crossed.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "app/plan_source.h"
#include "cells/mesh_scene.h"
#include "plans/mesh.h"
#include "tests/ray_oracle.h"
#include "tests/test_files.h"
#include "tests/test_plans.h"

using namespace avenues;
using avenues::testing::OracleIndex;

namespace {

/// Rays from random points of random cells (and from corners of faces, on the faces'
/// planes) in random directions: first_hit and the cells crossed before it, both ways.
void expect_index_agrees(const CellComplex& c, unsigned seed, int rays) {
  const OracleIndex index(c);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, c.cells.size() - 1);
  std::uniform_real_distribution<double> unit(-1, 1);
  int hits = 0, crossings = 0;
  for (int r = 0; r < rays; ++r) {
    const Cell& cell = c.cells[pick(rng)];
    // Every fourth on a face's corner: that face does not stop it.
    const Vec3 o = r % 4 == 3 ? cell.faces[size_t(rng() % cell.faces.size())].poly[0]
                              : avenues::testing::random_point_in(cell, rng);
    Vec3 dir{unit(rng), unit(rng), unit(rng)};
    if (r % 8 == 5) dir.z = 0;  // level, as most of a walker's rays
    if (r % 16 == 9) dir = {0, 0, -1};  // straight down, along two axes of every box
    SCOPED_TRACE("ray " + std::to_string(r));
    const double brute = avenues::testing::first_hit(c, o, dir), boxed = index.first_hit(o, dir);
    ASSERT_EQ(brute, boxed);
    hits += std::isfinite(brute);
    std::set<CellId> all, crossed;
    for (CellId id = 0; id < CellId(c.cells.size()); ++id)
      if (avenues::testing::length_inside(c.cells[size_t(id)], o, dir, 0, brute) > 1e-6) all.insert(id);
    index.cells_crossed(o, dir, brute, [&](CellId id) { crossed.insert(id); });
    ASSERT_EQ(all, crossed);
    crossings += int(all.size());
  }
  EXPECT_GT(hits, rays / 2);  // most rays end on a surface (the far box is opaque)
  EXPECT_GT(crossings, rays);
}

}  // namespace

TEST(RayOracle, BoxTreesFindWhatEveryFaceAndCellTriedFindOnAPlan) {
  const CellComplex c = app::load_plan_source(avenues::testing::plan_path("jones-house.toml")).complex;
  expect_index_agrees(c, 1, 4000);
}

TEST(RayOracle, BoxTreesFindWhatEveryFaceAndCellTriedFindOnSoups) {
  for (const char* f : {"meshes/CornellBox-Original.obj", "meshes/alpine-cabin/house.obj"}) {
    SCOPED_TRACE(f);
    const CellComplex c = build_mesh_scene({load_mesh(avenues::testing::outside_path(f))});
    expect_index_agrees(c, 2, 3000);
  }
}
