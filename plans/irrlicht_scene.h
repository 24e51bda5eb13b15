// Avenues — Irrlicht's XML scenes (.irr, as irrEdit and CopperCube save them) and static
// meshes (.irrmesh), read with pugixml.
//
// Assimp has readers of both, but in Debian 12's Assimp (5.2) they refuse every such file
// ("XML parse error while loading IRR file": its XML reader was replaced by pugixml and the
// two readers were left expecting the old one's text, UTF-16 and all; assimp/assimp#4553).
// This reader takes what a walkthrough needs: the geometry, where it is placed, and one
// colour per material.
//
// Irrlicht's space is left-handed with y up; a point (x, y, z) of it is (x, z, y) in
// Avenues' (right-handed, z up). That mirror turns each triangle over, so its corners are
// reversed: the side Irrlicht shows it from ((b − a) × (c − a) towards the viewer, in its
// coordinates, as its files' normals agree) is then the side Avenues calls outside.
// Irrlicht has no unit: one unit is a metre unless --unit (MeshAxes::metres_per_unit)
// says otherwise.
//
// A scene's nodes are placed as Irrlicht places them (translation, then rotation in degrees
// about z, y and x in that order of matrices, then scale; each child within its parent):
// - `mesh`, `animatedMesh` and `octTree` nodes draw the file their `Mesh` attribute names,
//   found beside the scene (a name whose case differs from the file's, as scenes written
//   on Windows name them, is found too): an .irrmesh by this reader, any other model through
//   Assimp (plans/assimp_reader.h) turned into Irrlicht's space as Irrlicht's own readers
//   turn it (an OBJ's x negated; other formats as Assimp makes a left-handed scene, z
//   negated); an animated mesh as it stands in its file;
// - `cube` and `sphere` nodes are Irrlicht's own cube (`Size`) and sphere (`Radius`,
//   `PolyCountX`, `PolyCountY`);
// - `empty` and `dummyTransformation` nodes only place their children;
// - what is no surface of a building (a light, a camera, a sky box or dome, a billboard,
//   particles, text, a terrain) and a node whose type Irrlicht does not define is left
//   out, its children kept, with a warning naming it; so is a mesh that cannot be read,
//   and a hidden node (`Visible` false) with its children, as Irrlicht hides them.
// Animators are not played: the scene is shown as placed.
//
// Colours: a material's first texture's mean colour (plans/image_colour.h), found as the
// meshes are, else its Diffuse colour. A mesh node's <materials> replace its .irrmesh
// buffers' (and a cube's or sphere's) one for one, as Irrlicht's scene loader does; a model
// read through Assimp keeps its own materials.
//
// Strict where the file is broken (XML that does not parse, no <irr_scene> or <mesh> root,
// a scene that names itself): a std::runtime_error naming the file and line. Lenient where
// Irrlicht is: a vertex whose position is not a number, and a triangle naming it or no
// vertex at all, are dropped with a warning naming the buffer and line.
#pragma once

#include <string>

#include "plans/assimp_reader.h"

namespace avenues {

enum class IrrlichtFile {
  None,   ///< not Irrlicht's XML
  Scene,  ///< root element <irr_scene>
  Mesh,   ///< root element <mesh>, with <buffer> elements or Irrlicht's namespace
};

/// What the file is, by its content (UTF-8, or UTF-16 with its byte-order mark, as
/// Irrlicht writes it), whatever its name; None for anything else or no readable file.
IrrlichtFile irrlicht_file_kind(const std::string& path);

/// Reads an Irrlicht scene or mesh (irrlicht_file_kind) as a scene of nodes placed in
/// Avenues' space (see above); ImportedScene::format says which. Throws std::runtime_error
/// naming the file (and the line) when it cannot be read or holds no triangle.
ImportedScene read_irrlicht(const std::string& path, const ImportOptions& options = {});

}  // namespace avenues
