// Tests of closed seams (CellComplex::close_seams, cells/seam.cpp): where opaque pieces meet
// along a line, every corner of one inside an edge of another is a corner of both, so that
// a picture resolved by depth (the hull search's) leaves no sample on a seam uncovered.
// Found on the 64 × 64 grid of open boxes: a grazing view drew 11 black samples along the
// far box's top, where one sky cell's piece ran 5 m beside its neighbours' 1 m pieces.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "plans/plan.h"
#include "render/halftone.h"
#include "tests/test_meshes.h"
#include "visibility/visible_set.h"

namespace avenues {
namespace {

using testing::open_boxes;

/// The oracle, pair by pair: the corners of all pieces lying inside an edge of some piece
/// (farther than `tol` from both its ends, within `tol` of the segment).
size_t corners_inside_edges(const CellComplex& c, double tol) {
  std::vector<Vec3> corners;
  std::vector<std::pair<Vec3, Vec3>> edges;
  for (const Cell& cell : c.cells)
    for (const Face& face : cell.faces)
      for (const OpaquePoly& piece : face.opaque)
        for (size_t i = 0; i < piece.poly.size(); ++i) {
          corners.push_back(piece.poly[i]);
          edges.emplace_back(piece.poly[i], piece.poly[(i + 1) % piece.poly.size()]);
        }
  size_t inside = 0;
  for (const auto& [a, b] : edges) {
    const Vec3 d = b - a;
    const double len = length(d);
    for (const Vec3 v : corners) {
      const double t = dot(v - a, d) / (len * len);
      if (t * len > tol && (1 - t) * len > tol && length(v - (a + t * d)) <= tol) ++inside;
    }
  }
  return inside;
}

TEST(Seam, NoCornerOfAPieceLiesInsideAnotherPiecesEdge) {
  // A soup whose BSP leaves T-junctions on the far box's faces and the boxes' floors.
  CellComplex boxes = build_mesh_scene({open_boxes(4)});
  EXPECT_EQ(corners_inside_edges(boxes, 1e-9), 0u);
  EXPECT_EQ(boxes.close_seams(), 0u) << "closing the seams of a complex already closed changes it";
  // A plan's cells: floors and ceilings cut where the rooms' cells meet.
  CellComplex house = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/two-storey-house.toml"));
  EXPECT_EQ(corners_inside_edges(house, 1e-9), 0u);
  EXPECT_EQ(house.close_seams(), 0u);
}

TEST(Seam, ACornerInsideAnEdgeIsPutIntoItInOrderAndOnlyThere) {
  // Two cells side by side under one opaque ceiling: the left's ceiling runs along x = 1
  // from y = 0 to 3, the right's two pieces end there at y = 1 and y = 2.
  CellComplex c;
  auto cell_with = [](std::vector<std::vector<Vec3>> pieces) {
    Cell cell;
    Face face;
    face.plane = {{0, 0, 1}, -1};
    face.poly = pieces.front();
    for (auto& p : pieces) face.opaque.push_back({std::move(p), -1});
    cell.faces.push_back(std::move(face));
    return cell;
  };
  c.cells.push_back(cell_with({{{0, 0, 1}, {0, 3, 1}, {1, 3, 1}, {1, 0, 1}}}));
  c.cells.push_back(cell_with({{{1, 0, 1}, {1, 1, 1}, {2, 1, 1}, {2, 0, 1}},
                               {{1, 1, 1}, {1, 2, 1}, {2, 2, 1}, {2, 1, 1}},
                               {{1, 2, 1}, {1, 3, 1}, {2, 3, 1}, {2, 2, 1}}}));
  EXPECT_EQ(c.close_seams(), 2u);
  const std::vector<Vec3> left{{0, 0, 1}, {0, 3, 1}, {1, 3, 1}, {1, 2, 1}, {1, 1, 1}, {1, 0, 1}};
  EXPECT_EQ(c.cells[0].faces[0].opaque[0].poly, left);
  // The right's pieces meet corner to corner already, and the left's corners are theirs.
  EXPECT_EQ(c.cells[1].faces[0].opaque[1].poly.size(), 4u);
  EXPECT_EQ(c.close_seams(), 0u);
}

TEST(Seam, TheHullSearchLeavesNoSampleOfAGrazingViewOverAGridUncovered) {
  // Before the seams were closed, these views of the 16 × 16 grid left 3 to 9 samples on
  // the far box's top uncovered (black), where the merged search's grown masks overlap.
  const CellComplex c = build_mesh_scene({open_boxes(16)});
  HalftoneOptions o;
  o.threads = 1;
  for (const double yaw : {30.0, 44.0, 60.0}) {
    const Camera cam = Camera::yaw_pitch({-1, -0.3, 1.6}, yaw, 0, 88.8, 320, 180);
    const CellId eye = c.locate(cam.eye).cell;
    ASSERT_NE(eye, kNoCell);
    for (const bool hull : {true, false}) {
      TraverseParams params;
      params.merge_pieces = true;
      params.hull_pieces = hull;
      RenderStats stats;
      render_view(c, cam, find_visible(c, cam, eye, params), o, &stats);
      EXPECT_EQ(stats.pixels, 320L * 180) << "yaw " << yaw << (hull ? ", hull search" : ", merged search")
                                          << ": samples no polygon covers";
    }
  }
}

}  // namespace
}  // namespace avenues
