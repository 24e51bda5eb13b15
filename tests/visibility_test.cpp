// Tests of visibility/: the avenues of sight against an independent ray-casting oracle,
// on Jones's house and every bundled plan, and the hard cases of the visibility issue.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <set>

#include "cells/build_cells.h"
#include "ray_oracle.h"
#include "visibility/visible_set.h"

using namespace avenues;
using avenues::testing::first_hit;
using avenues::testing::length_inside;

namespace {

std::string plan_path(const std::string& name) {
  return (std::filesystem::path(AVENUES_SOURCE_DIR) / "plans" / name).string();
}

RoomId room_named(const CellComplex& c, const std::string& name) {
  for (size_t r = 0; r < c.rooms.size(); ++r)
    if (c.rooms[r].name == name) return RoomId(r);
  return -1;
}

struct OracleResult {
  int missing = 0, extra = 0, rays = 0;
};

/// Casts one ray per pixel (every `step` pixels): each cell a ray crosses before its first
/// opaque hit must be visible. Each avenue whose mask covers more than a pixel must be
/// crossed by the ray through its mask's centroid.
OracleResult check_against_rays(const CellComplex& c, const Camera& cam, const VisibleSet& vs, int step) {
  OracleResult r;
  std::set<CellId> visible(vs.cells.begin(), vs.cells.end());
  for (int j = step / 2; j < cam.height; j += step)
    for (int i = step / 2; i < cam.width; i += step) {
      Vec3 dir = cam.ray_through_raster({i + 0.5, j + 0.5});
      double t = first_hit(c, cam.eye, dir);
      ++r.rays;
      for (CellId id = 0; id < CellId(c.cells.size()); ++id)
        if (!visible.count(id) && length_inside(c.cells[size_t(id)], cam.eye, dir, 0, t) > 1e-6) ++r.missing;
    }
  const double px2 = (cam.width / (2 * cam.half_width())) * (cam.height / (2 * cam.half_height()));
  for (const Avenue& a : vs.avenues) {
    double area = 0, cx = 0, cy = 0;
    for (size_t k = 0; k < a.mask.size(); ++k) {
      Vec2 p = a.mask[k], q = a.mask[(k + 1) % a.mask.size()];
      double w = cross(p, q);
      area += w / 2;
      cx += (p.x + q.x) * w / 6;
      cy += (p.y + q.y) * w / 6;
    }
    if (area * px2 <= 1 || a.depth == 0) continue;  // the eye's own cell holds the eye, perhaps on its face
    Vec3 dir = (cx / area) * cam.right + (cy / area) * cam.up + cam.forward;
    double t = first_hit(c, cam.eye, dir);
    if (!(length_inside(c.cells[size_t(a.cell)], cam.eye, dir, 0, t) > 0)) ++r.extra;
  }
  return r;
}

/// A random eye inside a random room or outside cell, at a height within the cell.
Vec3 random_eye(const CellComplex& c, std::mt19937& rng, CellId& cell) {
  std::uniform_int_distribution<size_t> pick(0, c.cells.size() - 1);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  for (;;) {
    cell = CellId(pick(rng));
    const Cell& k = c.cells[size_t(cell)];
    if (k.kind != CellKind::Room && k.kind != CellKind::Outside) continue;
    // A random convex combination of the footprint's vertices.
    std::vector<double> w(k.footprint.size());
    double sum = 0;
    for (double& x : w) sum += (x = u(rng));
    Vec2 p{0, 0};
    for (size_t i = 0; i < w.size(); ++i) p = p + (w[i] / sum) * k.footprint[i];
    return {p.x, p.y, k.z0 + u(rng) * (k.z1 - k.z0)};
  }
}

}  // namespace

TEST(Visibility, JonesKitchenIsSeenThroughTheDoorAndSeparatelyThroughTheHatch) {
  CellComplex c = build_cells(read_plan(plan_path("jones-house.toml")));
  Camera cam = Camera::look_at({1.0, 0.5, 1.2}, {6, 3, 1.2}, 100, 400, 300);
  Location loc = c.locate(cam.eye);
  ASSERT_EQ(loc.what, Location::What::Cell);
  const RoomId K = room_named(c, "K"), D = room_named(c, "D");
  ASSERT_GE(K, 0);
  for (Kernel k : {Kernel::Double, Kernel::Exact}) {
    VisibleSet vs = find_visible(c, cam, loc.cell, k);
    int direct = 0, via_hatch = 0;
    for (size_t a = 0; a < vs.avenues.size(); ++a) {
      if (c.cells[size_t(vs.avenues[a].cell)].room != K) continue;
      bool through_dining = false;
      for (PortalId p : vs.path(int(a))) {
        const Portal& portal = c.portals[size_t(p)];
        through_dining |= c.cells[size_t(portal.cell[0])].room == D || c.cells[size_t(portal.cell[1])].room == D;
      }
      (through_dining ? via_hatch : direct)++;
    }
    EXPECT_GE(direct, 1) << to_string(k);
    EXPECT_GE(via_hatch, 1) << to_string(k);
    OracleResult r = check_against_rays(c, cam, vs, 4);
    EXPECT_EQ(r.missing, 0);
    EXPECT_EQ(r.extra, 0);
  }
}

TEST(Visibility, RandomViewsOfEveryBundledPlanAgreeWithRayCasting) {
  std::mt19937 rng(2026);
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(AVENUES_SOURCE_DIR) / "plans")) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    CellComplex c = build_cells(read_plan(entry.path().string()));
    for (int v = 0; v < 12; ++v) {
      CellId cell;
      Vec3 eye = random_eye(c, rng, cell);
      std::uniform_real_distribution<double> yaw(0, 360), pitch(-30, 30), fov(40, 110);
      const double y = yaw(rng), p = pitch(rng), f = fov(rng);
      Camera cam = Camera::yaw_pitch(eye, y, p, f, 96, 64);
      SCOPED_TRACE("view " + std::to_string(v) + ": eye " + std::to_string(eye.x) + "," + std::to_string(eye.y) +
                   "," + std::to_string(eye.z) + " yaw " + std::to_string(y) + " pitch " + std::to_string(p) +
                   " fov " + std::to_string(f));
      VisibleSet vs = find_visible(c, cam, cell, Kernel::Double);
      OracleResult r = check_against_rays(c, cam, vs, 1);
      EXPECT_EQ(r.missing, 0) << "view " << v << " eye " << eye.x << "," << eye.y << "," << eye.z;
      EXPECT_EQ(r.extra, 0) << "view " << v;
      // The exact kernel sees the same cells.
      const VisibleSet exact = find_visible(c, cam, cell, Kernel::Exact);
      EXPECT_EQ(exact.cells, vs.cells) << "view " << v;
      EXPECT_EQ(find_visible(c, cam, cell, Kernel::Filtered).cells, exact.cells) << "view " << v;
    }
  }
}
