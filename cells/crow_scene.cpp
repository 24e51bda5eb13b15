// Avenues — a scene of one of Crow's objects (see crow.h): its polygons as a solid in free
// space (mesh_scene.h), or its line list standing in free space. Kept apart from the reader
// (crow.cpp), which the fuzz target builds without CGAL.
#include <exception>
#include <filesystem>
#include <stdexcept>

#include "cells/crow.h"

namespace avenues {

CellComplex read_crow_scene(const std::string& path, const MeshSceneParams& params) {
  const CrowObject o = read_crow(path);
  CellComplex c;
  try {
    if (o.table == CrowObject::Table::Polygons) {
      c = build_mesh_scene({crow_mesh(o)}, params);
    } else {
      MeshSceneParams p = params;
      for (Vec3 q : o.points) p.include.add(q);
      c = build_mesh_scene({}, p);
      add_real_lines(c, crow_lines(o));
    }
  } catch (const PlanError&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  c.plan_name = std::filesystem::path(path).stem().string();
  return c;
}

}  // namespace avenues
