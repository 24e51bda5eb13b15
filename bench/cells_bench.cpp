// Avenues — how fast the cell complex is built and loaded (Google Benchmark).
//
//   ./build/bench/avenues_bench                      everything
//   ./build/bench/avenues_bench --benchmark_filter=office
//
// Targets (docs/PERFORMANCE.md): each bundled plan builds in < 0.2 s; the 100x100
// office builds in < 10 s and its saved complex loads in < 1 s. Each benchmark
// reports cells, portals and cells per room as counters.
#include <unistd.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "cells/build_cells.h"
#include "plans/generate.h"
#include "plans/plan.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

void set_counters(benchmark::State& state, const CellComplex& c) {
  size_t room_cells = 0;
  for (const Cell& cell : c.cells) room_cells += cell.kind == CellKind::Room;
  state.counters["cells"] = static_cast<double>(c.cells.size());
  state.counters["portals"] = static_cast<double>(c.portals.size());
  state.counters["rooms"] = static_cast<double>(c.rooms.size());
  state.counters["cells_per_room"] =
      c.rooms.empty() ? 0.0 : static_cast<double>(room_cells) / static_cast<double>(c.rooms.size());
}

// A failure (a plan the decomposer rejects) is reported as that benchmark's error,
// and the other benchmarks still run.
void build(benchmark::State& state, const std::shared_ptr<const Plan>& plan) {
  CellComplex c;
  for (auto _ : state) {
    try {
      c = build_cells(*plan);
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      break;
    }
    benchmark::DoNotOptimize(c.cells.data());
  }
  set_counters(state, c);
}

void load(benchmark::State& state, const std::string& path) {
  CellComplex c;
  for (auto _ : state) {
    try {
      c = load_cells(path);
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      break;
    }
    benchmark::DoNotOptimize(c.cells.data());
  }
  set_counters(state, c);
}

/// Reads (or parses) a plan for registration; on failure, registers the error.
std::shared_ptr<const Plan> plan_or_error(const std::string& name, const std::function<Plan()>& read) {
  try {
    return std::make_shared<const Plan>(read());
  } catch (const std::exception& e) {
    std::string what = e.what();
    benchmark::RegisterBenchmark(("build/" + name).c_str(),
                                 [what](benchmark::State& s) {
                                   s.SkipWithError(what.c_str());
                                   for (auto _ : s) {
                                   }
                                 });
    return nullptr;
  }
}

std::vector<fs::path> bundled_plans() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(fs::path(AVENUES_SOURCE_DIR) / "plans"))
    if (e.path().extension() == ".toml") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  for (const fs::path& p : bundled_plans()) {
    auto plan = plan_or_error(p.stem().string(), [&] { return read_plan(p.string()); });
    if (!plan) continue;
    benchmark::RegisterBenchmark(("build/" + p.stem().string()).c_str(),
                                 [plan](benchmark::State& s) { build(s, plan); })
        ->Unit(benchmark::kMillisecond);
  }
  for (int n : {10, 30, 100}) {
    std::string name = "office-" + std::to_string(n) + "x" + std::to_string(n);
    auto plan = plan_or_error(name, [&] { return parse_plan(generate_office_toml(n, n), name + ".toml"); });
    if (!plan) continue;
    auto* b = benchmark::RegisterBenchmark(("build/" + name).c_str(),
                                           [plan](benchmark::State& s) { build(s, plan); });
    b->Unit(n >= 100 ? benchmark::kSecond : benchmark::kMillisecond);
    if (n >= 100) b->Iterations(1);
  }

  // Loading the saved 100x100 office: built and saved once, on first use (untimed),
  // so that a --benchmark_filter leaving it out costs nothing.
  const fs::path saved = fs::temp_directory_path() / ("avenues-bench-" + std::to_string(::getpid()) + ".cells");
  benchmark::RegisterBenchmark("load/office-100x100",
                               [saved](benchmark::State& s) {
                                 static const std::string error = [&]() -> std::string {
                                   try {
                                     Plan office = parse_plan(generate_office_toml(100, 100), "office-100x100.toml");
                                     save_cells(build_cells(office), saved.string());
                                     return "";
                                   } catch (const std::exception& e) {
                                     return e.what();
                                   }
                                 }();
                                 if (!error.empty()) {
                                   s.SkipWithError(error.c_str());
                                   for (auto _ : s) {
                                   }
                                   return;
                                 }
                                 load(s, saved.string());
                               })
      ->Unit(benchmark::kMillisecond);

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::error_code ec;
  fs::remove(saved, ec);
  return 0;
}
