// Avenues — a Mesh written as a Wavefront OBJ file and its materials as an MTL library,
// such that load_mesh (plans/mesh.h) reads back the same mesh: its vertices (to OpenMesh's
// single precision), its polygons, and each polygon's material with its colour.
//
// A polygon is written as the corners of the fan mesh_of_polygons cut it into (from the
// fan's apex), so that reading it back cuts the same triangles; triangles of a polygon
// that are no such fan are written one face each. Each material becomes an MTL material of
// a name of its own (`newmtl` and `usemtl` take the rest of the line, so a name is made
// one line with no '#'), its Kd the sRGB encoding of its linear colour: obj_materials.h
// reads Kd as sRGB-encoded, so the colour comes back to within rounding.
#pragma once

#include <string>
#include <vector>

#include "plans/mesh.h"

namespace avenues {

/// The mesh as OBJ text, naming `mtl_file` (beside it) in its mtllib line when the mesh
/// has materials; z-up metres, as the mesh holds them.
std::string obj_of_mesh(const Mesh& mesh, const std::string& mtl_file);

/// The mesh's materials as MTL text (Kd each); "" when it has none.
std::string mtl_of_mesh(const Mesh& mesh);

}  // namespace avenues
