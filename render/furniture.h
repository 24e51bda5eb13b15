// Avenues — furniture: the plan's objects as edges to draw and polygons that hide.
//
// An object changes no cell (Jones's cells are the space between walls), so its own hidden
// lines are removed the older way, Crow 1981's: "polygons closer to the eyepoint hide all or
// part of one that is farther away", each candidate edge being clipped against the polygons
// that face the eye. The candidate edges of a mesh are
//  - silhouettes: edges between a polygon facing the eye and one facing away (Crow's back-face
//    test; the same rule as line_weight.h, for two faces), and the edges of an open mesh's
//    boundary: outlines;
//  - creases: edges between two different polygons, both facing the eye, whose normals differ
//    by more than a threshold: creases. A quad's diagonal joins two triangles of one polygon,
//    so it is never an edge here at all.
// Walls hide furniture through the cells: an object belongs to every cell it meets
// (scene_objects.h, cells_met: the cell holding its centroid, and any other it reaches), and
// each of its edges is cut to each such cell's prism and then to that cell's masks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "render/drawing.h"
#include "render/interval_clip.h"
#include "render/scene_objects.h"
#include "plans/mesh.h"
#include "visibility/camera.h"

namespace avenues {

/// An edge between two polygons of a mesh (or on its boundary).
struct FurnitureEdge {
  int32_t v[2] = {-1, -1};        ///< vertex indices into the piece's mesh
  int32_t polygon[2] = {-1, -1};  ///< the polygons either side; polygon[1] = -1 on an open mesh's boundary
  double dihedral_deg = 0;        ///< [deg] in [0, 180]: angle between the two polygons' normals (90 on a box)
};

/// One object of the plan, placed.
struct FurniturePiece {
  std::string name;
  Mesh mesh;                         ///< placed: world coordinates [m]
  std::vector<Vec3> polygon_normal;  ///< unit, outward, per input polygon of the mesh
  std::vector<Vec3> polygon_point;   ///< a vertex of each polygon
  std::vector<FurnitureEdge> edges;  ///< every edge between two different polygons, and the boundary
  std::vector<CellId> cells;         ///< ascending: the cells it meets (cells_met)
};

struct Furniture {
  std::vector<FurniturePiece> pieces;  ///< one per complex.objects entry, same order
};

/// The objects as placed (place_objects: one per complex.objects entry, in order, with
/// the cells each meets), with their edges. The clusters of a cell's detail (Object::cell)
/// are one surface: a side two clusters share is an edge between their polygons, and one
/// along a face of its cell (where a polygon was cut) is none.
Furniture furniture_of(const CellComplex& complex, const std::vector<PlacedObject>& placed);

/// Crow's back-face test: 1 for each polygon of `piece` that faces `eye`.
std::vector<uint8_t> polygons_facing(const FurniturePiece& piece, Vec3 eye);
/// The same for a camera: facing its eye, or a parallel camera's viewer (against its forward).
std::vector<uint8_t> polygons_facing(const FurniturePiece& piece, const Camera& camera);

/// Whether `edge` is drawn, given which polygons face the eye, and how heavy.
bool edge_is_seen(const FurnitureEdge& edge, const std::vector<uint8_t>& facing, double crease_deg, Weight& weight);

/// A triangle of a polygon facing the eye, in camera space: the points it hides are those
/// inside the cone from the eye over the triangle and strictly behind its plane. In a
/// parallel projection the cone is the prism along the direction of view over the triangle,
/// and the eye is the viewer, infinitely far before the picture plane.
struct Occluder {
  Vec3 side[3];   ///< the cone's sides: side·P >= 0 inside (planes through the eye); parallel: side·(x, y, 1) >= 0
  Vec3 n;         ///< unit normal of the triangle's plane, the eye on its positive side
  double d = 0;   ///< n·P + d: [m] signed distance of P from the plane
  Vec2 lo, hi;    ///< bounding box on the picture plane (infinite when a corner is behind the eye)
};

/// Appends the occluders of `piece`: the triangles of its polygons facing the eye (every
/// triangle of an open mesh, which is seen from both sides). A parallel camera's occluders
/// are what lies of them beyond `beyond` (eval >= 0: the plane its rays start from, which
/// cuts away what stands before it), when given.
void add_occluders(const FurniturePiece& piece, const std::vector<uint8_t>& facing, const Camera& camera,
                   std::vector<Occluder>& out, const Plane* beyond = nullptr);

/// The occluders of one view, binned on the picture plane: a grid over the extent of their
/// boxes, each listing the occluders whose box meets it (those whose box is unbounded, or
/// covers a quarter of the grid, are listed apart and met by every segment). A segment is
/// then tested only against the occluders binned where its own box lies: in a view of a
/// steel structure (a soup's detail: a few hundred thousand triangles) testing every edge
/// against every occluder took minutes.
class OccluderGrid {
 public:
  OccluderGrid() = default;
  /// `parallel`: the occluders of a parallel camera (add_occluders).
  explicit OccluderGrid(std::vector<Occluder> occluders, bool parallel = false);
  const std::vector<Occluder>& all() const { return occluders_; }
  bool parallel() const { return parallel_; }
  /// Replaces `out` with the occluders binned where the picture-plane segment from a to b
  /// passes (a bin either side of it, for rounding), and those listed apart, each once:
  /// every occluder that can hide a point of it.
  void near(Vec2 a, Vec2 b, std::vector<int32_t>& out) const;

 private:
  std::vector<Occluder> occluders_;
  bool parallel_ = false;
  std::vector<int32_t> everywhere_;  ///< ascending
  Vec2 lo_, size_;                   ///< the grid's corner and the size of one bin
  int n_ = 0;                        ///< n × n bins
  std::vector<int32_t> start_, items_;
};

/// Removes from `intervals` (sorted, disjoint parameters along the camera-space segment
/// P(t) = p0 + t·(p1 − p0), all with Z > 0 unless `parallel`) what the occluders hide.
void hide_behind(const std::vector<Occluder>& occluders, Vec3 p0, Vec3 p1, std::vector<detail::Interval>& intervals,
                 bool parallel = false);
/// The same, testing only the occluders binned where the segment lies: the same result.
void hide_behind(const OccluderGrid& occluders, Vec3 p0, Vec3 p1, std::vector<detail::Interval>& intervals);

}  // namespace avenues
