// Avenues — what each effect costs, and that a scene calling for none costs nothing extra
// (Google Benchmark).
//
//   ./build/bench/avenues_bench --benchmark_filter=Effects
//
// Target (issue 9): a plan with no lights and no objects renders as fast as the bare
// pipeline, within 3% — render_view deciding the effects on every call (plan_effects, the
// default) against render_view with plan_effects = false, in the same process, same frame.
// Then each effect on against the same scene with it off: depth resolution (a furnished room
// with and without its table), the implicit-line search (searched, as the bare pipeline does,
// or skipped because nothing crosses), shadows (a lamp, per frame with the shadows prepared
// once, or cast every frame, against the same plan lit from the eye), smooth shading, the
// distance law and coloured light. One thread, 1280 × 720, one sample per pixel; the
// visible set is found once, outside the timing.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>

#include "cells/build_cells.h"
#include "render/effects.h"
#include "render/halftone.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

constexpr int kWidth = 1280, kHeight = 720;

enum class Scene {
  House,      ///< jones-house.toml, its lamp taken out: no lights, no objects
  Furnished,  ///< furnished-room.toml: a table, no lights
  Lamp,       ///< furnished-room.toml with a white lamp over the table
  Coloured,   ///< the same lamp, warm white (1, 0.85, 0.7)
};

const CellComplex& scene_complex(Scene s) {
  static std::map<Scene, std::unique_ptr<CellComplex>> cache;
  auto& slot = cache[s];
  if (slot) return *slot;
  const std::string file = s == Scene::House ? "jones-house.toml" : "furnished-room.toml";
  Plan p = read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans" / file).string());
  p.lights.clear();
  if (s == Scene::Lamp || s == Scene::Coloured) {
    Light l;
    l.name = "lamp";
    l.position = {1.6, 1.4, 2.2};
    if (s == Scene::Coloured) l.colour = {1, 0.85, 0.7};
    p.lights.push_back(l);
  }
  slot = std::make_unique<CellComplex>(build_cells(p));
  return *slot;
}

struct Case {
  Scene scene = Scene::House;
  bool plan = true;           ///< HalftoneOptions::plan_effects
  bool prepared = false;      ///< prepare_effects once, outside the timing (the walkthrough's way)
  bool objects = true;        ///< draw the plan's objects
  ShadingModel shading = ShadingModel::Flat;
  double falloff_start = 5;
  Lights lights = Lights::Plan;
};

void effects_frame(benchmark::State& state, Case k) {
  const CellComplex& c = scene_complex(k.scene);
  const Viewpoint vp = default_viewpoint(c);
  const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, kWidth, kHeight);
  const VisibleSet visible = find_visible(c, cam, c.locate(vp.eye).cell);
  const std::vector<PlacedObject> objects = k.objects ? place_objects(c) : std::vector<PlacedObject>{};
  HalftoneOptions o;
  o.threads = 1;
  o.plan_effects = k.plan;
  o.shading.model = k.shading;
  o.shading.falloff_start = k.falloff_start;
  o.lights = k.lights;
  const SceneEffects effects = prepare_effects(c, objects, o);
  Image frame;
  RenderStats stats;
  for (auto _ : state) {
    if (k.prepared) render_view(c, objects, effects, cam, visible, o, frame, &stats);
    else render_view(c, objects, cam, visible, o, frame, &stats);
    benchmark::DoNotOptimize(frame.data.data());
    benchmark::ClobberMemory();
  }
  state.counters["depth_sorts"] = double(stats.depth_sorts);
  state.counters["implicit_lines"] = double(stats.implicit_lines);
  state.counters["light_pieces"] = double(stats.light_pieces);
  state.counters["effects_us"] = stats.effects_us;
}

/// Deciding the effects and casting the shadows alone (once per scene).
void effects_prepare(benchmark::State& state, Scene s) {
  const CellComplex& c = scene_complex(s);
  const std::vector<PlacedObject> objects = place_objects(c);
  const HalftoneOptions o;
  long shadow_polygons = 0;
  for (auto _ : state) {
    const SceneEffects e = prepare_effects(c, objects, o);
    shadow_polygons = e.shadows.lights.empty() ? 0 : e.shadows.lights[0].shadow_polygons;
    benchmark::DoNotOptimize(e.plan.depth.on);
  }
  state.counters["shadow_polygons"] = double(shadow_polygons);
}

void with_repetitions(benchmark::internal::Benchmark* b) {
  b->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(9)->ReportAggregatesOnly(true);
}

Case bare(Case k) {
  k.plan = false;
  return k;
}

}  // namespace

// No lights, no objects: planned against bare (the 3% target).
BENCHMARK_CAPTURE(effects_frame, Effects_none_bare, bare(Case{}))->Apply(with_repetitions);
BENCHMARK_CAPTURE(effects_frame, Effects_none_planned, Case{})->Apply(with_repetitions);
// Depth resolution: the furnished room without and with its table (search skipped: no crossing).
BENCHMARK_CAPTURE(effects_frame, Effects_depth_off, Case{Scene::Furnished, true, false, false})->Apply(with_repetitions);
BENCHMARK_CAPTURE(effects_frame, Effects_depth_on, Case{Scene::Furnished})->Apply(with_repetitions);
// The implicit-line search the bare pipeline makes wherever objects stand.
BENCHMARK_CAPTURE(effects_frame, Effects_depth_on_implicit_search, bare(Case{Scene::Furnished}))->Apply(with_repetitions);
// Shadows: one lamp, lit from the eye instead; shadows prepared once; cast every frame.
BENCHMARK_CAPTURE(effects_frame, Effects_shadows_off,
                  Case{Scene::Lamp, true, true, true, ShadingModel::Flat, 5, Lights::Eye})->Apply(with_repetitions);
BENCHMARK_CAPTURE(effects_frame, Effects_shadows_on, Case{Scene::Lamp, true, true})->Apply(with_repetitions);
BENCHMARK_CAPTURE(effects_frame, Effects_shadows_on_cast_each_frame, Case{Scene::Lamp})->Apply(with_repetitions);
BENCHMARK_CAPTURE(effects_prepare, Effects_prepare_lamp, Scene::Lamp)->Unit(benchmark::kMicrosecond);
// Smooth shading and the distance law (the light at the eye).
BENCHMARK_CAPTURE(effects_frame, Effects_smooth_no_falloff,
                  Case{Scene::House, true, false, true, ShadingModel::Smooth, 0})->Apply(with_repetitions);
BENCHMARK_CAPTURE(effects_frame, Effects_smooth_falloff, Case{Scene::House, true, false, true, ShadingModel::Smooth})
    ->Apply(with_repetitions);
// Coloured light: the lamp warm white against white (shadows prepared once, both).
BENCHMARK_CAPTURE(effects_frame, Effects_coloured_light, Case{Scene::Coloured, true, true})->Apply(with_repetitions);
