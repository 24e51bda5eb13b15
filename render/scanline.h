// Avenues — the scanline engine: Wylie's and Bouknight's LINESCAN over convex polygons on
// the raster, delivering "key squares" (spans) where the visible polygon changes.
//
// Bouknight 1969: "the only information necessary for generation of a half-tone image for
// a planar polygon structure is 1) the coefficients of the plane equations of the
// surfaces of the structure and 2) the perspective projections of the edges." So is it
// here: a ScreenPolygon is a convex outline on the raster and its inverse depth 1/Z as an
// affine function of the raster position (Wylie's 1/w; Bouknight's perspective plane
// equation z' = A'x' + B'y' + C' orders depths the same way, z' being affine in 1/Z).
//
// The passes, per picture and per row:
//   1. EdgeTable: every non-horizontal edge, bucket-sorted by the first row it crosses
//      (Bouknight's Appendix 1: one "bin" per scanline, and a bin for edges starting
//      above the window, which preset the active list when scanning begins; here any
//      band of rows begins that way, so bands can be scanned in parallel); and every
//      polygon by the rows it spans (Wylie's y-entry and y-exit tables).
//   2. The active edge list: the edges crossing the current row, each stepping its
//      crossing exactly from row to row (Bouknight's X = X + DX, in integers).
//   3. Per polygon on the row (Wylie's y-occupied table), its span: right of its left
//      edges, left of its right edges, and inside its clip region (the avenue's mask).
//   4. The span ends in scan order — two lists, by start and by end, kept sorted from row
//      to row by insertion, cheap because spans move little (coherence) — walked left
//      to right with the set of polygons the scan ray is in; at equal x polygons left
//      come before polygons entered (Bouknight: "lines ... where the scan ray will leave
//      a polygon will appear before the lines where the ray enters a polygon"). Between
//      two ends that set is fixed; the visible polygon is decided there (resolve, below)
//      and emitted as spans, consecutive runs of one polygon merged.
//
// Rasterization conventions (as in llvmpipe's lp_setup_tri.c, written down):
//   - Vertices are fixed point with kSubpixelBits = 8 fractional bits: 1/256 sample.
//     The scene builder rounds each vertex once; all coverage arithmetic after that is
//     exact 64-bit integer arithmetic, so an edge shared by two polygons (the same two
//     fixed-point end points) is the same line for both.
//   - A sample is taken at its centre: sample (i, j) at (i + ½, j + ½).
//   - Fill rule "top-left", with half-open spans: a sample is inside a polygon when its
//     centre lies inside, or on a left edge, or on a top (horizontal) edge. In the row
//     direction an edge is active on rows whose centre y lies in [y_top, y_bottom); along
//     a row a polygon covers the samples [L, R), L the first sample whose centre is at or
//     right of every left edge, R the first at or right of a right edge. Two polygons
//     sharing an edge therefore cover every sample near it exactly once.
//   - Coordinates stay within ±2^20 samples (the scene builder clips to a guard band),
//     which keeps every product below 2^62.
//
// Hidden surfaces (resolve): the polygons a ScreenScene holds are of two roles.
//   - Faces of cells, each in one avenue of sight (group) at a depth of portals (rank).
//     Within one avenue the faces of a convex cell never overlap, and a deeper avenue
//     lies inside the portal it was seen through, so no depth is needed: the face of the
//     deepest avenue present is the one seen (a portal's face is drawn whole; what lies
//     beyond shows through because it is deeper).
//   - Objects (meshes), which resolve depth against each other and the face of their own
//     group only: an object hides its cell's face when nearer than it, and then hides
//     deeper avenues too. A scene of meshes alone is one group of objects, resolved in
//     full by Bouknight's depth sort.
//   Depth sorts happen only where two or more polygons compete; where the nearest polygon
//   changes between two span ends an "implicitly defined line" is crossed and the span is
//   split where the two planes meet (Bouknight's Appendix 2) — at the first sample whose
//   centre sees the new polygon nearer, found from the pair's difference of 1/Z, an affine
//   function evaluated the same way everywhere, so the split moves monotonically along the
//   row and nearly parallel planes do not speckle.
#pragma once

#include <cstdint>
#include <vector>

#include "core/cache_lines.h"
#include "render/raster_map.h"

namespace avenues {

constexpr int kSubpixelBits = 8;
constexpr int64_t kSubpixelOne = int64_t(1) << kSubpixelBits;  ///< fixed-point units per sample
constexpr int64_t kRasterLimit = int64_t(1) << 20;             ///< [samples] |coordinate| bound

/// A point on the raster in fixed point: 1/256 sample.
struct FixedPoint {
  int64_t x = 0, y = 0;
  friend bool operator==(FixedPoint a, FixedPoint b) { return a.x == b.x && a.y == b.y; }
};

/// The sign of an outline's area, exactly (as the edge table takes it): 1 counter-clockwise
/// in (x, y) as stored, −1 clockwise, 0 none.
int orientation(const std::vector<FixedPoint>& outline);

enum class PolygonRole : uint8_t {
  Face,    ///< a face of a cell: no depth within its group; deeper groups (rank) win
  Object,  ///< a mesh polygon: depth-resolved within its group, in front of deeper groups
};

struct ScreenPolygon {
  std::vector<FixedPoint> outline;  ///< convex, either orientation, >= 3 vertices
  RasterPlane depth;                ///< 1/Z [1/m] at raster position [samples]; larger is nearer
  int32_t clip = -1;                ///< index into the scene's clip regions; -1: the whole raster
  int32_t group = 0;                ///< avenue of sight (objects resolve depth within it), >= 0
  int32_t rank = 0;                 ///< the avenue's depth in portals, >= 0
  PolygonRole role = PolygonRole::Object;
};

/// A convex region of the raster that cuts the spans of the polygons referring to it.
struct ClipRegion {
  std::vector<FixedPoint> outline;  ///< convex, either orientation
};

/// A key square run: samples [x0, x1) of one row see `polygon` (-1: nothing, background).
struct Span {
  int32_t x0 = 0, x1 = 0;
  int32_t polygon = -1;
};

/// The spans of one row, in storage of the scanning thread's own (core/cache_lines.h).
using SpanRow = OwnLines<Span>;

/// What the scan did, in Bouknight's terms.
struct ScanCounters {
  long scanlines = 0;          ///< rows with a non-empty active edge list
  long intersections = 0;      ///< edge crossings processed: active edges summed over those rows
  long spans = 0;              ///< key squares emitted (background runs included)
  long implicit_lines = 0;     ///< span splits where two polygons' depth order changes
  long depth_sorts = 0;        ///< nearest-polygon searches among two or more polygons
  long depth_comparisons = 0;  ///< pairwise 1/Z comparisons made by those searches
  int active_max = 0;          ///< most edges in the active list on one row
  void add(const ScanCounters& o);
};

/// The edges of a picture, bucket-sorted by first row (Bouknight's Appendix 1), and its
/// polygons by the rows they span (Wylie's y-entry and y-exit tables). Built once per
/// picture; read by any number of ScanlineEngines.
///
/// An edge that cannot matter is left out: one bounding its polygon on the left while
/// lying wholly left of the polygon's clip region (or of the window), or on the right
/// while wholly right of it, since the region cuts the span tighter anyway. A polygon
/// seen through a small mask then often has no edge at all, and costs the scan nothing but
/// its entry in the polygon table; one wholly beside its region is left out altogether. So
/// is every edge of a clip region no polygon refers to.
class EdgeTable {
 public:
  EdgeTable(int width, int height, const std::vector<ScreenPolygon>& polygons, const std::vector<ClipRegion>& clips);
  /// An empty table, for build().
  EdgeTable() = default;
  /// Makes this the table of another picture, reusing the storage of the last one.
  void build(int width, int height, const std::vector<ScreenPolygon>& polygons, const std::vector<ClipRegion>& clips);

  long edge_count() const { return long(edges_.size()); }

 private:
  friend class ScanlineEngine;
  friend class SecondaryScan;
  struct Edge {
    int64_t x0 = 0, y0 = 0;  ///< upper end point [1/256 sample]
    int64_t dx = 0, dy = 0;  ///< to the lower end point; dy > 0
    int32_t first_row = 0;   ///< first row whose centre is at or below y0
    int32_t end_row = 0;     ///< first row whose centre is at or below the lower end (exclusive)
    int32_t owner = 0;       ///< polygon index, or clip region index when `clip`
    bool clip = false;
    bool left = false;       ///< bounds its owner's spans on the left (else on the right)
  };
  /// Rows [first, end) of the raster.
  struct Rows {
    int32_t first = 0, end = 0;
  };
  /// Adds the outline's edges that matter within [x_lo, x_hi] (fixed point); returns the
  /// rows the whole outline spans within [row0, row1).
  Rows add_outline(const std::vector<FixedPoint>& outline, int32_t owner, bool clip, Rows within, int64_t x_lo,
                   int64_t x_hi);

  int width_ = 0, height_ = 0;
  const std::vector<ScreenPolygon>* polygons_ = nullptr;
  size_t clip_count_ = 0;
  std::vector<Edge> edges_;                 ///< sorted by first_row (bucket order)
  std::vector<Edge> unsorted_;              ///< build(): the edges before the sort
  std::vector<int32_t> row_start_;          ///< height + 1 offsets into edges_: the bucket of each row
  std::vector<Rows> polygon_rows_;          ///< per polygon: the rows it spans (first >= end: none)
  std::vector<int32_t> polygon_clip_;       ///< per polygon: its clip region (-1: none), kept close at hand
  std::vector<int32_t> polygon_order_;      ///< polygons sorted by first row
  std::vector<int32_t> polygon_row_start_;  ///< height + 1 offsets into polygon_order_
  std::vector<int32_t> polygons_ending_;    ///< height + 1: how many polygons end before each row (Wylie's y-exit table)
};

/// Scans rows one after the other from any starting row. One per thread.
class ScanlineEngine {
 public:
  /// `implicit_lines` false: the scene has no interpenetrating polygons (effects.h), so the
  /// nearest polygon at the left end of a run is the nearest all along it and the search for
  /// implicitly defined lines is skipped (one depth sort per run instead of two or more).
  explicit ScanlineEngine(const EdgeTable& table, bool implicit_lines = true);
  /// An engine for no table yet, for reset().
  ScanlineEngine() = default;
  /// Makes this a fresh engine for `table`, reusing the storage of the last one.
  void reset(const EdgeTable& table, bool implicit_lines = true);

  /// Places the scan at `row`: the edges already crossing it enter the active list.
  void start(int row);
  /// The spans of the current row, left to right, tiling [0, width); then moves down a row.
  /// The reference holds until the next scan or start.
  const SpanRow& scan();
  /// Only each polygon's own span on the current row (coverage()), no hidden surfaces; then
  /// moves down a row. The secondary scan's step.
  void scan_coverage();
  const ScanCounters& counters() const { return counters_; }
  /// Whether the row last scanned was the one before it again: no edge began, ended or
  /// stepped to another sample, no polygon began or ended, and the row before was resolved
  /// without depth (which changes from row to row), so its spans are the same; they were
  /// not looked for again. (A level eye sees walls' edges upright, and the rows between the
  /// lowest ceiling edge and the highest floor edge are often all alike.)
  bool repeated() const { return repeated_; }
  /// Each polygon's own span on the row last scanned, before hidden surfaces were
  /// resolved (for checking coverage: the fill rule's "exactly once").
  const SpanRow& coverage() const { return coverage_; }

 private:
  struct ActiveEdge {
    int64_t crossing;   ///< first sample whose centre is at or right of the edge on this row
    int64_t remainder;  ///< crossing·den − numerator, in [0, den): the exact fraction left over
    int64_t den;        ///< 256·dy
    int64_t step_q, step_r;  ///< 256·dx = step_q·den + step_r, 0 <= step_r < den
    int32_t end_row, owner;
    bool clip, left;
  };
  /// What the current row's edges say of one polygon or clip region.
  struct Extent {
    int32_t row = -1;  ///< the row these bounds belong to; another row: no edge, no bound
    int64_t left, right;
    bool has_left, has_right;
  };
  void enter(const EdgeTable::Edge& e, int row);
  void enter_polygon(int32_t p);
  void touch(Extent& x, const ActiveEdge& a);
  /// This row's counters.
  void count_row();
  /// This row's counters, and each polygon's and clip region's extent from its active edges.
  void extents_of_row();
  void spans_of_polygons(bool sort);
  void walk();
  void next_row();
  /// The visible polygon of samples [x0, x1), where the ray is in two or more (inside_).
  void resolve(int32_t x0, int32_t x1);
  void resolve_groups(int32_t x0, int32_t x1, size_t first, int32_t deepest_face, int level);
  void emit(int32_t x0, int32_t x1, int32_t polygon);
  int32_t nearest(const OwnLines<int32_t>& candidates, int32_t x);
  double nearer_by(int32_t p, int32_t q, int32_t x) const;
  int32_t first_nearer(int32_t q, int32_t cur, int32_t from, int32_t last) const;

  const EdgeTable* table_ = nullptr;
  const std::vector<ScreenPolygon>* polygons_ = nullptr;
  int row_ = 0;
  // Written on every row, by this engine's thread alone: in lines of their own.
  OwnLines<ActiveEdge> active_;                 ///< the active edge list
  OwnLines<Extent> polygon_extent_, clip_extent_;
  OwnLines<int32_t> span_left_, span_right_;    ///< per polygon, its span on this row (kNoSpan: none)
  OwnLines<int32_t> on_row_;                    ///< the polygons whose rows include this one, in entry order
  /// The ends of the spans on this row in scan order, each a word: x (32 bits), whether
  /// the ray enters there (1) or leaves (0), the polygon (31 bits).
  OwnLines<uint64_t> ends_;
  static uint64_t span_end(int32_t x, bool enters, int32_t polygon) {
    return uint64_t(uint32_t(x)) << 32 | uint64_t(enters) << 31 | uint64_t(uint32_t(polygon));
  }
  static int32_t end_x(uint64_t end) { return int32_t(end >> 32); }
  static bool end_enters(uint64_t end) { return (end >> 31) & 1; }
  static int32_t end_polygon(uint64_t end) { return int32_t(end & 0x7fffffff); }
  OwnLines<int32_t> entering_;                  ///< spans_of_polygons: the polygons whose spans are new on this row
  OwnLines<uint64_t> entering_ends_, merged_;   ///< their ends; a merge's output
  SpanRow coverage_;
  OwnLines<int32_t> inside_;       ///< polygons the scan ray is in
  OwnLines<int32_t> inside_at_;    ///< per polygon, its index in inside_ (-1: not in)
  OwnLines<int32_t> objects_;      ///< resolve: the objects inside, nearest groups first
  std::vector<OwnLines<int32_t>> candidates_;  ///< resolve: per level of groups
  SpanRow row_spans_;  ///< the spans of the row last scanned, handed out again for a row repeated
  SpanRow* out_ = nullptr;
  double row_centre_ = 0.5;
  bool implicit_lines_ = true;
  bool depth_free_ = false;  ///< the row last resolved was resolved without depth
  /// walk(): per end, the polygon seen from it to the next end on the row last resolved
  /// (kUnresolved: that run was empty there); known when that row was resolved without depth.
  OwnLines<int32_t> seen_after_;
  static constexpr int32_t kUnresolved = -2;
  bool seen_known_ = false;
  bool same_order_ = false;  ///< spans_of_polygons(): the same ends as on the row before, in the same order
  bool repeats_ = false;     ///< next_row(): the row coming is the row last scanned again
  bool repeated_ = false;    ///< repeated()
  ScanCounters counters_;
};

/// Bouknight's secondary scan (Chapter V): "a secondary scan which simply keeps track of
/// which shadows are being pierced by the scan ray at any given point on the scan", run
/// alongside the primary scan over the same rows. Its polygons are the shadow polygons and
/// lit pieces of the surfaces (shadows.h) on the raster, each belonging to one light and one
/// polygon of the primary scan; no depth is needed, since the primary scan has already chosen
/// the polygon a sample sees. Coverage follows the primary scan's conventions exactly (the
/// same fixed point, edges stepped the same way, the top-left rule), so a shadow polygon's
/// edge shared with its polygon's edge bounds both alike: the test per sample is exact.
class SecondaryScan {
 public:
  explicit SecondaryScan(const EdgeTable& pieces);
  /// Makes this a fresh scan of `pieces`, reusing the storage of the last one.
  void reset(const EdgeTable& pieces);
  /// Places the scan at `row`, as ScanlineEngine::start.
  void start(int row);
  /// Finds each piece's samples on the current row, then moves down a row.
  void scan();
  /// Whether the row last scanned was the one before it again (ScanlineEngine::repeated).
  bool repeated() const { return engine_.repeated(); }
  /// Whether piece `piece` has the same samples on the row last scanned as on the row
  /// before it (none on both counts), this scan having scanned both.
  bool unmoved(int32_t piece) const;
  /// The samples [x0, x1) of piece `piece` on the row last scanned (x0 >= x1: none).
  Span span_of(int32_t piece) const {
    return row_of_[size_t(piece)] == row_ ? spans_[size_t(piece)] : Span{0, 0, piece};
  }

 private:
  ScanlineEngine engine_;
  OwnLines<Span> spans_;      ///< per piece, its span on row row_of_[piece]
  OwnLines<int32_t> row_of_;  ///< per piece, the row its span belongs to
  OwnLines<int32_t> moved_on_;  ///< per piece, the last row whose span was not its span on the row before
  int32_t row_ = -1;             ///< the row last scanned
  int32_t next_ = 0;             ///< the row scan() does next
};

}  // namespace avenues
