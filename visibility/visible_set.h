// Avenues — the visible set: every (cell, mask) reached from the eye, with its avenue.
#pragma once

#include <string>
#include <optional>
#include <vector>

#include "cells/cell_complex.h"
#include "visibility/camera.h"

namespace avenues {

/// The arithmetic the traversal runs in (see mask.h for what each one guarantees):
/// float and double round (with a sign bound that treats near-touching as touching);
/// filtered evaluates in interval arithmetic and falls back to exact rationals only when
/// an interval cannot decide a sign (CGAL::Lazy_exact_nt); exact is GMP rationals throughout.
enum class Kernel { Float, Double, Filtered, Exact };
const char* to_string(Kernel k);
/// Parses "float", "double", "filtered" or "exact"; false if it is none of them.
bool parse_kernel(const std::string& s, Kernel& out);

/// [m] An eye this near a face's plane stands on it (in the cells on both sides): far below
/// any plan's detail, far above the rounding of coordinates of a building's size. The
/// search and the ray oracle that checks it both take it so.
inline constexpr double kOnBoundary = 1e-9;

/// One avenue of sight ending in a cell (Jones's Fig. 5: a node of the directed subgraph).
struct Avenue {
  CellId cell = kNoCell;
  int parent = -1;         ///< index of the avenue this one extends; -1 for the eye's cell
  PortalId portal = -1;    ///< the portal crossed last; -1 for the eye's cell
  int depth = 0;           ///< portals crossed
  std::vector<Vec2> mask;  ///< convex, counter-clockwise, on the picture plane (x = X/Z, y = Y/Z; parallel: x = X, y = Y)
};

struct VisibleSet {
  CellId eye_cell = kNoCell;
  std::vector<Avenue> avenues;  ///< depth-first order; avenues[0] is the eye's cell; an eye on its cell's boundary: one root (parent -1) per cell holding it, each through the directions entering it (parallel: one root per cut cell); searched in strips (strips.h): each strip's avenues in turn, its own roots first
  std::vector<CellId> cut_cells;  ///< parallel: the cells the cut plane crosses, ascending (the roots)
  std::optional<Plane> cut;       ///< parallel: the plane the rays start on (the cut, or the picture plane)
  std::vector<CellId> cells;    ///< distinct visible cells, ascending
  long portals_tested = 0;      ///< portals examined (facing test and clipping)
  long avenues_pruned = 0;      ///< avenues not followed: mask inside one already found into the cell
  long avenues_merged = 0;      ///< merged (or hull) search: pieces joined into another piece of their cell
  long masks_settled = 0;       ///< floating point: masks with a corner strayed past their parent's, settled (Mask::settle_within)
  long between_samples = 0;     ///< pieces of view not followed: no sample's centre in them (TraverseParams::samples_per_side)
  /// The hull search (TraverseParams::hull_pieces) found it: the cells hold every visible
  /// cell and the masks every ray of their cells, but may hold more (so what they show must
  /// be resolved by depth).
  bool conservative = false;
  /// Searched in strips of the window (strips.h): the index of each strip's first avenue,
  /// the strips from the left. Empty: one search of the whole window.
  std::vector<int> strips;
  std::vector<double> strip_micros;  ///< [µs] and each strip's search time
  int max_depth = 0;
  double micros = 0;            ///< [µs] time of the traversal
  /// The avenue's portals from the eye outwards.
  std::vector<PortalId> path(int avenue) const;
  /// Sets `cells` to the distinct cells of `avenues`, ascending, and `max_depth`.
  void collect_cells();
};

/// How the search runs.
struct TraverseParams {
  Kernel kernel = Kernel::Double;
  /// Do not follow an avenue whose mask lies inside that of an avenue already found into
  /// the same cell (certainly inside: exactly in the exact kernels, conservatively in float
  /// and double). The cells seen and the union of masks per cell stay the same. Off by
  /// default: in a complex of cells that do not overlap, two avenues into one cell see
  /// disjoint rays, and on the benchmark's views it pruned nothing (traverse.h).
  bool prune_covered = false;
  /// Join the avenues into one cell whose masks meet along a whole edge and whose union is
  /// convex before going on through the cell's portals (traverse.h, "The merged search"),
  /// so that the pieces an outside sliced by artificial portals parts a view into are
  /// followed once, not once per chain of portals. Every cell and every ray's view stay as
  /// Jones's search finds them; the avenues are fewer and form a graph (an avenue's
  /// `parent` is the first of the avenues its pieces came through). Off: Jones's tree.
  bool merge_pieces = false;
  /// The hull search: the pieces into a cell are joined into their convex hull, whether or
  /// not their union is convex (Mask::hull), so every cell is searched once, through one
  /// mask. Conservative: every ray's cell is found, and perhaps cells no ray reaches; each
  /// mask holds its cell's view and perhaps more (VisibleSet::conservative). A picture that
  /// resolves depth among all the faces found (render_view does for such a set) is the same;
  /// a hidden-line drawing is not, so line drawings take the merged search. Implies merging.
  bool hull_pieces = false;
  /// A perspective search through part of the window only: the picture-plane x from `x0`
  /// to `x1` (a strip of it, searched on its own: strips.h). Unset: the whole window.
  struct Strip {
    double x0, x1;
  };
  std::optional<Strip> strip;
  /// > 0, with hull_pieces: the search is for a half-tone of the camera's width × height
  /// pixels with this many samples a side each (samples_per_side, render/halftone.h), in
  /// the double or float kernel. A polygon covers a sample only where the sample's centre
  /// lies in its clip region, so a piece of view whose bounds (grown by 1/16 of a sample)
  /// hold no sample's centre colours nothing, and nothing beyond it can: it is not followed
  /// (VisibleSet::between_samples counts them). The hull search's picture, resolved by
  /// depth, is the same to the byte; the cells found are fewer (far cells seen through
  /// slivers). Ignored by the other searches, whose masks decide what a sample shows.
  int samples_per_side = 0;
};

/// "jones", "merged" or "hull": the search's name on the command line.
inline const char* search_label(const TraverseParams& p) {
  return p.hull_pieces ? "hull" : p.merge_pieces ? "merged" : "jones";
}

/// The same search with exact masks: the hull search becomes the merged one (what line
/// drawings and anything else that reads masks as the view itself need).
inline TraverseParams exact_masks(TraverseParams p) {
  p.merge_pieces = p.merge_pieces || p.hull_pieces;  // the hull search implies merging
  p.hull_pieces = false;
  return p;
}

/// Jones's recursive search of the avenues of sight from `camera.eye`, which lies in
/// cell `eye_cell` (closed). Exact convex masks; see mask.h for the representation. An eye
/// on the boundary of its cell (a sheet wall, a doorway's plane, a T-junction) is searched
/// from every cell that holds it, each through the directions that enter it.
VisibleSet find_visible(const CellComplex& complex, const Camera& camera, CellId eye_cell, const TraverseParams& params);
VisibleSet find_visible(const CellComplex& complex, const Camera& camera, CellId eye_cell,
                        Kernel kernel = Kernel::Double);

/// A parallel search from a cut plane (camera.projection == Parallel): every cell the
/// closed plane meets inside the window is seen through its own cross-section (an avenue of
/// depth 0), and the search goes on through portals beyond it, along camera.forward. Rays
/// start on the cut, so nothing on the near side of it is seen. With a parallel camera,
/// find_visible() is this search from the picture plane through the eye.
/// Throws std::invalid_argument when the camera is not parallel or !cut_plane_usable().
VisibleSet find_visible_from_cut(const CellComplex& complex, const Camera& camera, const Plane& cut,
                                 Kernel kernel = Kernel::Double);
VisibleSet find_visible_from_cut(const CellComplex& complex, const Camera& camera, const Plane& cut,
                                 const TraverseParams& params);
/// A cut plane a parallel search can start from: finite, and not parallel to the rays.
bool cut_plane_usable(const Camera& camera, const Plane& cut);

/// The peer a renderer without cells would use: every cell whose bounding box meets the
/// view frustum (tests every cell; no occlusion at all).
std::vector<CellId> frustum_cells(const CellComplex& complex, const Camera& camera);

}  // namespace avenues
