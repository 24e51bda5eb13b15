// Avenues — models read with Assimp: every mesh format it knows (glTF 2, COLLADA, FBX, 3DS,
// IFC, ...), as Avenues' own plain structs.
//
// Only assimp_reader.cpp includes Assimp. What leaves it is a list of the file's nodes,
// each with its own triangles already placed in the world (node transforms applied) and
// turned into Avenues' axes: z up, metres. The file's own up axis and unit are used where
// the format has them: Assimp turns glTF, COLLADA (its <up_axis> and <unit>), 3DS and IFC
// to Y-up and applies COLLADA's and IFC's units itself; FBX says its axes and unit in the
// scene's metadata (UpAxis, UpAxisSign, UnitScaleFactor in centimetres). For formats that
// say nothing (OBJ, PLY, STL, OFF, ...), MeshAxes gives them (default z up, metres).
//
// Assimp's logging stays silent: Avenues never creates Assimp's DefaultLogger, so its
// NullLogger drops every message; what fails is reported from Importer::GetErrorString.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plans/mesh.h"
#include "plans/plan.h"

namespace avenues {

/// One node of the file's hierarchy with the triangles of its own meshes.
struct ImportedNode {
  std::string name;                           ///< as Assimp names it ("IfcDoor_M_Single..._1hOSvn6df7F8_7GcBWlRGQ")
  int parent = -1;                            ///< index into ImportedScene::nodes; -1 for the root
  std::vector<Vec3> vertices;                 ///< [m] world, z up
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  std::array<double, 3> colour{0.8, 0.8, 0.8};  ///< linear RGB [0,1]: its first mesh's diffuse colour
  bool coloured = false;                      ///< the file gave that colour
  std::vector<int> triangle_material;         ///< per triangle: index into ImportedScene::materials, -1 none
};

/// One of the file's materials, as far as Avenues uses it.
struct ImportedMaterial {
  std::string name;
  std::array<double, 3> colour{0.8, 0.8, 0.8};  ///< linear RGB [0,1]: its diffuse (glTF: base) colour
  bool coloured = false;                        ///< the file gave that colour
};

struct ImportedScene {
  std::string path;
  std::string format;                 ///< Assimp's importer ("glTF2 Importer", "Collada Importer", ...)
  std::vector<ImportedNode> nodes;    ///< parents before their children; nodes[0] is the root
  std::vector<ImportedMaterial> materials;  ///< Assimp's, in its order
  double import_seconds = 0;          ///< [s] Assimp's own ReadFile (with post-processing)
  /// The file's own first view, where its format keeps one and its reader takes it (a VRML
  /// Viewpoint, an Irrlicht camera), in Avenues' space; Mesh::viewpoint.
  std::optional<Viewpoint> viewpoint;
  std::vector<std::string> warnings;  ///< what was ignored (an option the file overrides, ...)
};

struct ImportOptions {
  MeshAxes axes;            ///< for formats that declare no up axis or unit
  bool ifc_spaces = false;  ///< IFC: keep IfcSpace volumes (Assimp skips them by default)
  /// When not empty: the file's bytes as they are to be read, from memory (the IFC reader's
  /// rewritten STEP text); the path still names the file, and its extension the format.
  std::string_view contents;
};

/// Whether Assimp has an importer for this extension (".gltf", with the dot).
bool assimp_reads_extension(const std::string& ext);

/// Whether one of the model readers knows the file by its content (a magic number, or the
/// keywords its format begins with), whatever its name: for a model whose name has no
/// extension or one that says nothing (3DS's "MM" chunk, "AC3D", "*3DSMAX_ASCIIEXPORT", "xof ").
/// Assimp's importers, and Avenues' own readers of Irrlicht's XML and VRML97, which
/// import_scene reads instead. Returns the reader as a message names it ("Assimp's Discreet
/// 3DS Importer", "Avenues' VRML97 reader"), or "" when none knows it.
std::string assimp_importer_by_content(const std::string& path);

/// Reads a model file. Throws std::runtime_error naming the file and Assimp's reason when
/// Assimp cannot read it (an unknown IFC entity, a broken glTF buffer, an empty file).
ImportedScene import_scene(const std::string& path, const ImportOptions& options = {});

/// Every triangle of the scene as one Mesh (mesh_of_polygons), each with its material's
/// colour where the file gives one (Mesh::materials). Throws std::runtime_error naming
/// the file when it holds no triangles.
Mesh mesh_of_scene(const ImportedScene& scene);

/// A file read with Assimp as one mesh (import_scene, then mesh_of_scene); warnings, such
/// as an ignored option, are appended to `warnings` when given.
Mesh load_assimp_mesh(const std::string& path, const MeshAxes& axes, std::vector<std::string>* warnings = nullptr);

}  // namespace avenues
