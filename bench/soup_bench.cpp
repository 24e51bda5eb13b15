// Avenues — how fast a mesh scene's free space is decomposed: the soup BSP (the default,
// cells/soup_bsp.h) against the former Nef path, in one run (Google Benchmark).
//
//   ./build/bench/avenues_bench --benchmark_filter='soup/'
//
// Targets (docs/PERFORMANCE.md): the Viking room (3,828 faces, not closed) in <= 5 s; the
// duplex IFC model read as a soup (Assimp's triangles, 12,718) in <= 10 s; on a
// k x k grid of open boxes (k = 4..64, 10 k^2 triangles) the time per triangle growing no
// faster than log n. The Nef path runs once on the Viking room and on the small grids
// (it takes minutes beyond). Counters: triangles, cells, portals, and each stage's seconds;
// `bsp-1-thread` is the same decomposition with TBB held to one thread.
//
// `soup/open-boxes-32/grazing-frame/WxH` is the walkthrough's frame where the 32 x 32 grid
// is hardest: from outside its corner at the height of the walls, looking across the
// diagonal, so that thousands of cells are seen in slivers (the hull search, then the flat
// half-tone on two threads, effects prepared once, the frame's storage reused, as
// `avenues walk` renders).
//
// `soup/open-boxes-64/search-over-the-walls/{whole,strips-2}` is the walk's slowest search
// of the 64 x 64 grid: from outside its corner, the eye at 1.6 m over walls 1 m high, about
// 8,000 cells seen; the hull search of the whole window against the window in two strips
// searched side by side (visibility/strips.h, cut where the whole window's avenues say).
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "bench/walk_frame.h"
#include "cells/mesh_scene.h"
#include "visibility/strips.h"
#include "render/effects.h"
#include "render/halftone.h"
#include "render/scene_objects.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

using namespace avenues;

namespace {

/// A file from outside (AVENUES_OUTSIDE_DIR, set by the build: ../shared/outside).
std::string outside(const std::string& name) { return (std::filesystem::path(AVENUES_OUTSIDE_DIR) / name).string(); }

/// k x k open boxes (a floor and four walls each, 1 m, open at the top) 2 m apart.
Mesh open_boxes(int k) {
  Mesh m;
  m.path = "open-boxes-" + std::to_string(k);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const double x = 2.0 * i, y = 2.0 * j;
      const Vec3 c[8] = {{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0},
                         {x, y, 1}, {x + 1, y, 1}, {x + 1, y + 1, 1}, {x, y + 1, 1}};
      const int b = int(m.vertices.size());
      m.vertices.insert(m.vertices.end(), c, c + 8);
      const int quads[5][4] = {{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
      for (const auto& q : quads) {
        const int poly = m.polygon_of.empty() ? 0 : m.polygon_of.back() + 1;
        m.triangles.push_back({b + q[0], b + q[1], b + q[2]});
        m.triangles.push_back({b + q[0], b + q[2], b + q[3]});
        m.polygon_of.push_back(poly), m.polygon_of.push_back(poly);
      }
    }
  return m;
}

/// Decomposes the meshes once an iteration; `threads` > 0 caps TBB's threads (1: the
/// one-thread peer of the same code, in the same process).
void decompose(benchmark::State& state, const std::vector<Mesh>& meshes, MeshSceneMethod method, int threads) {
  MeshSceneParams params;
  params.method = method;
  std::optional<tbb::global_control> cap;
  if (threads > 0) cap.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
  CellComplex c;
  for (auto _ : state) {
    try {
      c = build_mesh_scene(meshes, params);
    } catch (const std::exception& e) {
      state.SkipWithError(e.what());
      break;
    }
    benchmark::DoNotOptimize(c.cells.data());
  }
  size_t triangles = 0;
  for (const Mesh& m : meshes) triangles += m.triangles.size();
  state.counters["triangles"] = double(triangles);
  state.counters["cells"] = double(c.cells.size());
  state.counters["portals"] = double(c.portals.size());
  state.counters["us_per_triangle"] = benchmark::Counter(1e-6 * double(triangles),
                                                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  // The last iteration's stages [s]: where the time goes.
  for (const StageTime& t : c.timings) state.counters[t.stage + "_s"] = t.seconds;
}

void decompose_bsp(benchmark::State& state, const std::vector<Mesh>& meshes) {
  decompose(state, meshes, MeshSceneMethod::Bsp, 0);
}
void decompose_bsp_one_thread(benchmark::State& state, const std::vector<Mesh>& meshes) {
  decompose(state, meshes, MeshSceneMethod::Bsp, 1);
}
void decompose_nef(benchmark::State& state, const std::vector<Mesh>& meshes) {
  decompose(state, meshes, MeshSceneMethod::Nef, 0);
}

/// One walkthrough frame of the k = 32 grid per iteration (see the top of this file).
void grazing_frame(benchmark::State& state, int width, int height) {
  static const CellComplex c = build_mesh_scene({open_boxes(32)});
  const Camera cam = Camera::yaw_pitch({-1.0, -0.3, 0.6}, 45, 0, 88, width, height);
  const CellId eye_cell = c.locate(cam.eye).cell;
  const std::vector<PlacedObject> objects = place_objects(c);
  TraverseParams search;
  search.merge_pieces = search.hull_pieces = true;
  RenderStats stats;
  VisibleSet visible;
  bench::time_walk_frames(state, c, objects, cam, eye_cell, search, stats, visible);
  state.counters["cells_seen"] = double(visible.cells.size());
  state.counters["visibility_us"] = visible.micros;
  state.counters["polygons"] = double(stats.polygons);
  state.counters["AL_max"] = stats.active_max;
}

/// The search over the walls of the k = 64 grid per iteration, in `strips` strips (1: the
/// whole window) on two threads (see the top of this file).
void search_over_the_walls(benchmark::State& state, int strips) {
  static const CellComplex c = build_mesh_scene({open_boxes(64)});
  const Camera cam = Camera::yaw_pitch({-1.0, -0.3, 1.6}, 44, 0, 88.8, 320, 180);
  const CellId eye_cell = c.locate(cam.eye).cell;
  TraverseParams search;
  search.merge_pieces = search.hull_pieces = true;
  const VisibleSet whole = find_visible(c, cam, eye_cell, search);
  const std::vector<double> edges = strip_edges(cam, strips, &whole);
  VisibleSet visible;
  for (auto _ : state) {
    visible = find_visible_in_strips(c, cam, eye_cell, search, edges, 2);
    benchmark::DoNotOptimize(visible.avenues.data());
  }
  state.counters["cells_seen"] = double(visible.cells.size());
  state.counters["avenues"] = double(visible.avenues.size());
}

[[maybe_unused]] const bool registered = [] {
  std::vector<Mesh> viking;
  try {
    viking.push_back(load_mesh(outside("meshes/viking-room/viking_room.obj")));
  } catch (const std::exception&) {
  }
  if (!viking.empty()) {
    benchmark::RegisterBenchmark("soup/viking-room/bsp", decompose_bsp, viking)->Unit(benchmark::kSecond)->Iterations(1);
    benchmark::RegisterBenchmark("soup/viking-room/bsp-1-thread", decompose_bsp_one_thread, viking)
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark("soup/viking-room/nef", decompose_nef, viking)
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
  }
  std::vector<Mesh> duplex;
  try {
    duplex.push_back(load_mesh(outside("ifc/duplex.ifc")));
  } catch (const std::exception&) {
  }
  if (!duplex.empty()) {
    benchmark::RegisterBenchmark("soup/duplex/bsp", decompose_bsp, duplex)->Unit(benchmark::kSecond)->Iterations(1);
    benchmark::RegisterBenchmark("soup/duplex/bsp-1-thread", decompose_bsp_one_thread, duplex)
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
  }
  for (int k : {4, 8, 16, 32, 64}) {
    const std::vector<Mesh> boxes{open_boxes(k)};
    benchmark::RegisterBenchmark(("soup/open-boxes-" + std::to_string(k) + "/bsp").c_str(), decompose_bsp, boxes)
        ->Unit(benchmark::kSecond)
        ->Iterations(1);
    if (k <= 8)
      benchmark::RegisterBenchmark(("soup/open-boxes-" + std::to_string(k) + "/nef").c_str(), decompose_nef, boxes)
          ->Unit(benchmark::kSecond)
          ->Iterations(1);
  }
  for (const auto& [w, h] : {std::pair{320, 180}, std::pair{1280, 720}})
    benchmark::RegisterBenchmark(
        ("soup/open-boxes-32/grazing-frame/" + std::to_string(w) + "x" + std::to_string(h)).c_str(),
        [w = w, h = h](benchmark::State& s) { grazing_frame(s, w, h); })
        ->Unit(benchmark::kMillisecond)
        ->Repetitions(5)
        ->ReportAggregatesOnly(true);
  for (int strips : {1, 2})
    benchmark::RegisterBenchmark(
        strips == 1 ? "soup/open-boxes-64/search-over-the-walls/whole" : "soup/open-boxes-64/search-over-the-walls/strips-2",
        [strips](benchmark::State& s) { search_over_the_walls(s, strips); })
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Repetitions(5)
        ->ReportAggregatesOnly(true);
  return true;
}();

}  // namespace
