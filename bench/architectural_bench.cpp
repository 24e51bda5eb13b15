// Avenues — the architect's drawings of the generated 100 × 100-room office (issue 20),
// against the z-buffer peer in the same parallel projection (Google Benchmark):
//
//   ./build/bench/avenues_bench --benchmark_filter=Architectural
//
// Target: a plan (storey 0 cut at 1.2 m) or a section (west to east through the middle
// room, looking north) in <= 50 ms, plus
// its export. For each kind: .../visibility is Jones's search from the cut plane
// (find_visible_from_cut, double), .../drawing that search and the drawing
// (draw_architectural: cut outlines, fill, lines beyond; on every core, as the command
// draws, and .../drawing-1-thread on one), .../export_svg and .../export_pdf
// the drawing put on paper, and .../llvmpipe Mesa's llvmpipe drawing every opaque triangle
// of the building with a z-buffer in the same parallel projection (glOrtho from the cut
// plane), on a picture of the same size. The plan is drawn at 1:500 (4 px a paper mm).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "bench/llvmpipe_peer.h"
#include "cells/build_cells.h"
#include "plans/generate.h"
#include "render/architectural_drawing.h"
#include "render/drawing.h"
#include "render/scene_objects.h"
#include "visibility/visible_set.h"

using namespace avenues;

namespace {

constexpr double kPxPerM = 4 * 1000 / 500.0;  // 1:500

struct Office {
  CellComplex complex;
  LineScene scene;
  std::map<std::string, ArchitecturalView> views;
};

const Office& office() {
  static Office* o = [] {
    auto* of = new Office;
    of->complex = build_cells(parse_plan(generate_office_toml(100, 100), "office 100x100"));
    of->scene = prepare_line_scene(of->complex);
    of->views["plan"] = plan_view(of->complex, 0, 1.2, kPxPerM);
    const Box3 b = building_bounds(of->complex);
    // Across the middle, through the middle of the room there (not along a wall).
    const Vec2 mid{0.5 * (b.lo.x + b.hi.x), 0.5 * (b.lo.y + b.hi.y)};
    double y = mid.y, best = HUGE_VAL;
    for (const Cell& cell : of->complex.cells) {
      const Vec2 m = centroid(cell.footprint);
      if (cell.kind == CellKind::Room && length(m - mid) < best) best = length(m - mid), y = m.y;
    }
    of->views["section"] = section_view(of->complex, {b.lo.x - 1, y}, {b.hi.x + 1, y}, kPxPerM);
    return of;
  }();
  return *o;
}

void visibility(benchmark::State& state, const std::string& kind) {
  const Office& o = office();
  const ArchitecturalView& v = o.views.at(kind);
  VisibleSet vs;
  for (auto _ : state) {
    vs = find_visible_from_cut(o.complex, v.camera, v.cut);
    benchmark::DoNotOptimize(vs.avenues.data());
  }
  state.counters["cells_cut"] = double(vs.cut_cells.size());
  state.counters["visible"] = double(vs.cells.size());
  state.counters["avenues"] = double(vs.avenues.size());
  state.counters["pixels"] = double(v.camera.width) * v.camera.height;
}

void drawing(benchmark::State& state, const std::string& kind, int threads) {
  const Office& o = office();
  const ArchitecturalView& v = o.views.at(kind);
  ArchitecturalOptions options = v.options;
  options.threads = threads;
  size_t lines = 0;
  for (auto _ : state) {
    const VisibleSet vs = find_visible_from_cut(o.complex, v.camera, v.cut);
    const Drawing d = draw_architectural(o.complex, o.scene, v.camera, v.cut, vs, options);
    lines = d.strokes.size();
    benchmark::DoNotOptimize(d.strokes.data());
  }
  state.counters["lines"] = double(lines);
}

void export_as(benchmark::State& state, const std::string& kind, const std::string& ext) {
  const Office& o = office();
  const ArchitecturalView& v = o.views.at(kind);
  const Drawing d =
      draw_architectural(o.complex, o.scene, v.camera, v.cut, find_visible_from_cut(o.complex, v.camera, v.cut), v.options);
  size_t bytes = 0;
  for (auto _ : state) bytes = encode_drawing(d, "office" + ext).bytes.size();
  state.counters["bytes"] = double(bytes);
}

void llvmpipe(benchmark::State& state, const std::string& kind) {
  const Office& o = office();
  const ArchitecturalView& v = o.views.at(kind);
  static auto* peers = new std::map<std::string, std::unique_ptr<LlvmpipePeer>>;
  auto& peer = (*peers)[kind];
  if (!peer) {
    peer = std::make_unique<LlvmpipePeer>(v.camera.width, v.camera.height);
    peer->upload(o.complex, {});
  }
  for (auto _ : state) peer->draw(v.camera);
  state.counters["triangles"] = double(peer->triangles());
  state.counters["pixels"] = double(v.camera.width) * v.camera.height;
}

int register_all() {
  for (const std::string kind : {"plan", "section"}) {
    const std::string base = "Architectural/office100x100/" + kind;
    benchmark::RegisterBenchmark((base + "/visibility").c_str(), [kind](benchmark::State& s) { visibility(s, kind); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(5)->ReportAggregatesOnly(true);
    // As `avenues drawing` draws (every core), and its one-thread peer.
    benchmark::RegisterBenchmark((base + "/drawing").c_str(), [kind](benchmark::State& s) { drawing(s, kind, 0); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(5)->ReportAggregatesOnly(true);
    benchmark::RegisterBenchmark((base + "/drawing-1-thread").c_str(), [kind](benchmark::State& s) { drawing(s, kind, 1); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(5)->ReportAggregatesOnly(true);
    for (const std::string ext : {".svg", ".pdf"})
      benchmark::RegisterBenchmark((base + "/export_" + ext.substr(1)).c_str(),
                                   [kind, ext](benchmark::State& s) { export_as(s, kind, ext); })
          ->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(5)->ReportAggregatesOnly(true);
    benchmark::RegisterBenchmark((base + "/llvmpipe").c_str(), [kind](benchmark::State& s) { llvmpipe(s, kind); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(5)->ReportAggregatesOnly(true);
  }
  return 0;
}

}  // namespace

const int registered_architectural = register_all();
