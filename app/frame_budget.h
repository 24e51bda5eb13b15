// Avenues — the walkthrough's frame budget: while the eye moves, a frame that ran over its
// budget (16.7 ms for 60 fps) makes the next ones cheaper — fewer samples per pixel, then
// (in a plan lit by its own lamps) the light at the eye instead of the lamps and their
// shadows, then fewer pixels (each rendered sample shown as a 2 × 2, then 4 × 4 block), and
// last the objects (furniture, a mesh's detail) beyond 16, then 8 metres of the eye, as CAD
// viewers drop objects while navigating a large model — and frames well under it, for long
// enough, bring detail back one step; when the eye stops, the view is rendered once more at
// full detail (progressive refinement, as a still picture should be). The far objects go
// last because a picture of thousands of them costs their polygons at any resolution.
//
// The walkthrough measures its own frames (from the poll of events to the swap) and tells
// the budget after each one; the budget answers what detail the next frame gets.
#pragma once

#include <cmath>
#include <string>
#include <vector>

namespace avenues::app {

/// What a frame is rendered at.
struct Detail {
  int samples = 1;  ///< half-tone samples per pixel: 1, 4 or 16
  int scale = 1;    ///< window pixels per rendered pixel along each side: 1, 2 or 4
  bool lamps = true;  ///< the plan's own lights (as asked); false: the light at the eye, no shadows
  double reach = HUGE_VAL;  ///< [m] objects farther from the eye are not drawn (HalftoneOptions::objects_within)
  bool operator==(const Detail& o) const {
    return samples == o.samples && scale == o.scale && lamps == o.lamps && reach == o.reach;
  }
  bool operator!=(const Detail& o) const { return !(*this == o); }
};

/// "4 samples", "half resolution, 1 sample": what a reduced detail gives up, for the status line.
inline std::string to_string(const Detail& d) {
  std::string s = d.scale == 1 ? "" : d.scale == 2 ? "half resolution, " : d.scale == 4 ? "quarter resolution, " : "";
  s += std::to_string(d.samples) + (d.samples == 1 ? " sample" : " samples") + (d.lamps ? "" : ", the light at the eye");
  if (d.reach < HUGE_VAL) s += ", no objects beyond " + std::to_string(std::lround(d.reach)) + " m";
  return s;
}

class FrameBudget {
 public:
  /// `budget_ms` <= 0: no budget (every frame at full detail). `samples`: the full detail's.
  /// `lamps`: the full detail is lit by the plan's own point lights (their shadows cast),
  /// which a frame may give up for the light at the eye before it gives up pixels.
  FrameBudget(double budget_ms, int samples, bool lamps = false) : budget_ms_(budget_ms) {
    ladder_.push_back({samples, 1});
    if (samples > 4) ladder_.push_back({4, 1});
    if (samples > 1) ladder_.push_back({1, 1});
    if (lamps) ladder_.push_back({1, 1, false});
    ladder_.push_back({1, 2, !lamps});
    ladder_.push_back({1, 4, !lamps});
    for (const double reach : kReach) ladder_.push_back({1, 4, !lamps, reach});
  }
  /// [m] the last steps' reach of objects.
  static constexpr double kReach[] = {16, 8};

  double budget_ms() const { return budget_ms_; }
  const Detail& full() const { return ladder_.front(); }
  /// The detail of the next frame: full when the eye is still (or there is no budget).
  Detail next(bool moving) const { return moving && budget_ms_ > 0 ? ladder_[level_] : full(); }

  /// After a frame (of `work_ms`) rendered at next(moving): over budget while moving, one
  /// step less detail at once; under half the budget for kSettle frames running, one step
  /// more (so the detail does not flicker between two steps every frame).
  void measured(double work_ms, bool moving) {
    last_ms_ = work_ms;
    if (!moving || budget_ms_ <= 0) return;
    if (work_ms > budget_ms_) {
      if (level_ + 1 < ladder_.size()) ++level_;
      fast_frames_ = 0;
    } else if (work_ms < 0.5 * budget_ms_ && level_ > 0) {
      if (++fast_frames_ >= kSettle) --level_, fast_frames_ = 0;
    } else {
      fast_frames_ = 0;
    }
  }
  /// The same for a frame whose picture is w × h pixels. The first frame at a size is not
  /// counted: it pays once for what the frames after it at that size reuse (the texture
  /// made for it; on the first frame of all, the GL pipeline's start, 60 ms under llvmpipe
  /// where later frames take 5), so it says nothing of what the view costs.
  void measured(double work_ms, bool moving, int w, int h) {
    const bool first_at_size = w != picture_w_ || h != picture_h_;
    picture_w_ = w, picture_h_ = h;
    if (first_at_size) last_ms_ = work_ms;
    else measured(work_ms, moving);
  }
  /// [ms] the last frame measured.
  double last_ms() const { return last_ms_; }

  /// Frames in a row under half the budget before detail comes back one step (half a second at 60 fps).
  static constexpr int kSettle = 30;

 private:
  double budget_ms_;
  std::vector<Detail> ladder_;  ///< from full detail down
  size_t level_ = 0;            ///< into ladder_: the detail while moving
  int fast_frames_ = 0;
  double last_ms_ = 0;
  int picture_w_ = 0, picture_h_ = 0;  ///< the last frame's picture (measured with a size)
};

}  // namespace avenues::app
