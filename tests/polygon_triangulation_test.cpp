// Tests of plans/polygon_triangulation.h through mesh_of_polygons and load_mesh: a mesh's
// polygons that are not convex are covered exactly by their triangles (no notch filled,
// nothing doubled), in their own orientation; convex ones keep their fan.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "plans/mesh.h"
#include "plans/polygon_triangulation.h"
#include "tests/test_files.h"

using namespace avenues;
using avenues::testing::outside_path;

namespace {

double triangle_area(const Mesh& m, size_t t) {
  const auto& tr = m.triangles[t];
  const Vec3 a = m.vertices[size_t(tr[0])], b = m.vertices[size_t(tr[1])], c = m.vertices[size_t(tr[2])];
  return 0.5 * length(cross(b - a, c - a));
}

double total_area(const Mesh& m) {
  double s = 0;
  for (size_t t = 0; t < m.triangles.size(); ++t) s += triangle_area(m, t);
  return s;
}

/// True when a triangle of m holds point q (on the plane z = 0) strictly inside, either way round.
bool covered(const Mesh& m, Vec2 q) {
  for (const auto& tr : m.triangles) {
    const Vec3 a = m.vertices[size_t(tr[0])], b = m.vertices[size_t(tr[1])], c = m.vertices[size_t(tr[2])];
    auto side = [&](Vec3 u, Vec3 v) { return (v.x - u.x) * (q.y - u.y) - (v.y - u.y) * (q.x - u.x); };
    const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
    if ((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0)) return true;
  }
  return false;
}

/// Every triangle counter-clockwise seen from +z (the polygons' side).
void expect_facing_up(const Mesh& m) {
  for (const auto& tr : m.triangles) {
    const Vec3 a = m.vertices[size_t(tr[0])], b = m.vertices[size_t(tr[1])], c = m.vertices[size_t(tr[2])];
    EXPECT_GT(cross(b - a, c - a).z, 0);
  }
}

}  // namespace

TEST(PolygonTriangulation, AnLShapedFaceLeavesItsNotchOpen) {
  // 2 × 2 less its top-right quarter, counter-clockwise seen from above; the fan from the
  // first corner would cover the notch.
  const Mesh m = mesh_of_polygons("l.obj", {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}},
                                  {{0, 1, 2, 3, 4, 5}});
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_NEAR(total_area(m), 3.0, 1e-12);
  EXPECT_FALSE(covered(m, {1.5, 1.5}));
  EXPECT_TRUE(covered(m, {0.4, 1.6}));
  expect_facing_up(m);
  for (int p : m.polygon_of) EXPECT_EQ(p, 0);
}

TEST(PolygonTriangulation, AHoleBridgedIntoTheOutlineStaysOpen) {
  // A 3 × 3 square with a 1 × 1 hole, as exporters write it: one polygon that runs round
  // the outside, along a bridge to the hole, round the hole the other way, and back.
  const std::vector<Vec3> v = {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}, {1, 1, 0}, {1, 2, 0}, {2, 2, 0}, {2, 1, 0}};
  const Mesh m = mesh_of_polygons("keyhole.obj", v, {{0, 1, 2, 3, 0, 4, 5, 6, 7, 4}});
  EXPECT_NEAR(total_area(m), 8.0, 1e-12);
  EXPECT_FALSE(covered(m, {1.5, 1.5}));
  EXPECT_TRUE(covered(m, {0.3, 2.6}));
  expect_facing_up(m);
}

TEST(PolygonTriangulation, ABowTieKeepsBothLobesAndGainsItsCrossing) {
  std::vector<Vec3> v = {{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0}};
  const Mesh m = mesh_of_polygons("bowtie.obj", v, {{0, 1, 2, 3}});
  EXPECT_EQ(m.vertices.size(), 5u);  // the crossing at (1, 1)
  EXPECT_NEAR(m.vertices.back().x, 1, 1e-12);
  EXPECT_NEAR(m.vertices.back().y, 1, 1e-12);
  EXPECT_NEAR(total_area(m), 2.0, 1e-12);
  EXPECT_TRUE(covered(m, {1.8, 1.0}));
  EXPECT_TRUE(covered(m, {0.2, 1.0}));
  EXPECT_FALSE(covered(m, {1.0, 0.2}));
}

TEST(PolygonTriangulation, AConvexPolygonKeepsItsFanAndAStarIsNotConvex) {
  const std::vector<Vec3> hex = {{2, 0, 0}, {1, 1.7, 0}, {-1, 1.7, 0}, {-2, 0, 0}, {-1, -1.7, 0}, {1, -1.7, 0}};
  EXPECT_TRUE(polygon_is_convex(hex, {0, 1, 2, 3, 4, 5}));
  const Mesh m = mesh_of_polygons("hex.obj", hex, {{0, 1, 2, 3, 4, 5}});
  ASSERT_EQ(m.triangles.size(), 4u);
  for (const auto& t : m.triangles) EXPECT_EQ(t[0], m.triangles[0][0]);  // one apex
  // A pentagram turns one way at every corner, but twice round.
  std::vector<Vec3> star;
  for (int k = 0; k < 5; ++k) star.push_back({std::cos(k * 4 * M_PI / 5), std::sin(k * 4 * M_PI / 5), 0});
  EXPECT_FALSE(polygon_is_convex(star, {0, 1, 2, 3, 4}));
  // Collinear corners (a T-junction's vertex) leave a polygon convex.
  EXPECT_TRUE(polygon_is_convex({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}}, {0, 1, 2, 3, 4}));
}

TEST(PolygonTriangulation, AFaceStandingInAnyPlaneFacesItsOwnWay) {
  // The L of the first test stood up on the plane x = 0, seen from −x (clockwise in y, z).
  const Mesh m = mesh_of_polygons("wall.obj", {{0, 0, 0}, {0, 0, 2}, {0, 1, 2}, {0, 1, 1}, {0, 2, 1}, {0, 2, 0}},
                                  {{0, 1, 2, 3, 4, 5}});
  EXPECT_NEAR(total_area(m), 3.0, 1e-12);
  for (const auto& tr : m.triangles) {
    const Vec3 a = m.vertices[size_t(tr[0])], b = m.vertices[size_t(tr[1])], c = m.vertices[size_t(tr[2])];
    EXPECT_LT(cross(b - a, c - a).x, 0);
  }
}

/// Real files: Sweet Home 3D's own door and door-frame models (in every home with a door),
/// whose faces run round the doorway. Their triangles cover exactly the faces' areas as the
/// file's polygons give them by Newell's formula (simple polygons), where a fan from each
/// face's first corner covers 2.3 and 5.5 times as much: the doorway filled.
TEST(PolygonTriangulation, SweetHomesDoorFramesLeaveTheDoorwayOpen) {
  const std::filesystem::path resources = std::filesystem::path(AVENUES_SH3D_EXAMPLES) / "com/eteks/sweethome3d/io/resources";
  for (const char* name : {"doorFrame.obj", "door.obj"}) {
    SCOPED_TRACE(name);
    const std::string path = (resources / name).string();
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path << " (.ci/install-deps)";
    std::ifstream in(path);
    std::vector<Vec3> v;
    double faces = 0, fans = 0;
    for (std::string line; std::getline(in, line);) {
      std::istringstream s(line);
      std::string tag;
      s >> tag;
      if (tag == "v") {
        Vec3 p;
        s >> p.x >> p.y >> p.z;
        v.push_back(p);
      } else if (tag == "f") {
        std::vector<int> f;
        for (std::string c; s >> c;) f.push_back(std::stoi(c.substr(0, c.find('/'))) - 1);
        Vec3 n{0, 0, 0};
        for (size_t i = 0; i < f.size(); ++i) n = n + cross(v[size_t(f[i])], v[size_t(f[(i + 1) % f.size()])]);
        faces += 0.5 * length(n);
        for (size_t k = 1; k + 1 < f.size(); ++k)
          fans += 0.5 * length(cross(v[size_t(f[k])] - v[size_t(f[0])], v[size_t(f[k + 1])] - v[size_t(f[0])]));
      }
    }
    EXPECT_GT(fans, 2 * faces);  // what the fans did
    const Mesh m = load_mesh(path);  // no turn, no scale: areas as in the file
    // OpenMesh keeps single precision: 10⁻⁶ of the total.
    EXPECT_NEAR(total_area(m), faces, 1e-6 * faces);
  }
}
