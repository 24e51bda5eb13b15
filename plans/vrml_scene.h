// Avenues — VRML97 worlds (.wrl, gzipped .wrz) and X3D's classic VRML encoding (.x3dv),
// read by Avenues: Debian 12's Assimp has no VRML reader, and VRML97 is what many CAD and
// modelling tools still export a building as (ArchiCAD, 3ds Max, SketchUp, FreeCAD, older
// Blender).
//
// The syntax is read whole, generically: every node with its fields, DEF and USE, lists and
// single values, whatever the node's type, so that nodes this reader does not draw (lights,
// viewpoints, sensors, scripts, interpolators) are passed over without
// knowing their fields. A PROTO's instance is its body's first node, each IS in it given
// the instance's value of that field or the PROTO's default (VRML97 4.8). What is drawn:
// - Shape nodes with an IndexedFaceSet (each face cut into triangles, a face that is not
//   convex by a constrained triangulation), an ElevationGrid, an Extrusion (swept as the
//   standard says, a closed one facing out: plans/primitive_shapes.h), X3D's triangle and
//   quad sets (TriangleSet, QuadSet, their strips and fans, indexed or not), or the
//   primitives Box, Sphere, Cylinder and Cone;
// - within Transform (translation, rotation, scale, scaleOrientation, center), Group,
//   Anchor, Billboard (as placed), Collision, Switch (its chosen child), LOD (its first
//   level) and Inline (the world its url names, beside this one);
// - each Shape in its Material's diffuseColor, or its ImageTexture's mean colour
//   (plans/image_colour.h), taken as linear as Assimp's readers take colours; the
//   geometry's Color node, where it has one and no texture was read, colours each face (a
//   colour a face, or the mean of its corners').
// VRML's space is right-handed with y up, in metres: a point (x, y, z) is (x, −z, y) in
// Avenues'. `--up` and `--unit` (MeshAxes) override both, for CAD exports that do not keep
// to them.
//
// Left out with a warning naming them: EXTERNPROTO instances (their bodies are in other
// files, not read), Text, lines and points, a face naming no coordinate, an Inline that cannot
// be read. Refused naming the file and line: a file that is not VRML97 or classic X3D
// (VRML 1.0 included), broken syntax (an unclosed brace, a USE of a name never DEFined),
// nesting deeper than 1,000 nodes, PROTO instances expanding to more than 2,000,000 nodes.
#pragma once

#include <string>

#include "plans/assimp_reader.h"

namespace avenues {

/// Whether the file is a VRML97 world or classic-encoded X3D, by its first line ("#VRML
/// V2.0", "#X3D V3" or "#X3D V4"), gzipped or not, whatever its name.
bool is_vrml(const std::string& path);

/// Reads the world (see above) as a scene of nodes placed in Avenues' space; its format is
/// "VRML97 (Avenues' reader)". Throws std::runtime_error naming the file (and the line)
/// when it cannot be read or draws no triangle.
ImportedScene read_vrml(const std::string& path, const ImportOptions& options = {});

}  // namespace avenues
