// Avenues — what kind of file a path names, told by its content where the content says,
// else by its extension.
//
// A plan argument may be any of the formats Avenues reads (a TOML plan, saved cells, a
// Doom WAD, a Sweet Home 3D home, a mesh, a Crow object) or a file Avenues cannot read yet
// (an IFC model, a DXF drawing, a PNG image, ...), and its extension may be missing or
// wrong. detect_format() looks at the first bytes first: a magic number or signature
// ("AVCELLS\0", "PK\3\4", "IWAD"/"PWAD", "ISO-10303-21;", DXF's "0 / SECTION" group codes,
// PNG's signature, "ply", an OFF header, a binary STL whose size matches its triangle
// count, "<home" in XML) decides; without one the extension does; a text file with
// neither is taken for TOML, the native plan format (its reader then names the line).
#pragma once

#include <cstdint>
#include <string>

namespace avenues {

enum class FileFormat : uint8_t {
  Unknown,    ///< none of these (binary, no known signature)
  Toml,       ///< an Avenues plan (docs/PLAN_FORMAT.md)
  Cells,      ///< a saved cell complex ("AVCELLS\0")
  DoomWad,    ///< a Doom WAD ("IWAD" / "PWAD")
  SweetHome,  ///< a Sweet Home 3D home: a .sh3d (zip) archive or a bare Home.xml
  Off,        ///< meshes, read as whole scenes
  Obj,
  Ply,
  Stl,
  Crow,       ///< Crow 1981's object tables (.crow)
  Model,      ///< a 3D model another reader takes by its extension (Assimp: glTF, COLLADA, FBX, 3DS, ...)
  Ifc,        ///< an IFC model (read through Assimp, plans/formats/ifc_building.h)
  Dxf,        ///< a DXF drawing (plans/formats/dxf_plan.h)
  FloorplanVectors,  ///< floor-plan annotations, Raster-to-Vector's "x1 y1 x2 y2 category" (told by content)
  Png,        ///< formats Avenues does not read
  Jpeg,
  Pdf,
  Gzip,
};

/// What a message calls a file of this format: "an IFC model", "a PNG image".
const char* format_name(FileFormat f);

/// True for the mesh formats OpenMesh reads (OFF, OBJ, PLY, STL).
bool is_mesh_format(FileFormat f);

/// The format `path`'s extension names (case-insensitive); Unknown for none or another.
FileFormat format_of_extension(const std::string& path);

/// The format of the file at `path`, by its first bytes, else its extension (see above).
/// Unknown when it cannot be read at all or is neither.
FileFormat detect_format(const std::string& path);

/// The same, for a file's first bytes (up to a few KiB) and its size in bytes.
FileFormat detect_format(const std::string& path, const std::string& head, uint64_t size);

}  // namespace avenues
