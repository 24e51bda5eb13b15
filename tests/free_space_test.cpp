// The cells' union is the free space: an independent check with CGAL's Boolean set
// operations. At heights inside each storey, the area of the cells present there must
// equal the far box minus the union of the walls standing there (joined by CGAL, not by
// Avenues' triangulation), for the hand-made and bundled plans alike.
#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_set_2.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "cells/build_cells.h"
#include "cells/outline.h"

using namespace avenues;

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;

/// Area [m²] of the walls (thick-wall pieces) of `plan` that are solid at height z.
double wall_area_at(const Plan& plan, double z) {
  detail::Outline o = detail::make_outline(plan);
  CGAL::Polygon_set_2<K> walls;
  std::vector<CGAL::Polygon_2<K>> polys;
  for (const detail::Region& r : o.regions) {
    if (r.sheet) continue;
    const Storey& s = plan.storeys[size_t(r.storey)];
    if (z <= s.elevation || z >= s.elevation + s.height) continue;
    bool open = false;
    for (auto [lo, hi] : r.open) open |= lo < z && z < hi;
    if (open) continue;
    CGAL::Polygon_2<K> p;
    for (Vec2 v : r.poly) p.push_back(K::Point_2(v.x, v.y));
    polys.push_back(p);
  }
  walls.join(polys.begin(), polys.end());
  std::vector<CGAL::Polygon_with_holes_2<K>> out;
  walls.polygons_with_holes(std::back_inserter(out));
  K::FT area = 0;
  for (const auto& pwh : out) {
    area += pwh.outer_boundary().area();
    for (auto h = pwh.holes_begin(); h != pwh.holes_end(); ++h) area += h->area();  // holes are clockwise
  }
  return CGAL::to_double(area);
}

double cell_area_at(const CellComplex& c, double z) {
  double a = 0;
  for (const Cell& cell : c.cells) {
    if (!(cell.z0 < z && z < cell.z1)) continue;
    double s = 0;
    for (size_t i = 0; i < cell.footprint.size(); ++i)
      s += cross(cell.footprint[i], cell.footprint[(i + 1) % cell.footprint.size()]);
    a += s / 2;
  }
  return a;
}

void expect_free_space(const Plan& plan) {
  CellComplex c = build_cells(plan);
  EXPECT_EQ(cells_are_valid(c), "") << plan.name;
  const double box = (c.far_box.hi.x - c.far_box.lo.x) * (c.far_box.hi.y - c.far_box.lo.y);
  for (const Storey& s : plan.storeys)
    for (double f : {0.05, 0.3, 0.5, 0.7, 0.97}) {
      double z = s.elevation + f * s.height;
      if (z <= 0) continue;  // below ground the outside is earth
      EXPECT_NEAR(cell_area_at(c, z), box - wall_area_at(plan, z), 1e-6 * box)
          << plan.name << " at z = " << z;
    }
}

}  // namespace

TEST(FreeSpace, BundledPlansCellsCoverExactlyTheSpaceBetweenWalls) {
  const std::filesystem::path dir = std::filesystem::path(AVENUES_SOURCE_DIR) / "plans";
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().string());
    expect_free_space(read_plan(entry.path().string()));
    ++n;
  }
  EXPECT_GE(n, 4);
}
