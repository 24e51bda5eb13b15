// Avenues — how fast hidden-line drawings are made and written (Google Benchmark).
//
//   ./build/bench/avenues_bench --benchmark_filter='Lines|DrawingExport'
//
// Targets: the line set of one view (render/view_lines.h: clipping to the masks, merging,
// weights, furniture; the scene prepared once, no file written) <= 50 µs median per view
// on the bundled plans at 1920x1080; the export of a 10,000-stroke drawing to each format
// (encoding and the atomic write) <= 50 ms.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <random>

#include "cells/build_cells.h"
#include "render/drawing.h"
#include "render/view_lines.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

/// A plan's complex and drawing scene, built once per process.
struct Prepared {
  CellComplex complex;
  LineScene scene;
};
const Prepared& prepared(const std::string& plan) {
  static std::map<std::string, std::unique_ptr<Prepared>> cache;
  auto& slot = cache[plan];
  if (!slot) {
    slot = std::make_unique<Prepared>();
    slot->complex = build_cells(read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans" / plan).string()));
    slot->scene = prepare_line_scene(slot->complex);
  }
  return *slot;
}

/// Fixed views, their visible sets found beforehand: the plan's own viewpoint, then eyes
/// inside rooms (seeded) looking in random horizontal directions.
std::vector<std::pair<Camera, VisibleSet>> views(const CellComplex& c, int n) {
  std::vector<std::pair<Camera, VisibleSet>> out;
  auto add = [&](const Camera& cam) {
    const Location at = c.locate(cam.eye);
    if (at.what == Location::What::Cell) out.push_back({cam, find_visible(c, cam, at.cell)});
  };
  const Viewpoint vp = default_viewpoint(c);
  add(Camera::look_at(vp.eye, vp.look, vp.fov_deg, 1920, 1080));
  std::mt19937 rng(1971);
  std::uniform_real_distribution<double> u(0.1, 0.9), yaw(0, 360);
  std::vector<CellId> rooms;
  for (CellId id = 0; id < CellId(c.cells.size()); ++id)
    if (c.cells[size_t(id)].kind == CellKind::Room) rooms.push_back(id);
  while (int(out.size()) < n) {
    const Cell& cell = c.cells[size_t(rooms[std::uniform_int_distribution<size_t>(0, rooms.size() - 1)(rng)])];
    const Vec2 a = cell.footprint[0], b = cell.footprint[1], d = cell.footprint[2];
    const double s = u(rng), t = u(rng) * (1 - s);
    const Vec2 p = a + s * (b - a) + t * (d - a);
    add(Camera::yaw_pitch({p.x, p.y, cell.z0 + 1.6}, yaw(rng), 0, 60, 1920, 1080));
  }
  return out;
}

/// Google Benchmark reports the mean over iterations; the target is on the median view, so
/// each view's own mean is kept too and their median reported as `median_view_us`.
void view_lines(benchmark::State& state, const std::string& plan) {
  const Prepared& p = prepared(plan);
  const auto vs = views(p.complex, 64);
  std::vector<double> micros(vs.size(), 0), runs(vs.size(), 0);
  size_t i = 0;
  double strokes = 0;
  for (auto _ : state) {
    const size_t k = i++ % vs.size();
    const auto t0 = std::chrono::steady_clock::now();
    Drawing d = draw_view(p.complex, p.scene, vs[k].first, vs[k].second);
    benchmark::DoNotOptimize(d);
    micros[k] += std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    runs[k] += 1;
    strokes += double(d.strokes.size());
  }
  std::vector<double> per_view;
  for (size_t k = 0; k < vs.size(); ++k)
    if (runs[k] > 0) per_view.push_back(micros[k] / runs[k]);
  std::sort(per_view.begin(), per_view.end());
  if (!per_view.empty()) state.counters["median_view_us"] = per_view[per_view.size() / 2];
  state.counters["strokes"] = benchmark::Counter(strokes, benchmark::Counter::kAvgIterations);
}

/// 10,000 strokes of both weights and layers on a 1920 × 1080 page, scattered the way a
/// large drawing's are: many short, some long.
const Drawing& big_drawing() {
  static const Drawing d = [] {
    Drawing dr;
    dr.width = 1920;
    dr.height = 1080;
    std::mt19937 rng(10000);
    std::uniform_real_distribution<double> x(0, 1920), y(0, 1080), angle(0, 6.283185307179586);
    std::exponential_distribution<double> len(1 / 40.0);
    for (int k = 0; k < 10000; ++k) {
      const Vec2 a{x(rng), y(rng)};
      const double l = len(rng), t = angle(rng);
      dr.strokes.push_back({a, a + Vec2{l * std::cos(t), l * std::sin(t)}, k % 3 ? Weight::Crease : Weight::Outline,
                            k % 7 ? Layer::Architecture : Layer::Furniture});
    }
    return dr;
  }();
  return d;
}

void export_drawing(benchmark::State& state, const std::string& ext) {
  const fs::path dir = fs::temp_directory_path() / ("avenues-bench-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / ("drawing" + ext)).string();
  const Drawing& d = big_drawing();
  double penup = 0;
  for (auto _ : state) {
    const DrawingStats st = write_drawing(d, path);
    penup = st.penup_mm_after;
    benchmark::DoNotOptimize(st);
  }
  state.counters["bytes"] = double(fs::file_size(path));
  if (penup > 0) state.counters["penup_mm"] = penup;
  fs::remove_all(dir);
}

int register_all() {
  for (const char* plan : {"jones-house.toml", "two-storey-house.toml", "office-corridor.toml", "curved-walls.toml",
                           "furnished-room.toml"})
    benchmark::RegisterBenchmark((std::string("Lines/") + plan).c_str(),
                                 [plan](benchmark::State& s) { view_lines(s, plan); })
        ->Unit(benchmark::kMicrosecond);
  for (const char* ext : {".svg", ".pdf", ".eps", ".dxf", ".hpgl"})
    benchmark::RegisterBenchmark((std::string("DrawingExport/10000_strokes/") + (ext + 1)).c_str(),
                                 [ext](benchmark::State& s) { export_drawing(s, ext); })
        ->Unit(benchmark::kMillisecond);
  return 0;
}
const int registered = register_all();

}  // namespace
