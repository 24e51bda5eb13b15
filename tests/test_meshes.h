// Avenues tests — meshes made in a test, and a reference ray cast against them.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/mesh.h"

namespace avenues::testing {

/// Volume [m³] of a convex cell from its faces alone (prism or not): a pyramid from one of
/// its vertices to each face, each face's area a fan about its own first vertex (no large
/// products cancelling far from the origin). Independent of the complex's own total_volume.
inline double cell_volume(const Cell& cell) {
  const Vec3 r = cell.faces.front().poly.front();
  double v = 0;
  for (const Face& f : cell.faces) {
    Vec3 s{0, 0, 0};
    for (size_t i = 1; i + 1 < f.poly.size(); ++i) s = s + cross(f.poly[i] - f.poly[0], f.poly[i + 1] - f.poly[0]);
    v += length(s) / 2 * dot(f.plane.n, f.poly.front() - r) / 3;
  }
  return v;
}

/// The free volume [m³] of a complex: the sum of its cells' volumes.
inline double free_volume(const CellComplex& c) {
  double v = 0;
  for (const Cell& cell : c.cells) v += cell_volume(cell);
  return v;
}

inline double box_volume(const Box3& b) { return (b.hi.x - b.lo.x) * (b.hi.y - b.lo.y) * (b.hi.z - b.lo.z); }

/// A mesh of these convex polygons (counter-clockwise seen from outside), made as the
/// readers make one (mesh_of_polygons: T-junctions joined, fans, corner normals).
inline Mesh mesh_from(std::vector<Vec3> vertices, std::vector<std::vector<int>> polygons) {
  return mesh_of_polygons("test mesh", std::move(vertices), std::move(polygons));
}

/// Möller–Trumbore: the distance along dir to the nearest triangle of the meshes (or inf).
inline double nearest_triangle(const std::vector<Mesh>& meshes, Vec3 o, Vec3 dir) {
  double best = std::numeric_limits<double>::infinity();
  for (const Mesh& m : meshes)
    for (const auto& t : m.triangles) {
      const Vec3 a = m.vertices[size_t(t[0])], b = m.vertices[size_t(t[1])], c = m.vertices[size_t(t[2])];
      const Vec3 e1 = b - a, e2 = c - a, p = cross(dir, e2);
      const double det = dot(e1, p);
      if (std::fabs(det) < 1e-300) continue;
      const Vec3 s = o - a;
      const double u = dot(s, p) / det;
      if (u < 0 || u > 1) continue;
      const Vec3 q = cross(s, e1);
      const double v = dot(dir, q) / det;
      if (v < 0 || u + v > 1) continue;
      const double tt = dot(e2, q) / det;
      if (tt > 0 && tt < best) best = tt;
    }
  return best;
}

}  // namespace avenues::testing
