// Avenues tests — meshes made in a test, and a reference ray cast against them.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
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

/// k × k open boxes (a floor and four walls each, 1 m, open at the top) 2 m apart, as the
/// soup benchmark makes them (bench/soup_bench.cpp).
inline Mesh open_boxes(int k) {
  std::vector<Vec3> v;
  std::vector<std::vector<int>> polygons;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const double x = 2.0 * i, y = 2.0 * j;
      const int b = int(v.size());
      v.insert(v.end(), {{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0},
                         {x, y, 1}, {x + 1, y, 1}, {x + 1, y + 1, 1}, {x, y + 1, 1}});
      for (const auto& q : {std::array{0, 3, 2, 1}, std::array{0, 1, 5, 4}, std::array{1, 2, 6, 5},
                            std::array{2, 3, 7, 6}, std::array{3, 0, 4, 7}})
        polygons.push_back({b + q[0], b + q[1], b + q[2], b + q[3]});
    }
  return mesh_from(std::move(v), std::move(polygons));
}

/// A closed sphere of radius r about c: an icosahedron whose faces are split into four
/// `levels` times, its corners pushed out on to the sphere (triangles only, no two coplanar).
inline Mesh icosphere(Vec3 c, double r, int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                      {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (Vec3& p : v) p = (1 / length(p)) * p;
  std::vector<std::array<int, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                                    {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, added] = middle.try_emplace(key, int(v.size()));
      if (added) {
        const Vec3 m = v[size_t(a)] + v[size_t(b)];
        v.push_back((1 / length(m)) * m);
      }
      return it->second;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.insert(next.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    f = std::move(next);
  }
  for (Vec3& p : v) p = c + r * p;
  std::vector<std::vector<int>> polygons;
  for (const auto& t : f) polygons.push_back({t[0], t[1], t[2]});
  return mesh_from(v, polygons);
}

/// A closed box from lo to hi (box_mesh, moved there).
inline Mesh box_between(Vec3 lo, Vec3 hi) {
  Mesh m = box_mesh(hi - lo);
  const Vec3 base{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), lo.z};
  for (Vec3& v : m.vertices) v = v + base;
  return m;
}

/// The mesh in one material of this name and colour.
inline Mesh painted(Mesh m, const std::string& name, std::array<double, 3> colour) {
  Material material;
  material.name = name;
  material.colour = colour;
  m.materials = {material};
  m.material_of.assign(m.triangles.size(), 0);
  return m;
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
