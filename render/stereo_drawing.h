// Avenues — a stereo pair on paper (Jones 1971, Fig. 14: "a stereoscopic pair").
//
// The two eyes' drawings (visibility/stereo.h gives their cameras) go either side by side
// in one drawing — left eye's view on the left for parallel viewing, on the right for
// cross-eyed viewing — or into two files named after the one asked for.
#pragma once

#include <array>
#include <string>

#include "render/drawing.h"
#include "visibility/stereo.h"

namespace avenues {

/// `left` at x in [0, left.width), `right` beside it; the page is as tall as the taller.
Drawing side_by_side(const Drawing& left, const Drawing& right);

/// "dir/view.svg" → {"dir/view-left.svg", "dir/view-right.svg"}.
std::array<std::string, 2> stereo_pair_paths(const std::string& path);

/// Writes the pair as `layout` says: one file at `path` (parallel, cross) or two (pair, see
/// stereo_pair_paths; both encoded before either is written). Stats are summed over files.
DrawingStats write_stereo_drawing(const Drawing& left, const Drawing& right, StereoLayout layout,
                                  const std::string& path, const PageOptions& page = {});

}  // namespace avenues
