// Avenues — the cell complex: convex cells joined by convex portals.
//
// Jones 1971: "the space ... is considered ... as a set of cells which are bounded
// partly by faces of the original objects, and partly by artificially introduced
// transparent faces. ... Each cell is required to be a convex polyhedron, ... each
// opening ... a convex polygon, ... shared by two adjacent cells."
//
// A plan's cells are vertical prisms: a convex footprint (counter-clockwise, seen from
// above) between two heights, except over a sloped wall, whose top is the floor of the
// cells above it; those, and a mesh scene's cells, are general convex polyhedra
// (Cell::prism). Plain structs linked by typed
// indices (Recast/Godot style); the CellComplex owns every array, cells never point
// at each other. All coordinates are doubles in metres, rounded once from the exact
// CGAL construction (cells/triangulate.cpp for plans, cells/mesh_scene.cpp for meshes).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cells/closed_surface.h"
#include "core/geometry.h"
#include "core/stage_timer.h"
#include "plans/plan.h"

namespace avenues {

using CellId = int32_t;    ///< index into CellComplex::cells
using PortalId = int32_t;  ///< index into CellComplex::portals
using LineId = int32_t;    ///< index into CellComplex::lines
using RoomId = int32_t;    ///< index into CellComplex::rooms; -1 = none (outside, sky)

constexpr CellId kNoCell = -1;

enum class CellKind : uint8_t {
  Room,       ///< a convex piece of a named (or enclosed, unnamed) room
  Doorway,    ///< the volume of an opening inside a thick wall, sill to head
  Stairwell,  ///< a hole through a floor slab
  Outside,    ///< free space around the building, storey or slab height
  Sky,        ///< free space above the building, up to the far box
};
const char* to_string(CellKind k);

enum class PortalKind : uint8_t {
  Transparent,  ///< an artificial face between two convex pieces of one space
  Door,
  Window,
  Hatch,
  Gap,          ///< the open part above a low wall
  Stairwell,    ///< horizontal, through a floor opening
  Open,         ///< horizontal or vertical between outside pieces (no building element)
};
const char* to_string(PortalKind k);

/// A convex polygon shared by exactly two cells.
struct Portal {
  CellId cell[2] = {kNoCell, kNoCell};
  std::vector<Vec3> poly;  ///< convex, counter-clockwise seen from cell[0] (its normal points into cell[1])
  Plane plane;             ///< n points from cell[0] into cell[1]
  PortalKind kind = PortalKind::Transparent;
  int opening = -1;        ///< plan element index (wall opening or floor opening), -1 if none
  CellId other(CellId c) const { return cell[0] == c ? cell[1] : cell[0]; }
};

/// An opaque convex polygon on a cell's boundary, facing into the cell.
struct OpaquePoly {
  std::vector<Vec3> poly;  ///< convex, counter-clockwise seen from inside the cell
  MaterialId material = -1;
  int32_t surface = -1;    ///< derived: its Surface in CellComplex::surfaces (index()); -1 before
};

/// The opaque pieces of the whole complex that lie in one plane, face one way and have one
/// material: one surface of the building (a wall's face, a floor), however many cells cut
/// it. Bouknight shaded each polygon of his scene flat, from its normal and the light's
/// direction; a surface the decomposition cut into pieces is still one polygon to him, so
/// the half-tone lights every piece of it from one point, its centroid, and it takes one
/// flat shade with no false edges where cells meet (cells/surface.cpp).
struct Surface {
  Vec3 normal;              ///< unit, into free space (the first piece's)
  Vec3 centroid;            ///< [m] area-weighted over all its pieces
  double area = 0;          ///< [m²]
  MaterialId material = -1;
};

/// One planar face of a cell's boundary: opaque except where portals open it.
struct Face {
  Plane plane;                    ///< outward
  std::vector<Vec3> poly;         ///< the whole face, convex, counter-clockwise seen from inside
  std::vector<PortalId> portals;  ///< portals lying in this face; on a prism's side face, sorted along it (from footprint[i])
  std::vector<OpaquePoly> opaque; ///< the face minus its portals, as convex pieces
  /// Some portals of this side face overlap along it (stacked one above another: a tall
  /// outside cell meeting cells of several bands), so sorted by start they are not sorted
  /// by end; a lookup by the stretch of face seen must then scan from the first.
  bool portals_overlap = false;
};

enum class LineKind : uint8_t {
  Concave,  ///< a crease seen from inside free space (wall–floor, inner corner)
  Convex,   ///< an outer corner, an edge of a reveal, a roof edge: can be a silhouette
  Sheet,    ///< an edge of a zero-thickness wall (its end, its openings' frames)
};
const char* to_string(LineKind k);

/// A real line of the architecture (never an edge of an artificial face).
struct RealLine {
  Vec3 a, b;  ///< [m]
  LineKind kind = LineKind::Concave;
};

/// The part of a real line that bounds one cell; `line` is shared by every cell
/// the line touches, so a renderer can draw each line once.
struct CellLine {
  LineId line = -1;
  double t0 = 0, t1 = 1;  ///< parameter range along RealLine a→b, 0 <= t0 < t1 <= 1
};

struct Cell {
  CellKind kind = CellKind::Room;
  RoomId room = -1;
  StoreyId storey = -1;          ///< storey whose band holds the cell; -1 above/below the building
  std::vector<Vec2> footprint;   ///< convex, counter-clockwise, no collinear vertices
  double z0 = 0, z1 = 0;         ///< [m] floor and ceiling of the prism, z0 < z1
  std::vector<Face> faces;       ///< sides (one per footprint edge, edge i from footprint[i]), then bottom, then top
  std::vector<PortalId> portals; ///< all portals of all faces
  std::vector<CellLine> lines;   ///< real lines on the cell's boundary
  int opening = -1;              ///< for Doorway/Stairwell cells: plan element index
  /// false: a general convex polyhedron (a mesh scene's cell, cells/mesh_scene.h). Its
  /// faces are all there is, in no particular order; `footprint` is its outline seen from
  /// above and z0..z1 its range of heights, for drawings and indexing only.
  bool prism = true;

  Box3 bounds() const;
  /// [m³] its footprint's area times its height (a prism), else pyramids from one of its
  /// vertices to every face.
  double volume() const;
  /// [m] the mean of its faces' corners: inside it, as it is convex.
  Vec3 middle() const;
  /// [m] how thin it is: the least, over its faces, of its depth behind the face.
  double width() const;
  /// Closed containment with tolerance tol [m] (positive grows the cell).
  bool contains(Vec3 p, double tol = 0) const;
};

struct RoomInfo {
  std::string name;
  StoreyId storey = 0;
  bool named = true;  ///< false for an enclosed space no plan room labels
  double area = 0;    ///< [m²] floor area (free footprint)
};

/// What a point is in (point location).
struct Location {
  enum class What : uint8_t { Cell, Solid, OutsideBox } what = What::OutsideBox;
  CellId cell = kNoCell;
  std::string solid;  ///< for Solid: what it is inside, e.g. "wall 'north' (plan.toml:12)"
};

struct CellComplex {
  std::string plan_name;
  std::vector<Storey> storeys;
  std::vector<Material> materials;
  std::vector<RoomInfo> rooms;
  std::vector<Cell> cells;
  std::vector<Portal> portals;
  std::vector<RealLine> lines;
  std::vector<Object> objects;  ///< carried along for the renderer
  /// Closed curved solids of a mesh scene drawn as detail (cells/closed_surface.h): free
  /// space runs through them, their facets are detail objects of the cells they cross, and
  /// these keep the walker out of them (visibility/walker.h) and name them for locate().
  std::vector<ClosedSurface> detail_solids;
  std::vector<Light> lights;
  Box3 far_box;                 ///< the large opaque box (Jones) around everything
  std::optional<Viewpoint> view;
  std::vector<StageTime> timings;
  /// What the importer and the decomposition noticed and repaired or dropped, one line
  /// each, naming the element (the CLI prints them to stderr).
  std::vector<std::string> warnings;

  /// Which cell holds p. `hint` (a cell near p, e.g. the last eye's) makes it a short
  /// walk through portals; a spatial index catches the rest. Points on a shared face
  /// go to either cell. Solid reports name the element when known; a point inside one of
  /// the detail solids is in that solid, though a cell holds it.
  Location locate(Vec3 p, CellId hint = kNoCell) const;
  /// The same for an eye looking along `facing`: an eye on a face of two cells (a sheet
  /// wall of no thickness, a floor) is on the side it looks to, in the cell that holds both
  /// it and a point just ahead of it, as an eye in a doorway's plane is in the room it
  /// looks into. (Looking along the face itself, either cell.) The search of what such an
  /// eye sees starts in every cell that holds it (find_visible, visibility/visible_set.h).
  Location locate(Vec3 p, Vec3 facing, CellId hint = kNoCell) const;
  /// Every cell whose closure, grown by tol [m], holds p, ascending: one for a point
  /// inside a cell, two or more for a point on a face two cells share (a sheet wall, a
  /// doorway's plane), at a T-junction of sheets or on a common edge.
  std::vector<CellId> cells_holding(Vec3 p, double tol) const;
  /// Replaces `out` with the cells the spatial index lists in the squares that b's plan
  /// meets, ascending, each once: every cell whose bounds meet b, and some others (the
  /// caller tests their bounds). Every cell when there is no index.
  void cells_near(const Box3& b, std::vector<CellId>& out) const;

  /// The room's largest cell of kind Room (by footprint area): where a person stands in
  /// it. kNoCell when the room has no such cell.
  CellId largest_cell_of(RoomId room) const;

  /// Builds the spatial index used by locate() and the surfaces (index_surfaces); done by
  /// build_cells, the mesh scenes and load_cells.
  void index();
  /// Puts into each opaque piece's edges the corners of other pieces that lie inside them
  /// (T-junctions, within the corners' rounding), so that pieces meeting along a line meet
  /// at the same corners and no sample on the seam falls between them (cells/seam.cpp).
  /// Done where cells are made, before index(), and when a .cells file written before it
  /// (format version 6 or older) is loaded; returns the corners added.
  size_t close_seams();
  /// Groups every opaque piece into `surfaces` (OpaquePoly::surface): pieces of one
  /// material whose planes agree within 1e-6 in direction and 10 µm in place.
  void index_surfaces();
  /// Lays out `portal_table` from the cells and portals as they are.
  void index_portals();
  /// Lists each cell's detail objects (Object::cell, a large soup's: cells/soup_detail.h)
  /// with their bounds in `detail_boxes`; done by index(), and by add_detail_objects.
  void index_detail();

  // --- spatial index (derived; rebuilt by index()) ---
  struct Band {
    double z0 = 0, z1 = 0;
    double x0 = 0, y0 = 0, cell_size = 1;
    int nx = 0, ny = 0;
    std::vector<int32_t> start;   ///< nx*ny+1 offsets into items
    std::vector<CellId> items;
  };
  std::vector<Band> bands;
  /// Solid regions for naming what a point is inside (footprints of walls etc.).
  struct SolidBox {
    std::vector<Vec2> quad;  ///< convex footprint
    double z0 = 0, z1 = 0;
    std::string what;
  };
  std::vector<SolidBox> solids;
  std::vector<Surface> surfaces;  ///< derived (index_surfaces)
  /// A cell's detail object and the bounds of its model (derived: index_detail). The walker
  /// stops where a move meets a triangle of one (visibility/walker.h): the slabs and walls
  /// of a large soup that were made detail so as not to cut space are still walls to a
  /// person.
  struct DetailBox {
    Box3 box;
    int32_t object = -1;  ///< index into `objects`
  };
  std::vector<int32_t> detail_start;   ///< per cell, and one more: its first in detail_boxes
  std::vector<DetailBox> detail_boxes;

  /// Each cell's portals laid out for the search of what an eye sees (derived; rebuilt by
  /// index_portals). The search meets a cell, then each portal of each of its faces, then
  /// each portal's corners: in the arrays above a chain of separate allocations (the cell,
  /// its faces, each face's list, each portal, its corners), each a cache miss when a view
  /// first reaches the cell, and most views reach most of their cells once. Here they lie
  /// cell by cell in a few flat arrays, in the order the search reads them: the cell's
  /// faces, each face's portals as seen from the cell, and their corners (copied: a portal's
  /// corners lie with each of its two cells).
  struct PortalTable {
    /// A portal of a face, as seen from the face's cell.
    struct Seen {
      Plane plane;            ///< the portal's (its normal into cell[1])
      PortalId portal = -1;
      CellId other = kNoCell; ///< the cell beyond it
      int32_t corner0 = 0;    ///< its first corner in `corners`
      uint32_t corners = 0;   ///< how many (Portal::poly, in order)
      uint32_t spread = 1;    ///< k: corners 0, k and k + 1 span the most area (1 for fewer than 4)
      bool first = false;     ///< the cell is the portal's cell[0]
    };
    std::vector<int32_t> cell_faces;  ///< per cell, and one more: its first face's entry in face_seen
    std::vector<int32_t> face_seen;   ///< per face of every cell in order, and one more: its first in `seen`
    std::vector<Seen> seen;
    /// Beside `seen`, each cell's neighbours across each face, in the order of Cell::portals:
    /// indices into `seen`, of the first of a face's portals into each other cell (its
    /// others lie in the same plane, on the same side of the eye), then -1 to the end of
    /// the cell's entries. What the merged search reads to find a pending neighbour in
    /// front of a cell (a soup's cell: 56 portals, 4 such neighbours, on average in one
    /// IFC model).
    std::vector<int32_t> listed;
    std::vector<Vec3> corners;
    /// Per face of every cell in order, and one more: its first entry in `hulls`, an empty
    /// range where the face holds no two portals into one cell or its cell is a prism.
    std::vector<int32_t> face_hulls;
    /// A face's portals into each other cell as one: their convex hull in the face's plane
    /// (its corners some of theirs, in `corners`; `portal` the least of theirs; `first`
    /// true, the plane's normal into `other`), or where their hull has no area (rounding),
    /// each of them as in `seen`. A soup's cell face is cut into many convex
    /// portals around the surfaces that cover parts of it (a slab's many openings onto the
    /// cell below: hundreds); the hull search, which joins whatever reaches a cell into its
    /// hull anyway, clips a mask to their hull once instead of to each (traverse.h).
    std::vector<Seen> hulls;
    size_t portal_count = 0;          ///< portals.size() when laid out
    /// Whether the table was laid out for a complex of c's size (a complex changed since
    /// must be indexed again, as for the spatial index).
    bool fits(const CellComplex& c) const {
      return cell_faces.size() == c.cells.size() + 1 && portal_count == c.portals.size();
    }
  };
  PortalTable portal_table;
};

/// Sum of cell volumes [m³].
double total_volume(const CellComplex& c);

/// c's portals laid out cell by cell (CellComplex::PortalTable): what index_portals keeps,
/// and what the search lays out for itself in a complex never indexed.
CellComplex::PortalTable lay_out_portals(const CellComplex& c);

}  // namespace avenues
