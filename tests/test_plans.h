// Small helpers the tests share: hand-made plan elements and the bundled plans' paths.
#pragma once

#include <filesystem>
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

}  // namespace avenues::testing
