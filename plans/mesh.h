// Avenues — triangle meshes read from files (OBJ, OFF, PLY, STL) with OpenMesh.
//
// Objects of a plan (furniture, Jones's "set of unconnected objects") and the papers'
// scenes arrive as meshes. Avenues keeps them as plain arrays: vertices, triangles, and
// the polygon each triangle came from (so a renderer can tell a crease between two
// polygons from the diagonal of a quad, and a drawing never draws the latter).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/geometry.h"
#include "plans/plan.h"

namespace avenues {

struct Mesh {
  std::string path;                        ///< where it was read from
  std::vector<Vec3> vertices;              ///< [m]
  std::vector<std::array<int, 3>> triangles;  ///< counter-clockwise seen from outside
  std::vector<int> polygon_of;             ///< per triangle: the input polygon it came from
  /// Per triangle corner (3 per triangle, in order): the unit normal smooth shading uses
  /// there, averaged over the polygons around the corner's vertex that meet the triangle's
  /// polygon at less than a crease angle (smooth_corner_normals): a box keeps flat faces,
  /// a torus cut into polygons is shaded as the smooth surface it stands for.
  std::vector<Vec3> corner_normals;
  /// Per triangle: its material, an index into `materials` (-1: none); empty when the file
  /// gives none. Formats read through Assimp give each of their materials' diffuse (glTF's
  /// base) colour; a whole scene's cells carry them onto its faces.
  std::vector<MaterialId> material_of;
  std::vector<Material> materials;
  /// Per polygon number (optional; empty for every mesh a reader makes): the point [m]
  /// flat shading lights the polygon from, the centroid of the whole polygon it is a piece
  /// of, so that the pieces of one polygon cut apart (a soup's detail, cells/soup_detail.h)
  /// take one shade. Empty: each polygon is lit from its own centroid.
  std::vector<Vec3> polygon_light;
  /// The file's own first view, where its format keeps one (a VRML Viewpoint, an Irrlicht
  /// camera), in the mesh's space: a scene built from the mesh starts there when the eye
  /// stands in free space (cells/mesh_scene.h).
  std::optional<Viewpoint> viewpoint;
  bool closed = false;                     ///< every edge shared by exactly two polygons
  int boundary_edges = 0;                  ///< edges with one polygon (0 when closed)
};

/// Fills m.corner_normals from its triangles (and polygon_of): at each corner, the
/// area-weighted normals of the polygons around the vertex whose normals lie within
/// `crease_deg` of the corner's own polygon's, summed and made unit.
void smooth_corner_normals(Mesh& m, double crease_deg = 45);

/// How many edges of `rings` (faces as rings of vertex indices; a ring of fewer than three
/// corners has none) one ring alone uses: 0 for a closed surface (Mesh::boundary_edges).
int boundary_edges(const std::vector<std::vector<int>>& rings);
int boundary_edges(const std::vector<std::array<int, 3>>& triangles);

/// A mesh of polygons (vertex indices, counter-clockwise seen from outside), as every
/// reader makes it: a vertex lying on another polygon's edge (a T-junction) is put into that
/// edge too, so that polygons meet vertex to vertex and their shared edges are one line on
/// any raster; each convex polygon is cut into a fan of triangles (from a corner whose sides
/// have no such vertex, where there is one), any other by a constrained triangulation in its
/// plane (plans/polygon_triangulation.h: a notch stays open; crossings of its edges become
/// vertices, appended); corner normals; closedness. Polygons of fewer than
/// three vertices make no triangles (the others keep their numbers, Mesh::polygon_of).
Mesh mesh_of_polygons(std::string path, std::vector<Vec3> vertices, std::vector<std::vector<int>> polygons);

/// Reads a mesh as z-up metres; the format follows the extension: OBJ, OFF, PLY and STL
/// through OpenMesh, turned and scaled as `axes` says (default z up, metres); every other
/// format Assimp reads (glTF 2, COLLADA, FBX, 3DS, ...) through plans/assimp_reader.h, in
/// the up axis and unit the file declares (`axes` where it declares none), and so is a
/// file whose name says no format when an Assimp importer knows its content. Throws
/// std::runtime_error naming the file for a missing, unreadable or empty mesh.
///
/// An OBJ is read as leniently as its own tools read it: a vertex that is no coordinate, or
/// a face naming no vertex, is dropped (with the faces using that vertex) and said in
/// `warnings`, naming its line; only a file left with no face is refused. UTF-16 text (with
/// its byte-order mark) is read as the ASCII it holds. An STL's triangle with a vertex that
/// is no coordinate is dropped likewise, as are an OFF's unusable vertex and face lines and
/// a PLY's vertex that is not a finite number (with its faces); a file whose structure is
/// broken (cut short, counts out of step) is refused.
///
/// An OBJ's `usemtl` groups become its materials (Mesh::materials), coloured by the MTL
/// libraries its `mtllib` lines name, found beside it, and their `map_Kd` images, beside
/// them (plans/obj_materials.h: an image's mean colour, else Kd, sRGB-encoded); Assimp's
/// formats bring their own. What is missing or cannot be read (a library, an image, a
/// material no library defines) leaves the default colour, with a line in `warnings` when
/// given, naming the file.
Mesh load_mesh(const std::string& path, const MeshAxes& axes = {}, std::vector<std::string>* warnings = nullptr);

/// True for an OFF file's first word, [ST][C][N][4][n]OFF ("OFF", "COFF", "STCNOFF", ...).
bool is_off_keyword(std::string_view word);

/// "x", "y", "z" as an up axis; std::nullopt for anything else.
std::optional<char> up_axis_named(const std::string& name);
/// One unit in metres: "m" 1, "cm" 0.01, "mm" 0.001, "in" 0.0254, "ft" 0.3048; std::nullopt
/// for anything else.
std::optional<double> metres_per_unit_named(const std::string& name);
/// Turns a mesh whose up axis is `up` ('x', 'y', 'z', right-handed) to z up and scales it
/// by `metres_per_unit`: y up becomes (x, -z, y), as Blender's Y-up export turned back.
void orient_z_up(Mesh& m, char up, double metres_per_unit);

/// The up axis a mesh read as its file has it, from a format that does not say (OBJ, PLY,
/// STL, OFF), seems drawn with: 'y' where the mesh stands on y = 0 (its lowest y within 2 %
/// of its height of zero, its highest above) while its z straddles zero by more than 5 % of
/// its extent either way, as Blender, SketchUp and 3ds Max export a model from their ground
/// plane with Y up; std::nullopt otherwise (z up, the default, stands).
std::optional<char> guessed_up_axis(const Mesh& m);

/// Reads a mesh held in memory (a model inside an archive): `ext` is its format (".obj"),
/// `name` what messages call it. Throws std::runtime_error naming it when it cannot be read.
/// An OBJ's `usemtl` groups become its materials, by name, in Material's default colour (the
/// MTL files it names are not at hand from memory: the caller colours them by name, see
/// plans/obj_materials.h); when they cannot be put on its faces, a line in `warnings`. The
/// OBJ's `mtllib` arguments, in order, go to `material_libraries` when given (read in the
/// same pass as its `usemtl` groups).
Mesh read_mesh_bytes(const std::string& bytes, const std::string& ext, const std::string& name,
                     std::vector<std::string>* warnings = nullptr,
                     std::vector<std::string>* material_libraries = nullptr);

/// A box `size` large (x by y, z high), its base centred on the origin: furniture known
/// only by its dimensions. Its path is mesh_key_of_box(size).
Mesh box_mesh(Vec3 size);
std::string mesh_key_of_box(Vec3 size);
/// What identifies an object's mesh, for loading each only once: its file, its model's
/// name, or its box.
std::string mesh_key(const Object& object);

/// The mesh of a plan's object (its model, Object::model; a box when it names no file,
/// Object::box); a failure names the object's place in the plan too
/// ("house.toml:62:1 (object 'table'): cannot read mesh ..."); so does each line it adds to
/// `warnings` (load_mesh's).
Mesh load_object_mesh(const Object& object, std::vector<std::string>* warnings = nullptr);

/// The mesh placed as `object` says: scaled, rotated about x, then y, then z (degrees),
/// then moved to object.position + (0, 0, floor_z).
Mesh place(const Mesh& mesh, const Object& object, double floor_z);

}  // namespace avenues
