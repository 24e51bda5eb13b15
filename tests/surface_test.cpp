// Tests of a complex's surfaces (cells/surface.cpp, Surface in cells/cell_complex.h): every
// opaque piece of one plane and one material is one surface, however many cells cut it,
// and the half-tone gives every piece of a surface one flat shade (Bouknight's polygon),
// so that no false edge shows where cells meet (issue 15: Freedoom MAP01's default view
// drew one plane of its left wall in three bands, 142, 136 and 132).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "plans/formats/doom_map.h"
#include "plans/plan.h"
#include "render/scene_objects.h"
#include "render/scene_screen.h"
#include "tests/test_files.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

namespace avenues {
namespace {

namespace fs = std::filesystem;

struct PieceAt {
  const OpaquePoly* piece;
  Vec3 normal;  ///< unit
};

/// Every opaque piece, with its unit normal (Newell's, from its own vertices).
std::vector<PieceAt> pieces_of(const CellComplex& c) {
  std::vector<PieceAt> out;
  for (const Cell& cell : c.cells)
    for (const Face& face : cell.faces)
      for (const OpaquePoly& p : face.opaque) {
        Vec3 n{0, 0, 0};
        for (size_t i = 0; i < p.poly.size(); ++i)
          n = n + cross(p.poly[i] - p.poly[0], p.poly[(i + 1) % p.poly.size()] - p.poly[0]);
        out.push_back({&p, (1 / length(n)) * n});
      }
  return out;
}

/// The oracle, pair by pair: two pieces are of one surface when they have one material,
/// face the same way and every vertex of each lies within a micrometre of the other's
/// plane (the grouping allows 10 µm; pieces of different surfaces are far further apart).
void expect_surfaces_are_planes_and_materials(const CellComplex& c) {
  const std::vector<PieceAt> pieces = pieces_of(c);
  ASSERT_FALSE(pieces.empty());
  std::map<int32_t, size_t> pieces_per_surface;
  for (const PieceAt& p : pieces) {
    ASSERT_GE(p.piece->surface, 0);
    ASSERT_LT(size_t(p.piece->surface), c.surfaces.size());
    ++pieces_per_surface[p.piece->surface];
  }
  auto on_plane_of = [](const PieceAt& a, const PieceAt& b) {
    for (Vec3 v : b.piece->poly)
      if (!(std::fabs(dot(a.normal, v - a.piece->poly[0])) < 1e-6)) return false;
    return true;
  };
  size_t same = 0;
  for (size_t i = 0; i < pieces.size(); ++i)
    for (size_t j = i + 1; j < pieces.size(); ++j) {
      const PieceAt &a = pieces[i], &b = pieces[j];
      const bool one = a.piece->material == b.piece->material && dot(a.normal, b.normal) > 1 - 1e-9 &&
                       on_plane_of(a, b) && on_plane_of(b, a);
      ASSERT_EQ(one, a.piece->surface == b.piece->surface)
          << "pieces " << i << " and " << j << " (surfaces " << a.piece->surface << ", " << b.piece->surface << ")";
      same += one;
    }
  EXPECT_GT(same, 0u) << "some surface is cut into pieces";
  // Each surface's centroid lies on its plane, and its area is its pieces' sum.
  std::vector<double> area(c.surfaces.size(), 0);
  for (const PieceAt& p : pieces) area[size_t(p.piece->surface)] += polygon_area(p.piece->poly);
  for (const PieceAt& p : pieces) {
    const Surface& s = c.surfaces[size_t(p.piece->surface)];
    EXPECT_LT(std::fabs(dot(p.normal, s.centroid - p.piece->poly[0])), 1e-6);
    EXPECT_NEAR(s.area, area[size_t(p.piece->surface)], 1e-9 * (1 + s.area));
  }
}

TEST(Surfaces, EachPlaneAndMaterialIsOneSurfaceInTheBundledPlans) {
  for (const auto& entry : fs::directory_iterator(fs::path(AVENUES_SOURCE_DIR) / "plans")) {
    if (entry.path().extension() != ".toml") continue;
    SCOPED_TRACE(entry.path().filename().string());
    expect_surfaces_are_planes_and_materials(build_cells(read_plan(entry.path().string())));
  }
}

// Far from the origin (as a surveyed plan is), rounding grows with the coordinates: the
// pieces of one wall are still one surface.
TEST(Surfaces, FarFromTheOriginTheyAreStillOne) {
  const Plan p = read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans/jones-house.toml").string());
  const CellComplex near = build_cells(p);
  const CellComplex far = build_cells(moved(p, {500000, 5400000}));
  expect_surfaces_are_planes_and_materials(far);
  EXPECT_EQ(far.surfaces.size(), near.surfaces.size());
}

TEST(Surfaces, EachPlaneAndMaterialIsOneSurfaceInAMeshScene) {
  const std::string cornell = avenues::testing::outside_path("meshes/CornellBox-Original.obj");
  if (!fs::exists(cornell)) GTEST_SKIP() << "no " << cornell;
  expect_surfaces_are_planes_and_materials(read_mesh_scene(cornell));
}

/// The flat shades of the face polygons of a view, by the surface each is a piece of.
std::map<int32_t, std::set<float>> flat_shades_by_surface(const CellComplex& c, const Viewpoint& vp) {
  const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 320, 180);
  const VisibleSet vs = find_visible(c, cam, c.locate(vp.eye).cell);
  SceneOptions so;
  so.shading.model = ShadingModel::Flat;
  const ScreenScene scene = screen_scene_of_view(c, {}, cam, vs, so);
  std::map<int32_t, std::set<float>> out;
  for (size_t i = 0; i < scene.polygons.size(); ++i) {
    const PolygonSource& src = scene.sources[i];
    if (src.kind != PolygonSource::Kind::Face) continue;
    const Face& face = c.cells[size_t(src.cell)].faces[size_t(src.face)];
    EXPECT_EQ(scene.shades[i].kind, SurfaceShade::Kind::Constant);
    // A face of one material is drawn whole, as its first piece's surface.
    out[face.opaque[0].surface].insert(scene.shades[i].intensity);
  }
  return out;
}

TEST(Surfaces, EveryPieceOfOneSurfaceTakesOneFlatShade) {
  const std::string wad = std::string(AVENUES_FREEDOOM_DIR) + "/freedoom2.wad";
  std::vector<std::pair<std::string, CellComplex>> complexes;
  if (fs::exists(wad)) complexes.emplace_back("freedoom2 MAP01", build_cells(read_doom_map(wad, "MAP01")));
  for (const char* plan : {"jones-house.toml", "office-corridor.toml"})
    complexes.emplace_back(plan, build_cells(read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans" / plan).string())));
  for (const auto& [name, c] : complexes) {
    SCOPED_TRACE(name);
    size_t cut = 0;  // surfaces seen in more than one piece
    for (const auto& [surface, shades] : flat_shades_by_surface(c, default_viewpoint(c))) {
      EXPECT_EQ(shades.size(), 1u) << "surface " << surface << " shows " << shades.size() << " flat shades";
      size_t pieces = 0;
      for (const Cell& cell : c.cells)
        for (const Face& f : cell.faces)
          for (const OpaquePoly& p : f.opaque) pieces += p.surface == surface;
      cut += pieces > 1;
    }
    EXPECT_GT(cut, 0u) << "the view shows a surface that cells cut";
  }
}

}  // namespace
}  // namespace avenues
