// Avenues — frames timed as `avenues walk` renders them (app/cmd_walk.cpp), for the
// benchmarks of walkthrough frames (halftone_bench.cpp, soup_bench.cpp).
#pragma once

#include <vector>

#include <benchmark/benchmark.h>

#include "render/effects.h"
#include "render/halftone.h"
#include "render/scene_objects.h"
#include "visibility/visible_set.h"

namespace avenues::bench {

/// One frame per iteration from `cam` in `eye_cell`: the search for the visible set, then
/// the flat half-tone on two threads, the effects decided (and the lamps' shadows cast)
/// once before the first frame and the frame's storage kept between frames, as the
/// walkthrough does. The last frame's statistics go to `stats`, its visible set to `visible`.
inline void time_walk_frames(benchmark::State& state, const CellComplex& c, const std::vector<PlacedObject>& objects,
                             const Camera& cam, CellId eye_cell, const TraverseParams& search, RenderStats& stats,
                             VisibleSet& visible) {
  HalftoneOptions options;
  options.threads = 2;
  const SceneEffects effects = prepare_effects(c, objects, options);
  FrameStorage storage;
  Image frame;
  for (auto _ : state) {
    visible = find_visible(c, cam, eye_cell, search);
    render_view(c, objects, effects, cam, visible, options, frame, storage, &stats);
    benchmark::DoNotOptimize(frame.data.data());
    benchmark::ClobberMemory();
  }
}

}  // namespace avenues::bench
