// Avenues — meshes to draw and what they are made of: a plan's objects placed in their
// cells, or meshes alone (the papers' scenes).
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/mesh.h"

namespace avenues {

/// What a mesh is made of: one material, or one per input polygon (Bouknight's cottage
/// gives the undersides of its roof "a smaller index of reflectivity").
struct MeshPaint {
  std::vector<Material> materials;    ///< empty: the default material (plans/plan.h)
  std::vector<int> polygon_material;  ///< per input polygon (Mesh::polygon_of): index into materials; empty: the first
  const Material& of_polygon(int polygon) const;
};

/// A mesh's own materials as its paint, polygon by polygon (Mesh::material_of through
/// Mesh::polygon_of; a polygon of none takes the default material); an empty paint (the
/// default material) when the mesh has no materials of its own.
MeshPaint paint_of_mesh(const Mesh& mesh);

/// A plan object loaded, placed, and assigned to the cell holding its centroid.
struct PlacedObject {
  std::string name;
  Mesh mesh;               ///< world coordinates [m]
  CellId cell = kNoCell;   ///< kNoCell: its centroid lies in a solid or outside the far box; never drawn
  MeshPaint paint;
  Box3 bounds;             ///< of the placed mesh's vertices
};

/// Loads every object of the complex (plans/mesh.h, each file read once), places it on
/// its storey, and finds the cell holding the centroid of its vertices. Its paint is its
/// own material (Object::material) where it has one, else its mesh's (paint_of_mesh). Throws
/// std::runtime_error naming the mesh file when one cannot be read; what reading a mesh let
/// pass (an OBJ's missing MTL library or image, load_object_mesh) goes to `warnings`
/// when given, once per mesh file.
std::vector<PlacedObject> place_objects(const CellComplex& complex, std::vector<std::string>* warnings = nullptr);

}  // namespace avenues
