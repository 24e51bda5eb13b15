// Avenues — the hull search of one view on several threads: the window cut into vertical
// strips, each searched on its own, side by side, their avenues joined.
//
// A ray of the picture lies in one strip (or on the line two share), and a strip's search
// is the hull search of the rays through it: every cell such a ray reaches is found, its
// mask holding the ray. So the strips' avenues together hold every ray of the window, as
// the search of the whole window does, and a picture that resolves depth among the faces
// found (render_view, for a conservative set) is the same. Their masks meet along the
// strips' edges as the roots of an eye on its cell's boundary meet: each root's and each
// deeper mask's clip region is grown, so no sample on an edge falls between.
//
// What it costs: the cells near the eye are seen from every strip, and searched once in
// each. Worth it only where a search is long (a view across thousands of cells: an open
// grid of boxes seen over its walls, 7,000 cells in 17 ms at 2.5 µs a cell), not for a
// room's view of 50 µs, which two threads would not shorten by the time it takes to wake
// them. The walkthrough cuts a view in strips when its last frame's search was long, where
// that frame's avenues say the work lies (strip_edges).
#pragma once

#include <vector>

#include "visibility/visible_set.h"

namespace avenues {

/// Where to cut `camera`'s window into `strips` vertical strips: the picture-plane x of
/// the strips - 1 cuts, ascending, strictly inside the window. With `last` (the visible set
/// of a nearby view: the walk's frame before), at the quantiles of its avenues' mask
/// centres, so that each strip holds about as many of them, each weighed by the time an
/// avenue of its strip took when `last` was searched in strips; without it, or with few
/// avenues, evenly. Each strip is at least a tenth of its even width.
std::vector<double> strip_edges(const Camera& camera, int strips, const VisibleSet* last = nullptr);

/// The search of `params` from `camera` in `eye_cell`, for a perspective hull search
/// (TraverseParams::hull_pieces) with the window cut at picture-plane x `edges`
/// (strip_edges) into strips searched side by side on up to `threads` threads
/// (core/thread_arena.h), their avenues joined strip after strip from the left, each in its
/// search's order (VisibleSet::strips says where each begins: a picture can build each
/// strip's part on its own thread too). Any other search, or no edge inside the window:
/// find_visible.
/// `micros` is the time of the whole; the counters are the strips' summed.
VisibleSet find_visible_in_strips(const CellComplex& complex, const Camera& camera, CellId eye_cell,
                                  const TraverseParams& params, const std::vector<double>& edges, int threads);

/// The searches of a walk's frames, one after another from an eye that moves a little
/// between them: each in strips side by side on `threads` threads when the search before
/// it took kFrom or more (and again until one takes under half of it), cut where that
/// search's avenues lay; otherwise find_visible. A search this long is worth the threads:
/// waking a second one costs tens of µs, and a home's search takes 20–300 µs.
class FrameSearches {
 public:
  static constexpr double kFrom = 1000;  ///< [µs]
  /// `threads`: at most this many (0: as many as TBB offers; at most 8 strips). `from`
  /// [µs]: the mark instead of kFrom.
  explicit FrameSearches(int threads = 0, double from = kFrom);
  VisibleSet find(const CellComplex& complex, const Camera& camera, CellId eye_cell, const TraverseParams& params);
  /// A stereo pair's two eyes, side by side on two threads under the same rule (each whole).
  void find_pair(const CellComplex& complex, const Camera& left, CellId left_cell, const Camera& right,
                 CellId right_cell, const TraverseParams& params, VisibleSet& left_set, VisibleSet& right_set);
  /// The threads the last search (or pair) ran on.
  int threads_used() const { return used_; }

 private:
  void judge(double micros);  ///< after a search: whether the next goes side by side
  int threads_ = 1;
  double from_ = kFrom;
  int used_ = 1;              ///< threads_used()
  bool next_on_ = false;      ///< the next search goes side by side
  std::vector<double> edges_;  ///< where the next is cut (strip_edges of the last)
};

}  // namespace avenues
