// Small helpers the tests share: hand-made plan elements and the bundled plans' paths.
#pragma once

#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/plan.h"

namespace avenues::testing {

inline std::string plan_path(const std::string& name) {
  return (std::filesystem::path(AVENUES_SOURCE_DIR) / "plans" / name).string();
}

inline RoomId room_named(const CellComplex& c, const std::string& name) {
  for (size_t r = 0; r < c.rooms.size(); ++r)
    if (c.rooms[r].name == name) return RoomId(r);
  return -1;
}

/// A straight wall along `centre` (no arcs).
inline Wall wall(const std::string& name, std::vector<Vec2> centre, double thickness) {
  Wall w;
  w.name = name;
  w.thickness = thickness;
  w.centre = std::move(centre);
  w.from_arc.assign(w.centre.size() - 1, false);
  return w;
}

/// A random point inside a convex cell: its faces' corners, each weighed by a random
/// weight in [0.05, 1).
inline Vec3 random_point_in(const Cell& cell, std::mt19937& rng) {
  std::uniform_real_distribution<double> w(0.05, 1.0);
  Vec3 p{0, 0, 0};
  double sum = 0;
  for (const Face& f : cell.faces)
    for (Vec3 q : f.poly) {
      const double k = w(rng);
      p = p + k * q, sum += k;
    }
  return (1.0 / sum) * p;
}

/// A random eye inside a random room or outside cell, at a height within the cell.
inline Vec3 random_eye(const CellComplex& c, std::mt19937& rng, CellId& cell) {
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

}  // namespace avenues::testing
