// Avenues — Crow's formats (Crow 1981, "Three-dimensional computer graphics, part 1",
// BYTE, table 1 and listings 1–2): the two ways the article stores an object.
//
// Table 1a, an object "constructed of straight pieces of wire": one point per line, "a
// command to draw a line to that position or just move to that position":
//     m 1.0 -1.0 -1.0
//     d -1.0 -1.0 -1.0
// (listing 1 reads a count of points first; the table prints none — both are accepted).
// Table 1b, a solid "defined as a set of polygons": a line "NumPts NumPolys", then NumPts
// lines "J X Y Z" (the point's number, 1 to NumPts, and its coordinates), then NumPolys
// lines "n i1 ... in" (a polygon's vertex count, then its point numbers), each polygon
// "in clockwise order (as seen from outside the object)".
// Which table a file holds is told by its content. Text in parentheses (the table's own
// "(NumPts NumPolys)") and after '#' is a comment. A mistake is a PlanError naming the
// file, the line and the point or polygon.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "cells/mesh_scene.h"
#include "plans/mesh.h"

namespace avenues {

struct CrowObject {
  enum class Table : uint8_t {
    Lines,     ///< table 1a: move/draw commands
    Polygons,  ///< table 1b: points, then polygons by point number
  };
  Table table = Table::Lines;
  std::string path;
  /// [m] the object's distinct points; in table 1b point J is points[J - 1] (table 1a's
  /// twenty commands visit ten points).
  std::vector<Vec3> points;
  /// Table 1a: each run of a move and the draws after it, as indices into points.
  std::vector<std::vector<int>> polylines;
  /// Table 1b: indices into points, clockwise seen from outside as Crow lists them.
  std::vector<std::vector<int>> polygons;
};

/// Reads either table. Throws PlanError (file:line, and the point or polygon) for
/// malformed input, std::runtime_error naming the file when it cannot be read.
CrowObject read_crow(const std::string& path);
/// The same from text; `name` stands for the file in messages.
CrowObject parse_crow(const std::string& text, const std::string& name);

/// Table 1b's polygons as a mesh: turned counter-clockwise seen from outside, cut into
/// triangles (ear clipping, so a concave polygon is fine), with polygon_of, vertex normals
/// and closedness as load_mesh gives them. Throws PlanError for an object with no polygons.
Mesh crow_mesh(const CrowObject& object);

/// The object's lines: table 1a's draws, or each edge of table 1b's polygons once.
/// Wires can be seen past on both sides, so every line is LineKind::Convex.
std::vector<RealLine> crow_lines(const CrowObject& object);

/// An object as a whole scene. Polygons become the solid of a mesh scene
/// (build_mesh_scene). A line list has no surfaces: its lines stand in free space, the
/// cells of an empty far box (the lines' bounds grown by params.margin), each line given to
/// the cells it passes through, so the hidden-line drawing shows them all.
CellComplex read_crow_scene(const std::string& path, const MeshSceneParams& params = {});

}  // namespace avenues
