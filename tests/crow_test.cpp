// Tests of cells/crow.h: Crow's tables 1a and 1b (his own ten-point object, bundled in
// plans/scenes/), their errors, and the scenes made of them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <tuple>

#include "cells/build_cells.h"
#include "cells/crow.h"

using namespace avenues;

namespace {

std::string scene_path(const std::string& name) {
  return (std::filesystem::path(AVENUES_SOURCE_DIR) / "plans" / "scenes" / name).string();
}

using Key = std::tuple<double, double, double>;
Key key(Vec3 p) { return {p.x, p.y, p.z}; }

/// The lines as a set of unordered point pairs.
std::set<std::pair<Key, Key>> segments(const std::vector<RealLine>& lines) {
  std::set<std::pair<Key, Key>> s;
  for (const RealLine& l : lines) s.insert(std::minmax(key(l.a), key(l.b)));
  return s;
}

/// The line of the PlanError parse_crow throws for `text`, or -1 when it throws none.
int error_line(const std::string& text, std::string* message = nullptr) {
  try {
    parse_crow(text, "bad.crow");
  } catch (const PlanError& e) {
    if (message) *message = e.what();
    return e.where().line;
  }
  return -1;
}

double mesh_volume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += dot(m.vertices[size_t(t[0])], cross(m.vertices[size_t(t[1])], m.vertices[size_t(t[2])])) / 6;
  return v;
}

}  // namespace

TEST(Crow, BothTablesOfCrowsObjectReadAsTheSameTenPointsAndFifteenEdges) {
  const CrowObject lines = read_crow(scene_path("crow-table-1a.crow"));
  const CrowObject polys = read_crow(scene_path("crow-table-1b.crow"));
  EXPECT_EQ(lines.table, CrowObject::Table::Lines);
  EXPECT_EQ(polys.table, CrowObject::Table::Polygons);
  EXPECT_EQ(lines.points.size(), 10u);  // twenty commands, ten points
  EXPECT_EQ(polys.points.size(), 10u);
  EXPECT_EQ(lines.polylines.size(), 5u);  // five moves
  EXPECT_EQ(polys.polygons.size(), 7u);
  std::set<Key> a, b;
  for (Vec3 p : lines.points) a.insert(key(p));
  for (Vec3 p : polys.points) b.insert(key(p));
  EXPECT_EQ(a, b);
  // Point 4 of table 1b, "-.00 -1.0 1.0".
  EXPECT_EQ(polys.points[3].x, 0.0);
  EXPECT_EQ(polys.points[3].z, 1.0);
  // Both tables describe one object: table 1a's draws are table 1b's edges (V - E + F = 2).
  const std::vector<RealLine> la = crow_lines(lines), lb = crow_lines(polys);
  EXPECT_EQ(la.size(), 15u);
  EXPECT_EQ(lb.size(), 15u);
  EXPECT_EQ(segments(la), segments(lb));
}

TEST(Crow, ListingOnesCountOfPointsMayComeFirst) {
  const CrowObject o = parse_crow("3\nm 0 0 0\nd 1 0 0\nd 1 1 0\n", "counted.crow");
  EXPECT_EQ(o.table, CrowObject::Table::Lines);
  EXPECT_EQ(o.points.size(), 3u);
  ASSERT_EQ(o.polylines.size(), 1u);
  EXPECT_EQ(o.polylines[0].size(), 3u);
}

TEST(Crow, MalformedInputIsAnErrorNamingFileAndLine) {
  std::string msg;
  EXPECT_EQ(error_line("# wire\nm 1 2\n", &msg), 2);
  EXPECT_NE(msg.find("bad.crow:2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("point 1"), std::string::npos) << msg;
  EXPECT_EQ(error_line("m 0 0 0\nd 1 x 0\n", &msg), 2);
  EXPECT_NE(msg.find("'x' is not a number"), std::string::npos) << msg;
  EXPECT_EQ(error_line("d 0 0 0\n", &msg), 1);
  EXPECT_NE(msg.find("before any move"), std::string::npos) << msg;
  EXPECT_EQ(error_line("m 0 0 0\nq 1 0 0\n"), 2);
  EXPECT_EQ(error_line("3\nm 0 0 0\nd 1 0 0\n", &msg), 1);  // a count that does not match
  EXPECT_NE(msg.find("says 3 points but 2 follow"), std::string::npos) << msg;
  const std::string points = "1 0 0 0\n2 1 0 0\n3 0 1 0\n";
  EXPECT_EQ(error_line("3 1\n1 0 0 0\n3 1 0 0\n2 0 1 0\n3 1 2 3\n", &msg), 3);  // numbered out of order
  EXPECT_NE(msg.find("point 2"), std::string::npos) << msg;
  EXPECT_EQ(error_line("3 1\n" + points + "3 1 2 9\n", &msg), 5);
  EXPECT_NE(msg.find("polygon 1"), std::string::npos) << msg;
  EXPECT_EQ(error_line("3 1\n" + points + "4 1 2 3\n", &msg), 5);
  EXPECT_NE(msg.find("says 4 vertices but lists 3"), std::string::npos) << msg;
  EXPECT_EQ(error_line("3 1\n" + points + "3 1 2 2\n"), 5);  // a point twice
  EXPECT_EQ(error_line("3 2\n" + points + "3 1 2 3\n", &msg), 5);  // one polygon short
  EXPECT_NE(msg.find("ends after 1 of 2 polygons"), std::string::npos) << msg;
  EXPECT_EQ(error_line("3 1\n" + points + "3 1 2 3\n3 3 2 1\n"), 6);  // one too many
  EXPECT_EQ(error_line("3 1 (NumPts NumPolys\n"), 1);
  EXPECT_EQ(error_line("1.5 2 3\n"), 1);
  EXPECT_EQ(error_line("\n# nothing\n", &msg), 0);
  EXPECT_NE(msg.find("bad.crow"), std::string::npos) << msg;
  EXPECT_THROW(read_crow("/nonexistent/object.crow"), std::runtime_error);
}

TEST(Crow, APolygonObjectBecomesAClosedMeshTurnedCounterClockwise) {
  const Mesh m = crow_mesh(read_crow(scene_path("crow-table-1b.crow")));
  EXPECT_TRUE(m.closed);
  EXPECT_EQ(m.boundary_edges, 0);
  EXPECT_EQ(m.vertices.size(), 10u);
  EXPECT_EQ(m.triangles.size(), 16u);  // (5-2)·3 + (4-2)·3 + (3-2)
  EXPECT_EQ(m.polygon_of.back(), 6);
  // A 2 m cube less its cut-off corner (a tetrahedron with three unit legs); positive
  // because the triangles now face out.
  EXPECT_NEAR(mesh_volume(m), 8 - 1.0 / 6, 1e-12);
  EXPECT_THROW(crow_mesh(read_crow(scene_path("crow-table-1a.crow"))), PlanError);
}

TEST(Crow, AConcavePolygonIsCutIntoTrianglesInsideIt) {
  // An L-shaped prism, its two L faces concave, listed clockwise from outside as Crow does.
  const std::string text =
      "12 8\n"
      "1 0 0 0\n2 2 0 0\n3 2 1 0\n4 1 1 0\n5 1 2 0\n6 0 2 0\n"
      "7 0 0 1\n8 2 0 1\n9 2 1 1\n10 1 1 1\n11 1 2 1\n12 0 2 1\n"
      "6 1 2 3 4 5 6\n"       // bottom: counter-clockwise from above is clockwise from below
      "6 12 11 10 9 8 7\n"    // top
      "4 1 7 8 2\n4 2 8 9 3\n4 3 9 10 4\n4 4 10 11 5\n4 5 11 12 6\n4 6 12 7 1\n";
  const Mesh m = crow_mesh(parse_crow(text, "ell.crow"));
  EXPECT_TRUE(m.closed);
  EXPECT_NEAR(mesh_volume(m), 3, 1e-12);
  double area = 0;  // the two L faces' triangles cover 3 m² each, none outside the L
  for (size_t t = 0; t < m.triangles.size(); ++t)
    if (m.polygon_of[t] < 2) {
      const auto& tr = m.triangles[t];
      area += length(cross(m.vertices[size_t(tr[1])] - m.vertices[size_t(tr[0])],
                           m.vertices[size_t(tr[2])] - m.vertices[size_t(tr[0])])) / 2;
    }
  EXPECT_NEAR(area, 6, 1e-12);
}

TEST(Crow, APolygonObjectIsTheSolidOfAMeshScene) {
  MeshSceneParams nef;  // closed solids: the Nef path (the soup BSP keeps the inside as free space)
  nef.method = MeshSceneMethod::Nef;
  const CellComplex c = read_crow_scene(scene_path("crow-table-1b.crow"), nef);
  EXPECT_EQ(cells_are_valid(c), "");
  EXPECT_TRUE(c.warnings.empty());
  EXPECT_EQ(c.plan_name, "crow-table-1b");
  // Crow's 15 edges are its real lines.
  EXPECT_EQ(segments(c.lines), segments(crow_lines(read_crow(scene_path("crow-table-1b.crow")))));
  double v = 0;
  for (const Cell& cell : c.cells) {
    const Vec3 r = cell.faces.front().poly.front();
    for (const Face& f : cell.faces) {
      Vec3 s{0, 0, 0};
      for (size_t i = 0; i < f.poly.size(); ++i) s = s + cross(f.poly[i], f.poly[(i + 1) % f.poly.size()]);
      v += length(s) / 2 * dot(f.plane.n, f.poly.front() - r) / 3;
    }
  }
  const Box3& b = c.far_box;
  EXPECT_NEAR(v, (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y) * (b.hi.z - b.lo.z) - (8 - 1.0 / 6), 1e-9);
  EXPECT_EQ(c.locate({0.5, 0.5, 0.5}).what, Location::What::Solid);
}

TEST(Crow, ALineListBecomesRealLinesInTheCellsOfAFreeBox) {
  const CellComplex c = read_crow_scene(scene_path("crow-table-1a.crow"));
  EXPECT_EQ(cells_are_valid(c), "");
  ASSERT_FALSE(c.cells.empty());
  // An empty far box: the lines' bounds grown by the margin, and nothing solid in it.
  EXPECT_DOUBLE_EQ(c.far_box.lo.x, -3);
  EXPECT_DOUBLE_EQ(c.far_box.hi.z, 3);
  EXPECT_EQ(c.locate({0, 0, 0}).what, Location::What::Cell);
  ASSERT_EQ(c.lines.size(), 15u);
  // Every line is given, whole, to the cells it passes through.
  std::vector<double> covered(c.lines.size(), 0);
  for (const Cell& cell : c.cells)
    for (const CellLine& l : cell.lines) {
      covered[size_t(l.line)] += l.t1 - l.t0;
      const RealLine& r = c.lines[size_t(l.line)];
      EXPECT_TRUE(cell.contains(r.a + 0.5 * (l.t0 + l.t1) * (r.b - r.a), 1e-9));
    }
  for (size_t i = 0; i < covered.size(); ++i) EXPECT_NEAR(covered[i], 1, 1e-9) << "line " << i;
}
