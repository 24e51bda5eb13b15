// Avenues tests — meshes made in a test, and a reference ray cast against them.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "plans/mesh.h"

namespace avenues::testing {

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
