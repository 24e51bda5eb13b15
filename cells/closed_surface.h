// Avenues — a closed surface: what lies inside it, and where a segment first enters it.
//
// A closed, outward-oriented triangle surface (a solid as modelling tools write one) bounds
// a region nobody stands in. The soup BSP keeps most such surfaces as faces of cells, and
// the cells inside them go (cells/solid_insides.h). A curved one is not cut into space:
// free space around a closed curved object needs at least as many convex cells as the
// object has facets (a point on one facet lies inside every other facet's plane, so a
// convex cell outside the object meets at most one facet in more than an edge), and a
// duck of 4,212 facets costs its walkthrough thousands of cells in every view of it. Such
// a surface is drawn as detail instead (cells/soup_detail.h), and kept here, whole, so that
// the walker cannot pass through it and no eye is placed inside it: the complex's
// `detail_solids` (cells/cell_complex.h).
//
// Both questions are answered through a hierarchy of boxes over the triangles (a few
// triangles a leaf), so a walker's move near the object costs a few dozen triangle tests.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace avenues {

using Triangle3 = std::array<Vec3, 3>;

/// The generalized winding number of the triangles about p: the sum of their solid angles
/// seen from p (Van Oosterom and Strackee's formula) over 4π. About 1 inside a closed
/// surface whose triangles turn counter-clockwise seen from outside, about −1 inside one
/// turned the other way, about 0 outside both or inside one of each.
double winding_number(const std::vector<Triangle3>& triangles, Vec3 p);

/// Möller and Trumbore's line–triangle intersection: the line's parameter t and the
/// barycentric coordinates (u, v) of the point where a + t·d meets the triangle's plane;
/// false when the line runs parallel to it.
bool line_plane_hit(const Triangle3& tri, Vec3 a, Vec3 d, double* t, double* u, double* v);

/// Where a segment first enters a closed surface.
struct SurfaceEntry {
  double t = 1;  ///< the fraction of the segment before it, in [0, 1]
  Vec3 normal;   ///< the entered triangle's unit normal, out of the surface (facing the segment's start)
  bool hit = false;
};

class ClosedSurface {
 public:
  ClosedSurface() = default;
  /// `triangles` counter-clockwise seen from outside, closed (every edge used once each way).
  ClosedSurface(std::string name, std::vector<Triangle3> triangles);

  const std::string& name() const { return name_; }
  const std::vector<Triangle3>& triangles() const { return triangles_; }
  const Box3& box() const { return box_; }

  /// Whether p lies inside (winding number over ½). Points on the surface: either.
  bool holds(Vec3 p) const;
  /// The first point at which the segment a→b crosses a triangle from outside to inside
  /// (a segment leaving the surface, or running along it, is not stopped).
  SurfaceEntry entry(Vec3 a, Vec3 b) const;

 private:
  struct Node {
    Box3 box;
    int32_t first = 0;  ///< a leaf's first triangle; an inner node's first child (the second follows)
    int32_t count = 0;  ///< a leaf's triangles; 0 for an inner node
  };
  /// Makes nodes_[node] hold triangles order[first, first + count), splitting it in two
  /// at the median of their centres along the widest axis down to a few a leaf.
  void build(int32_t node, int32_t first, int32_t count, std::vector<int32_t>& order, const std::vector<Vec3>& centres);
  /// Calls f(triangle) for each triangle in a leaf whose box the line a + t·d meets for t
  /// in [0, *t_max] (read again at each node: f may lower it), until f returns false;
  /// false when it did.
  template <class F>
  bool for_each_near(Vec3 a, Vec3 d, const double* t_max, F&& f) const;
  /// Adds to `sum` the signed crossings (+1 leaving, −1 entering) of the ray from p along
  /// d; false where the ray passes too near an edge or a corner to tell.
  bool crossings(Vec3 p, Vec3 d, int* sum) const;

  std::string name_;
  std::vector<Triangle3> triangles_;
  std::vector<Node> nodes_;
  Box3 box_;
};

}  // namespace avenues
