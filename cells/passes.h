// Avenues — what the passes of build_cells hand each other (internal to cells/).
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "cells/outline.h"
#include "cells/triangulation.h"

namespace avenues::detail {

/// A horizontal slice of the far box in which every cell spans the full height
/// (except doorway cells, which span their opening's sill to head inside a storey band).
struct Band {
  enum class Kind { Storey, Slab, Plinth, Sky } kind = Kind::Storey;
  double z0 = 0, z1 = 0;   ///< [m]
  StoreyId storey = -1;    ///< storey of a Storey band; the storey below a Slab band
  bool outside_free = true;///< false below ground (earth)
};

/// What free space a triangle is, in one band.
struct SpaceClass {
  CellKind kind = CellKind::Room;
  RoomId room = -1;
  int opening = -1;        ///< plan-wide opening id (Doorway) or floor-opening index (Stairwell)
  PortalKind portal = PortalKind::Transparent;  ///< kind of portal leading into it from a room
  int wall = -1;           ///< the wall a doorway is cut through
  Intervals open;          ///< heights [m] at which it is free (one cell per interval)
  /// Over a sloped wall: the last interval of `open` starts at this plane (the wall's top),
  /// not at its stored lower bound, the plane's least height over the class's triangles.
  std::optional<Slope> top;
};

/// Pass 3's result: per band, per triangle, a class index or -1 for solid.
struct Classes {
  std::vector<Band> bands;
  std::vector<SpaceClass> classes;
  std::vector<std::vector<int32_t>> of;   ///< of[band][triangle]
  std::vector<RoomInfo> rooms;
  std::vector<int32_t> wall_of;           ///< per band*T + t: wall owning a solid triangle of a storey band, or -1
  std::vector<std::string> warnings;      ///< spaces claimed by two rooms, rooms that leak, area dropped
};

Classes classify(const Plan& plan, const Outline& outline, const Triangulation& tri);

/// Calls f(region) for each sheet (wall of no thickness) of storey s on half-edge h.
template <class F>
void for_each_sheet_of_storey(const Outline& o, const Triangulation& T, int h, StoreyId s, F&& f) {
  for (int32_t k = T.sheet_start[size_t(h)]; k < T.sheet_start[size_t(h) + 1]; ++k)
    if (o.regions[size_t(T.sheet_items[size_t(k)])].storey == s) f(T.sheet_items[size_t(k)]);
}

/// Whether a sheet of storey s lies on half-edge h.
inline bool has_sheet_of_storey(const Outline& o, const Triangulation& T, int h, StoreyId s) {
  for (int32_t k = T.sheet_start[size_t(h)]; k < T.sheet_start[size_t(h) + 1]; ++k)
    if (o.regions[size_t(T.sheet_items[size_t(k)])].storey == s) return true;
  return false;
}

/// Whether a cut of band b lies on half-edge h.
inline bool has_cut_of_band(const Triangulation& T, int h, size_t b) {
  if (T.cut_start.empty()) return false;
  for (int32_t k = T.cut_start[size_t(h)]; k < T.cut_start[size_t(h) + 1]; ++k)
    if (size_t(T.cut_items[size_t(k)]) == b) return true;
  return false;
}

/// Per half-edge, whether band b's pieces may not be merged across it: a sheet of the
/// band's storey, or one of the band's cuts. Empty where nothing bars merging.
std::vector<uint8_t> band_barrier(const Outline& outline, const Triangulation& T, const Band& band, size_t b);

/// Pass 3b: where the triangulation of every storey's outlines parts a band's free space
/// into more pieces than that space needs, cuts `exact` where it parts it well, and hands
/// each triangle's class (and wall) in `C` on to the triangles it splits into
/// (cells/band_cuts.cpp).
void cut_bands(const Outline& outline, ExactTriangulation& exact, Classes& C);

/// Points a rounding apart: distinct in the exact triangulation, within a few ulps once
/// rounded (or equal). A footprint takes them as one point: the turn between them is noise.
bool rounding_apart(Vec2 a, Vec2 b);

/// What a point of a piece's closed boundary is as a corner of its footprint: a Repeat
/// (a rounding from the point before it; the first of such a run stands for it), or the
/// turn it makes between its nearest neighbours that are not a rounding from it
/// (cells/corners.cpp).
enum class Corner : uint8_t { Repeat, Straight, Left, Right, Reversal };
/// `made` (may be null): per point of the ring, whether a cut made it (Triangulation::cut_made).
void corners_of(const std::vector<Vec2>& ring, std::vector<Corner>& out, const std::vector<uint8_t>* made = nullptr);

/// The ring of points a piece's boundary (half-edges of T, each from its start) goes
/// through, and, where T was cut, which of them a cut made (else `made` is left empty):
/// what corners_of() judges. Returns `made`, or null where it is empty.
const std::vector<uint8_t>* ring_of(const Triangulation& T, const std::vector<int32_t>& half_edges,
                                    std::vector<Vec2>& ring, std::vector<uint8_t>& made);

/// Whether a closed boundary's footprint is convex: no corner turns right or back on
/// itself, and the boundary winds once. `corners` and `points` are scratch.
bool convex_footprint(const std::vector<Vec2>& ring, std::vector<Corner>& corners, std::vector<Vec2>& points,
                      const std::vector<uint8_t>* made = nullptr);

/// Pass 4: Hertel–Mehlhorn merging. Triangles with equal label >= 0 are merged across
/// edges not marked as barriers while the union stays convex. Returns a piece index per
/// triangle (-1 where label < 0) and each piece's boundary as half-edges 3t+i in
/// counter-clockwise order.
struct Pieces {
  std::vector<int32_t> of;                       ///< per triangle
  std::vector<std::vector<int32_t>> boundary;    ///< per piece, half-edges
  std::vector<int32_t> label;                    ///< per piece
};
Pieces merge_convex(const Triangulation& tri, const std::vector<int32_t>& label,
                    const std::vector<uint8_t>& barrier /* per half-edge, may be empty */);

/// Which cells stand on which pieces of which band (pass 5's bookkeeping, read by pass 6).
struct Layout {
  std::vector<Pieces> pieces;                             ///< per band
  std::vector<std::vector<std::vector<CellId>>> cells_of; ///< per band, per piece: its cells, bottom up
  /// Per cell: the sloped floor of a cell over a sloped wall (the wall's top), else none.
  /// Such a cell is no prism: Cell::z0 is its floor's least height.
  std::vector<std::optional<Slope>> floor_plane;
  /// The cell of band b over triangle t whose heights hold z (strictly inside), or -1. A
  /// cell with a sloped floor holds every z above its least height: the caller judges z
  /// against floor_plane at the point it looks at.
  CellId cell_at(const CellComplex& c, size_t b, int t, double z) const;
};

/// Pass 5: cells, portals and faces.
Layout extrude(const Plan& plan, const Outline& outline, const Triangulation& tri, const Classes& cls,
               CellComplex& out);

/// Pass 6: the real lines of the architecture, assigned to the cells they bound.
void real_lines(const Outline& outline, const Triangulation& tri, const Classes& cls, const Layout& layout,
                CellComplex& out);

}  // namespace avenues::detail
