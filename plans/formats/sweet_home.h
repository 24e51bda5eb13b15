// Avenues — a Sweet Home 3D home as a Plan.
//
// Sweet Home 3D (eTeks) saves a home as a .sh3d zip holding a serialized Java "Home"
// entry (every version; the only one before 5.3) and, since 5.3, a "Home.xml" entry
// describing the same home; the examples Debian ships are bare Home.xml files. Home.xml
// is read where there is one, else the serialized Home (java_stream.h reads the Java
// stream, sweet_home_serialized.cpp maps Sweet Home's classes); both fill one home tree
// (home_tree.h) in Home.xml's vocabulary, which one builder turns into the plan:
//   <level>            into storeys, stacked by elevation (levels at one elevation merged),
//   <wall>             into walls: joined walls of one thickness and height become one
//                      mitred centre line, arcs (arcExtent) are tessellated within
//                      Plan::arc_tolerance, sloped tops (heightAtEnd) kept as they are
//                      (Wall::height_at_end; stepped only on a wall of no thickness),
//   <doorOrWindow>     into openings of the wall they sit in (also inside furniture groups):
//                      where they cross its whole thickness, or Sweet Home cuts both sides
//                      (wallCutOutOnBothSides); a piece reaching only partly in (a shutter
//                      on the façade) is a niche in Sweet Home, not a hole: none is cut;
//                      one whose cutOutShape is no rectangle (an arched or round window,
//                      an SVG path: svg_path.h) is cut in strips across it, each open over
//                      what the shape opens all across it, stepped 4 cm at most where flat;
//                      doors and windows drawn into each other (a door under its fanlight)
//                      are one opening, their union, in strips where it is no rectangle,
//   <room>             into rooms labelled at a point well inside their polygon; a home of
//                      rooms and no walls (Sweet Home shows floors in the open) gets a wall
//                      of no thickness along each room edge, open its whole length and
//                      height, so every room is a cell joined to the open all round,
//   <pieceOfFurniture> into objects: the piece's OBJ model (an entry of the .sh3d, or
//                      beside a bare Home.xml at the path it names) fitted to the
//                      piece as Sweet Home fits it, else a box of its size with a
//                      warning; a staircase's cut-out (its curves flattened) into holes
//                      in the floors it climbs through,
//   <observerCamera>   into the plan's viewpoint;
//   colours, textures  into materials (linear light): each side of a wall its own
//                      (left/rightSideTexture, else left/rightSideColor; walls whose
//                      sides differ are not joined), a room's floor and ceiling (texture,
//                      else colour), a piece's color (else its texture) for the whole
//                      piece; else, material by material of its model, the piece's
//                      modelMaterials (<material name key color> / HomeMaterial, matched by
//                      key, else name; an opaque colour or a texture, else the model's own
//                      stays), else the model's own: its OBJ's usemtl groups coloured by
//                      its MTL libraries (beside the model) as map_Kd's image mean, else
//                      Kd (sRGB-encoded, made linear); a name no library defines takes
//                      Java 3D's built-in material of that name (plans/java3d_materials.h),
//                      and one neither defines keeps the default grey. A texture is its
//                      image's mean colour (PNG, JPEG, TGA, ...: plans/image_colour.h). Light
//                      pieces' sources become point lights (PLAN_FORMAT.md).
// Sweet Home lengths are centimetres with y pointing down the screen; a point (x, y)
// becomes (x/100, −y/100) m, which keeps counter-clockwise polygons counter-clockwise
// and turns Sweet Home's clockwise angles into Avenues' anticlockwise ones.
//
// Lenient where Sweet Home is: a wall, room or piece missing what it cannot do without
// is dropped with a warning naming it, not the whole home; a home whose walls are all
// dropped says why for each (the first few). Refused as Sweet Home refuses them: a
// damaged zip, a ContentDigests naming entries the archive lacks, an entry inflating past
// 512 MiB. Nesting (furniture groups) is walked without recursion.
//
// The plan is lenient (Plan::lenient): homes drawn by hand have terraces open to the
// outside, rooms labelled twice, room polygons that cross walls; build_cells() makes
// those warnings. What the importer itself repaired or dropped is in Plan::warnings.
#pragma once

#include <string>

#include "plans/plan.h"

namespace avenues {

/// Which entry of a .sh3d to read: Home.xml where there is one (else the serialized Home),
/// or one of them alone (to compare the two).
enum class HomeEntry { Preferred, Xml, Serialized };

/// How much a .sh3d may make the reader hold: a zip entry may claim anything in its header,
/// and a small archive may inflate to gigabytes.
struct HomeLimits {
  /// [bytes] an entry inflating past this is refused (PlanError naming it); no Sweet Home
  /// entry comes near the default 512 MiB. (The fuzz target sets far less.)
  size_t max_entry_bytes = size_t(512) << 20;
};

/// Reads a Sweet Home 3D home: a .sh3d file (a zip holding Home.xml, a serialized Java
/// Home, or both) or a bare Home.xml (the examples shipped in Debian's sweethome3d package
/// are bare XML), told apart by content. Throws PlanError naming the file and element
/// (with the XML line, or the byte of the serialized object, where known) for what
/// cannot be read.
Plan read_sweet_home(const std::string& path, HomeEntry entry = HomeEntry::Preferred, const HomeLimits& limits = {});

}  // namespace avenues
