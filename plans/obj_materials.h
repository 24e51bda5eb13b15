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
// [options] file` its diffuse image; other statements are skipped. Kd is kept as written
// by read_mtl. The format does not say how Kd is encoded, and writers differ (Blender
// writes its linear base colour); Avenues takes it as Sweet Home 3D does, which turns it
// into a colour as it does a colour the user picks (Kd · 255): sRGB-encoded, made linear
// by colour_obj_materials. One rule for every OBJ, so a model is one colour whether it
// comes inside a home, as a plan's object or as a whole scene.
#pragma once

#include <array>
#include <functional>
#include <map>
#include <optional>
#include <set>
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
/// (readable_obj in mesh.cpp has already checked the geometry and dropped what it cannot use).
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

/// The path of `name` (a file an OBJ or MTL file names) beside `file`: in its folder (the
/// text up to its last '/'); `name` itself when it is absolute (begins with '/').
std::string path_beside(const std::string& file, const std::string& name);
/// The paths `name` may mean beside `file`, in order: path_beside as written; then, for a
/// name written on Windows (`textures\wood.png`, `C:\models\chair.mtl`), with its
/// backslashes read as slashes; then its last component alone (the file moved beside the
/// model with it, as exporters' absolute paths usually are). Each once.
std::vector<std::string> paths_beside(const std::string& file, const std::string& name);
/// The file on disk that `name` (an image, a mesh a model names) means beside `model`:
/// the first of paths_beside that is a regular file; else, names written on one system
/// being looked for on another, found in any case folder by folder (a DOS-era 3DS's
/// "IMAGE1.JPG" beside it as IMAGE1.jpg; "../LWo2/x.jpg"), as written when relative, then by
/// its name alone. "" when none is.
std::string file_beside(const std::string& model, const std::string& name);
/// The bytes of a file on disk that a model names (its MTL libraries, their images): a
/// regular file's, std::nullopt for anything else (missing, a directory, a device, larger
/// than 256 MiB, more than a material file or image could sensibly be). MaterialFiles'
/// reader for files on disk.
std::optional<std::string> read_material_file(const std::string& path);

/// The files materials take their colours from, each read once however many models or
/// surfaces name it: MTL libraries and images (their mean colour, plans/image_colour.h).
/// `read` gives a file's bytes by its path (an entry of a Sweet Home archive, a file on
/// disk), std::nullopt when it is not at hand; messages name a file as `prefix` + path.
class MaterialFiles {
 public:
  using Reader = std::function<std::optional<std::string>(const std::string& path)>;
  explicit MaterialFiles(Reader read, std::string prefix = "") : read_(std::move(read)), prefix_(std::move(prefix)) {}

  /// An image's mean colour, or why there is none.
  struct Image {
    bool at_hand = false;                          ///< `read` found it
    std::optional<std::array<double, 3>> colour;   ///< linear RGB; nullopt when not at hand or unreadable
    std::string problem;                           ///< why an image at hand has no colour (names the file)
  };
  /// The image at `path`, decoded the first time it is asked for (`*first` set true then).
  const Image& image(const std::string& path, bool* first = nullptr);
  /// The MTL library at `path`, read the first time (`*first` set true then); nullptr when
  /// it is not at hand.
  const MtlLibrary* library(const std::string& path, bool* first = nullptr);
  /// How messages name the file at `path`.
  std::string name(const std::string& path) const { return prefix_ + path; }

 private:
  Reader read_;
  std::string prefix_;
  std::map<std::string, Image> images_;
  std::map<std::string, std::optional<MtlLibrary>> libraries_;  ///< nullopt: not at hand
};

/// What colour_obj_materials could not find.
struct ObjColouring {
  int libraries_missing = 0;        ///< mtllib arguments naming no library at hand
  std::set<std::string> undefined;  ///< material names neither a library at hand nor Java 3D defines
  int builtin = 0;                  ///< materials coloured from Java 3D's built-in table
  /// `names` as a message lists them: the first five quoted, then "..." if there are more.
  static std::string listed(const std::set<std::string>& names);
};

/// Colours a mesh's OBJ materials (name_obj_materials, by name) as their MTL libraries say,
/// as Sweet Home's OBJLoader does: a material's map_Kd image, where it can be read, as the
/// image's mean colour (Sweet Home draws a textured part in its texture's colours alone);
/// else its Kd, sRGB-encoded (see above), made linear; a name no library defines takes
/// Java 3D's built-in material of that name (plans/java3d_materials.h) as Sweet Home does,
/// and a name neither defines keeps Material's default colour. `libraries`: the OBJ's mtllib arguments (read_mesh_bytes),
/// each found beside `obj` (its path as `files` finds it; mtllib_candidates), each image
/// beside the library that names it (map_Kd_candidates). Each material's `where` becomes
/// its newmtl line. A library named but not at hand, an image not at hand (its Kd used
/// instead), a library's unreadable statements and an unreadable image (the first time
/// `files` reads them) are each one line in `warnings`, beginning with `who`.
ObjColouring colour_obj_materials(Mesh& m, const std::vector<std::string>& libraries, const std::string& obj,
                                  MaterialFiles& files, const std::string& who, std::vector<std::string>& warnings);

}  // namespace avenues
