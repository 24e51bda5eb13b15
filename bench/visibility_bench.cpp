// Avenues — how fast the avenues of sight are found (Google Benchmark).
//
//   ./build/bench/avenues_bench --benchmark_filter=Visibility
//
// Targets (docs/PERFORMANCE.md): median traversal per view <= 20 µs on the bundled
// plans at 1920x1080, reported beside a brute force that tests every cell against the
// view frustum; flat in building size: the same local view in a 10x10 and a 100x100
// office within 1.3x of each other.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <random>

#include "cells/build_cells.h"
#include "plans/generate.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

/// Complexes are built once per process and shared by the benchmarks.
const CellComplex& complex_of(const std::string& key) {
  static std::map<std::string, std::unique_ptr<CellComplex>> cache;
  auto& slot = cache[key];
  if (!slot) {
    Plan p = key.rfind("office:", 0) == 0
                 ? parse_plan(generate_office_toml(std::stoi(key.substr(7)), std::stoi(key.substr(7))), key)
                 : read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans" / key).string());
    slot = std::make_unique<CellComplex>(build_cells(p));
  }
  return *slot;
}

/// Fixed views: eyes inside rooms (seeded), looking in random horizontal directions.
std::vector<std::pair<Camera, CellId>> views(const CellComplex& c, int n) {
  std::mt19937 rng(1971);
  std::vector<std::pair<Camera, CellId>> out;
  std::uniform_real_distribution<double> u(0.1, 0.9), yaw(0, 360);
  std::vector<CellId> rooms;
  for (CellId id = 0; id < CellId(c.cells.size()); ++id)
    if (c.cells[size_t(id)].kind == CellKind::Room) rooms.push_back(id);
  while (int(out.size()) < n) {
    const Cell& cell = c.cells[size_t(rooms[std::uniform_int_distribution<size_t>(0, rooms.size() - 1)(rng)])];
    Vec2 a = cell.footprint[0], b = cell.footprint[1], d = cell.footprint[2];
    double s = u(rng), t = u(rng) * (1 - s);
    Vec2 p = a + s * (b - a) + t * (d - a);
    Vec3 eye{p.x, p.y, cell.z0 + 1.6};
    Location loc = c.locate(eye);
    if (loc.what != Location::What::Cell) continue;
    out.push_back({Camera::yaw_pitch(eye, yaw(rng), 0, 60, 1920, 1080), loc.cell});
  }
  return out;
}

void traverse(benchmark::State& state, const std::string& key, Kernel kernel) {
  const CellComplex& c = complex_of(key);
  auto vs = views(c, 64);
  size_t i = 0;
  double cells = 0;
  for (auto _ : state) {
    const auto& [cam, cell] = vs[i++ % vs.size()];
    VisibleSet v = find_visible(c, cam, cell, kernel);
    cells += double(v.cells.size());
    benchmark::DoNotOptimize(v);
  }
  state.counters["visible_cells"] = benchmark::Counter(cells, benchmark::Counter::kAvgIterations);
  state.counters["cells"] = double(c.cells.size());
}

void brute_force(benchmark::State& state, const std::string& key) {
  const CellComplex& c = complex_of(key);
  auto vs = views(c, 64);
  size_t i = 0;
  for (auto _ : state) {
    auto v = frustum_cells(c, vs[i++ % vs.size()].first);
    benchmark::DoNotOptimize(v);
  }
  state.counters["cells"] = double(c.cells.size());
}

/// The same view from the office's first room, whatever the office's size.
void local_view(benchmark::State& state, int size) {
  const CellComplex& c = complex_of("office:" + std::to_string(size));
  Camera cam = Camera::look_at({4, 1.5, 1.6}, {4, 8, 1.2}, 60, 1920, 1080);
  CellId cell = c.locate(cam.eye).cell;
  double cells = 0;
  for (auto _ : state) {
    VisibleSet v = find_visible(c, cam, cell, Kernel::Double);
    cells = double(v.cells.size());
    benchmark::DoNotOptimize(v);
  }
  state.counters["visible_cells"] = cells;
  state.counters["cells"] = double(c.cells.size());
}

int register_all() {
  for (const char* plan : {"jones-house.toml", "two-storey-house.toml", "office-corridor.toml", "curved-walls.toml"}) {
    for (Kernel k : {Kernel::Float, Kernel::Double, Kernel::Filtered, Kernel::Exact})
      benchmark::RegisterBenchmark((std::string("Visibility/") + plan + "/" + to_string(k)).c_str(),
                                   [plan, k](benchmark::State& s) { traverse(s, plan, k); })
          ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark((std::string("Visibility/") + plan + "/brute_force").c_str(),
                                 [plan](benchmark::State& s) { brute_force(s, plan); })
        ->Unit(benchmark::kMicrosecond);
  }
  for (int n : {10, 100})
    benchmark::RegisterBenchmark(("Visibility/local_view/office" + std::to_string(n) + "x" + std::to_string(n)).c_str(),
                                 [n](benchmark::State& s) { local_view(s, n); })
        ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("Visibility/office100x100/brute_force",
                               [](benchmark::State& s) { brute_force(s, "office:100"); })
      ->Unit(benchmark::kMicrosecond);
  return 0;
}
const int registered = register_all();

}  // namespace
