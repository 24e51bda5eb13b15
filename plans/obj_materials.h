// Avenues — a Wavefront OBJ model's own materials: which faces use which (usemtl), where
// they are defined (mtllib), and what an MTL library says of each (Kd, map_Kd).
//
// OpenMesh reads an OBJ's geometry but, reading from memory, cannot open the MTL files it
// names, and keeps no material names. So the OBJ text is read here a second time for its
// `usemtl` statements alone, each face taking the name in force where it stands
// ("default" before any, as Sweet Home 3D's OBJLoader names it), and the names are put on
// the mesh OpenMesh made (polygon i of mesh_of_polygons is OpenMesh's i-th face) only when
// both count the same faces: OpenMesh refuses a face that names one vertex twice (this
// reader predicts that), and any other face it refused would shift every name after it.
//
// MTL (Wavefront's Material Template Library, as Sweet Home reads it): `newmtl name`
// starts a material (a name may hold spaces), `Kd r g b` is its diffuse colour, `map_Kd
// [options] file` its diffuse image; other statements are skipped. Kd is kept as written:
// Sweet Home turns it into a colour as it does a colour the user picks (Kd · 255), so it
// is in the same (sRGB) encoding, not linear light; the caller decodes it.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plans/mesh.h"

namespace avenues {

/// The name a face has before any `usemtl` (Sweet Home's OBJLoader: "default").
inline constexpr std::string_view kObjDefaultMaterial = "default";

/// An OBJ file's use of materials.
struct ObjMaterialUse {
  /// Each `mtllib` statement's argument, in order (file names relative to the OBJ's folder;
  /// one statement may name several, separated by spaces, or one name holding spaces).
  std::vector<std::string> libraries;
  /// Per face ('f' statement) that OpenMesh keeps, in order: the material in force there.
  std::vector<std::string> face_material;
  bool uses_materials = false;  ///< the file has at least one `usemtl`
};

/// Reads the `mtllib` and `usemtl` statements and the faces of an OBJ text (comments from
/// '#' on ignored). Never throws: what is not a face or a material statement is skipped
/// (check_obj in mesh.cpp has already checked the geometry).
ObjMaterialUse obj_material_use(std::string_view obj);

/// Gives a mesh read from an OBJ (polygon i its i-th face OpenMesh kept, `faces_read` of
/// them) one material per name `use` names, in order of first use, each with Material's
/// default colour and reflectance (the caller colours them by name), and each triangle the
/// material of its polygon (Mesh::material_of). Nothing when the file has no `usemtl`.
/// Returns "" when done; when the faces counted differ and more than one name is used, the
/// reason, and every triangle gets the name most faces use (one material).
std::string name_obj_materials(Mesh& m, const ObjMaterialUse& use, size_t faces_read);

/// One material of an MTL library.
struct MtlMaterial {
  std::string name;                               ///< newmtl's argument
  std::optional<std::array<double, 3>> diffuse;   ///< Kd as written, each clamped to [0, 1] (sRGB-encoded, see above)
  std::string diffuse_map;                        ///< map_Kd's arguments (options, then the file name); "" when none
  int line = 0;                                   ///< 1-based, of its newmtl
};

/// An MTL file read: its materials (a name defined twice: the later, as Sweet Home's map
/// keeps it) and what could not be read, each "line N: ...".
struct MtlLibrary {
  std::vector<MtlMaterial> materials;
  std::vector<std::string> problems;
  const MtlMaterial* find(std::string_view name) const;
};

/// Reads an MTL text. Never throws: a statement it cannot read (a Kd that is not one or
/// three finite numbers, a colour before any newmtl) is left out with a problem noted.
MtlLibrary read_mtl(std::string_view text);

/// The files a `mtllib` argument may name, in the order Sweet Home tries them: each word,
/// then (several words, none found) the whole argument, a name holding spaces.
std::vector<std::string> mtllib_candidates(const std::string& argument);
/// The image a map_Kd's arguments may name, in the order Sweet Home tries them: the last
/// word (options come before it), then (several words) the whole argument.
std::vector<std::string> map_kd_candidates(const std::string& argument);

}  // namespace avenues
