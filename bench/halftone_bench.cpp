// Avenues — how fast a half-tone frame of a walkthrough is made (Google Benchmark).
//
//   ./build/bench/avenues_bench --benchmark_filter=Halftone
//
// Target: one 1920 × 1080 frame — Jones's traversal for the visible set, then the scanline
// half-tone (flat shading, one sample per pixel, no dithering) into a frame buffer reused
// from frame to frame — in at most 4 ms (median) on 2 threads, within 3× of the peer
// that only writes the same frame buffer once with memset. Each benchmark reports the
// median of its repetitions and, as counters, what the scan did per frame.
// `halftone_walk_frame` is the same frame as the walkthrough makes it: the effects
// prepared (the lamps' shadows cast) once, the frame's storage kept between frames.
#include <benchmark/benchmark.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <memory>

#include "cells/build_cells.h"
#include "bench/walk_frame.h"
#include "render/halftone.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

constexpr int kWidth = 1920, kHeight = 1080;

const CellComplex& plan_complex(const std::string& name) {
  static std::map<std::string, std::unique_ptr<CellComplex>> cache;
  auto& slot = cache[name];
  if (!slot) slot = std::make_unique<CellComplex>(build_cells(read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans" / name).string())));
  return *slot;
}

/// A plan seen from its own viewpoint at 1920 × 1080, its objects placed.
struct PlanView {
  const CellComplex& c;
  Camera cam;
  CellId eye_cell = kNoCell;
  std::vector<PlacedObject> objects;
  explicit PlanView(const std::string& plan) : c(plan_complex(plan)), objects(place_objects(c)) {
    const Viewpoint vp = default_viewpoint(c);
    cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, kWidth, kHeight);
    eye_cell = c.locate(vp.eye).cell;
  }
};

/// One frame per iteration from the plan's own viewpoint, as a one-shot view makes it:
/// visibility, then the half-tone into the same frame buffer (the effects decided, and
/// the lamps' shadows cast, for each frame).
void halftone_frame(benchmark::State& state, const std::string& plan, ShadingModel shading, int samples) {
  const PlanView v(plan);
  HalftoneOptions options;
  options.threads = 2;
  options.samples = samples;
  options.shading.model = shading;
  Image frame;
  RenderStats stats;
  for (auto _ : state) {
    const VisibleSet visible = find_visible(v.c, v.cam, v.eye_cell);
    render_view(v.c, v.objects, v.cam, visible, options, frame, &stats);
    benchmark::DoNotOptimize(frame.data.data());
    benchmark::ClobberMemory();
  }
  state.counters["avenues"] = double(find_visible(v.c, v.cam, v.eye_cell).avenues.size());
  state.counters["polygons"] = double(stats.polygons);
  state.counters["spans"] = double(stats.spans);
  state.counters["AL_max"] = stats.active_max;
  state.counters["render_us"] = stats.render_us;
}

/// The same frame as the walkthrough makes it (walk_frame.h).
void halftone_walk_frame(benchmark::State& state, const std::string& plan) {
  const PlanView v(plan);
  RenderStats stats;
  VisibleSet visible;
  bench::time_walk_frames(state, v.c, v.objects, v.cam, v.eye_cell, {}, stats, visible);
  state.counters["polygons"] = double(stats.polygons);
  state.counters["render_us"] = stats.render_us;
}

/// The peer: the same frame buffer (1920 × 1080 RGB) written once with memset.
void frame_memset(benchmark::State& state) {
  std::vector<uint8_t> frame(size_t(kWidth) * kHeight * 3, 1);
  int value = 0;
  for (auto _ : state) {
    std::memset(frame.data(), ++value & 0xff, frame.size());
    benchmark::DoNotOptimize(frame.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(frame.size()));
}

void with_repetitions(benchmark::internal::Benchmark* b) {
  b->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(7)->ReportAggregatesOnly(true);
}

}  // namespace

BENCHMARK_CAPTURE(halftone_frame, jones_house, "jones-house.toml", ShadingModel::Flat, 1)->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_frame, office_corridor, "office-corridor.toml", ShadingModel::Flat, 1)->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_frame, curved_walls, "curved-walls.toml", ShadingModel::Flat, 1)->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_frame, two_storey_house, "two-storey-house.toml", ShadingModel::Flat, 1)->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_frame, office_corridor_smooth, "office-corridor.toml", ShadingModel::Smooth, 1)->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_frame, office_corridor_16_samples, "office-corridor.toml", ShadingModel::Flat, 16)->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_frame, two_storey_house_4_samples, "two-storey-house.toml", ShadingModel::Flat, 4)->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_frame, curved_walls_4_samples, "curved-walls.toml", ShadingModel::Flat, 4)->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_walk_frame, jones_house, "jones-house.toml")->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_walk_frame, office_corridor, "office-corridor.toml")->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_walk_frame, curved_walls, "curved-walls.toml")->Apply(with_repetitions);
BENCHMARK_CAPTURE(halftone_walk_frame, two_storey_house, "two-storey-house.toml")->Apply(with_repetitions);
BENCHMARK(frame_memset)->Name("Halftone/frame_memset_peer")->Apply(with_repetitions);
