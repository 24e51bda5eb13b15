// Avenues — the IFC4 records Assimp 5.2 cannot read, handed to it as IFC2X3 writes them.
//
// Assimp 5.2's IFC reader knows only IFC2X3's entities: it crashes on an entity it does not
// know, or refuses the whole file. What IFC4 exporters write that breaks it is rewritten in
// the text it reads, as IFC2X3 says the same; the rest of the text is left as it is, and
// Assimp reads placements, mapped items, units, openings and styles as before.
//
// Owner histories. IFC4 made an IfcRoot's OwnerHistory optional, and files written by
// IfcOpenShell (BlenderBIM) often leave it out ($): Assimp refuses the whole file ("expected
// argument 1 to IfcRoot to be a `IfcOwnerHistory`"). One IfcOwnerHistory, of no one in
// particular, is added for every IfcRoot record that has none.
//
// Styles. IFC4 lets an IfcStyledItem name its IfcSurfaceStyle directly, where IFC2X3 wraps
// it in an IfcPresentationStyleAssignment (deprecated in IFC4): Assimp fails on the whole
// file with "std::bad_cast". Each such style gets its assignment, a new record.
//
// Indexed curves. ArchiCAD and BlenderBIM bound the profiles of their extrusions (a wall's
// footprint, a slab's outline) by IFC4's IfcIndexedPolyCurve over an IfcCartesianPointList2D;
// Assimp crashes on it. Each becomes an IfcPolyline of new IfcCartesianPoints (copied as
// written): its straight segments (IfcLineIndex) as they are, its arcs (IfcArcIndex: start, a
// point on the arc, end) as points along the circle at most 5° apart.
//
// New kinds and optional attributes. IFC4's kinds of product IFC2X3 knows under a more
// general name (IfcBeamStandardCase, IfcWallElementedCase, IfcSanitaryTerminal, IfcFurniture,
// IfcChimney, ...) are read as that (IfcBeam, IfcWall, IfcFlowTerminal, IfcFurnishingElement,
// a proxy): Assimp crashed on any of them. Attributes IFC4 made optional that IFC2X3 requires
// are given: a swept solid's or profile's Position (an identity placement, made once), a
// swept disk's StartParam and EndParam along a polyline (its whole range). A unit with an
// offset (degrees Fahrenheit) is a conversion-based unit.
//
// New solids. An IfcExtrudedAreaSolidTapered or IfcRevolvedAreaSolidTapered is read as the
// untapered solid, an IfcSweptDiskSolidPolygonal as an IfcSweptDiskSolid without its fillets
// (each said). What IFC2X3 has no form for (IfcAdvancedBrep's NURBS faces, a fixed-reference
// sweep, curved surfaces as items) is left out: an empty bounding box, said. An
// IfcAdvancedFace is an IfcFaceSurface, whose edge loops Assimp passes over (said).
//
// CSG, in IFC2X3 files as in IFC4. Assimp reads no CSG primitive and no IfcCsgSolid, and
// a boolean result only where its first operand is a swept solid or a boolean result. An
// IfcBlock is the extrusion of its rectangle, an IfcRightCircularCylinder that of its
// circle (new profile records, one IfcDirection up for all), an IfcCsgSolid the root of its
// tree written under its own id; a sphere, cone or pyramid is left out, said.
//
// Tessellated geometry. IFC4 added face sets over indexed points: IfcTriangulatedFaceSet and IfcPolygonalFaceSet,
// their corners in an IfcCartesianPointList3D. The Reference View (the view Revit, ArchiCAD
// and BlenderBIM offer for IFC4 exchange) has no other body geometry, so every wall, slab,
// door and space of such a file is one. Assimp crashes on a product whose representation
// holds one.
//
// So each face set record is rewritten, under its own id (the representations, mapped items
// and styles that name it still do), as what IFC2X3 writes for the same faces: an
// IfcFacetedBrep of an IfcClosedShell where the set says it is Closed, else an
// IfcShellBasedSurfaceModel of an IfcOpenShell. Each face becomes an IfcFace bounded by
// IfcPolyLoops over new IfcCartesianPoints, their coordinates copied as the file writes
// them; the inner loops of an IfcIndexedPolygonalFaceWithVoids are its inner bounds. PnIndex
// (IFC4 ADD2) maps the faces' indices into the point list.
//
// Lenient as IFC viewers are: a face naming a point the list does not have, or fewer than
// three distinct points, is dropped (its set is then no longer closed: an open shell); a
// set whose points cannot be read, or with no face left, becomes an empty bounding box,
// which Assimp passes over. Each is said once per set, naming its record and line.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace avenues {

struct Ifc4Rewrite {
  std::string text;                   ///< the STEP text as Assimp is to read it
  size_t face_sets = 0;               ///< tessellated face sets rewritten
  size_t styles = 0;                  ///< styles given an IfcPresentationStyleAssignment
  size_t owners = 0;                  ///< IfcRoot records given the owner history they lacked
  size_t curves = 0;                  ///< IfcIndexedPolyCurves rewritten as IfcPolylines
  size_t solids = 0;                  ///< solids read as Assimp reads them (IFC4 solids as IFC2X3s, CSG as extrusions), or left out
  size_t products = 0;                ///< IFC4 kinds of product read as the IFC2X3 kind they are one of
  std::map<std::string, std::string> kinds;  ///< GlobalId -> the IFC4 kind of such a product ("IfcSanitaryTerminal")
  std::vector<std::string> warnings;  ///< what was dropped, per set ("line 40, #31 (IfcTriangulatedFaceSet): ...")
  /// Of those, the records whose geometry was left out whole (a sphere, a NURBS face, a
  /// curve Assimp has no form for): the first few, and how many in all.
  std::vector<std::string> left_out;
  size_t left_out_count = 0;
};

/// The text with its owner histories, face sets and styles as IFC2X3 writes them; nullopt
/// when it has nothing to rewrite (then Assimp reads the file as it is).
std::optional<Ifc4Rewrite> ifc4_for_assimp(std::string_view step_text);

}  // namespace avenues
