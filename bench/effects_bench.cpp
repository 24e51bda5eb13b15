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
// distance law and coloured light. Each pair renders the effect off and on frame for frame in
// turn and reports both medians and their ratio (on_over_off), so that the load of a shared
// machine falls on both alike. One thread, 1280 × 720, one sample per pixel; the visible set
// is found once, outside the timing.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

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
  Corridor,   ///< office-corridor.toml, its lamps taken out: no lights, no objects, 24 offices
  Furnished,  ///< furnished-room.toml: a table, no lights
  Lamp,       ///< furnished-room.toml with a white lamp over the table
  Coloured,   ///< the same lamp, warm white (1, 0.85, 0.7)
};

const CellComplex& scene_complex(Scene s) {
  static std::map<Scene, std::unique_ptr<CellComplex>> cache;
  auto& slot = cache[s];
  if (slot) return *slot;
  const std::string file = s == Scene::House      ? "jones-house.toml"
                           : s == Scene::Corridor ? "office-corridor.toml"
                                                  : "furnished-room.toml";
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

/// One way of rendering one scene, set up outside the timing.
class Frame {
 public:
  explicit Frame(Case k) : k_(k), c_(scene_complex(k.scene)) {
    const Viewpoint vp = default_viewpoint(c_);
    cam_ = Camera::look_at(vp.eye, vp.look, vp.fov_deg, kWidth, kHeight);
    visible_ = find_visible(c_, cam_, c_.locate(vp.eye).cell);
    if (k.objects) objects_ = place_objects(c_);
    o_.threads = 1;
    o_.plan_effects = k.plan;
    o_.shading.model = k.shading;
    o_.shading.falloff_start = k.falloff_start;
    o_.lights = k.lights;
    effects_ = prepare_effects(c_, objects_, o_);
  }
  /// [ms] one frame.
  double render() {
    const auto t0 = std::chrono::steady_clock::now();
    if (k_.prepared) render_view(c_, objects_, effects_, cam_, visible_, o_, frame_, &stats_);
    else render_view(c_, objects_, cam_, visible_, o_, frame_, &stats_);
    benchmark::DoNotOptimize(frame_.data.data());
    benchmark::ClobberMemory();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  const RenderStats& stats() const { return stats_; }

 private:
  Case k_;
  const CellComplex& c_;
  Camera cam_;
  VisibleSet visible_;
  std::vector<PlacedObject> objects_;
  HalftoneOptions o_;
  SceneEffects effects_;
  Image frame_;
  RenderStats stats_;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

/// The effect off (a) and on (b), frame for frame in turn, in the same process: the medians
/// of each [ms] and their ratio b / a, so that the load of a shared machine falls on both alike.
void effects_pair(benchmark::State& state, Case a, Case b) {
  Frame fa(a), fb(b);
  std::vector<double> ta, tb;
  bool a_first = true;
  for (auto _ : state) {
    if (a_first) {
      ta.push_back(fa.render());
      tb.push_back(fb.render());
    } else {
      tb.push_back(fb.render());
      ta.push_back(fa.render());
    }
    a_first = !a_first;
  }
  const double ma = median(ta), mb = median(tb);
  state.counters["off_ms"] = ma;
  state.counters["on_ms"] = mb;
  state.counters["on_over_off"] = ma > 0 ? mb / ma : 0;
  state.counters["depth_sorts"] = double(fb.stats().depth_sorts);
  state.counters["light_pieces"] = double(fb.stats().light_pieces);
  state.counters["effects_us"] = fb.stats().effects_us;
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

void pairs(benchmark::internal::Benchmark* b) { b->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(200); }

Case bare(Case k) {
  k.plan = false;
  return k;
}

}  // namespace

// No lights, no objects: bare (a) against planned (b) — the 3% target.
BENCHMARK_CAPTURE(effects_pair, Effects_none_bare_vs_planned, bare(Case{}), Case{})->Apply(pairs);
BENCHMARK_CAPTURE(effects_pair, Effects_none_bare_vs_planned_corridor, bare(Case{Scene::Corridor}), Case{Scene::Corridor})
    ->Apply(pairs);
// Depth resolution: the furnished room without (a) and with (b) its table.
BENCHMARK_CAPTURE(effects_pair, Effects_depth, Case{Scene::Furnished, true, false, false}, Case{Scene::Furnished})
    ->Apply(pairs);
// The implicit-line search: skipped because nothing crosses (a), searched as the bare pipeline does (b).
BENCHMARK_CAPTURE(effects_pair, Effects_implicit_line_search, Case{Scene::Furnished}, bare(Case{Scene::Furnished}))
    ->Apply(pairs);
// Shadows: the lamp's plan lit from the eye (a), by the lamp with shadows prepared once (b).
BENCHMARK_CAPTURE(effects_pair, Effects_shadows,
                  Case{Scene::Lamp, true, true, true, ShadingModel::Flat, 5, Lights::Eye}, Case{Scene::Lamp, true, true})
    ->Apply(pairs);
// Shadows prepared once (a) or cast every frame (b).
BENCHMARK_CAPTURE(effects_pair, Effects_shadows_cast_each_frame, Case{Scene::Lamp, true, true}, Case{Scene::Lamp})
    ->Apply(pairs);
BENCHMARK_CAPTURE(effects_prepare, Effects_prepare_lamp, Scene::Lamp)->Unit(benchmark::kMicrosecond);
// Smooth shading: flat (a) against smooth without the distance law (b), the light at the eye.
BENCHMARK_CAPTURE(effects_pair, Effects_smooth, Case{Scene::House},
                  Case{Scene::House, true, false, true, ShadingModel::Smooth, 0})
    ->Apply(pairs);
// The distance law: smooth without (a) and with (b).
BENCHMARK_CAPTURE(effects_pair, Effects_falloff, Case{Scene::House, true, false, true, ShadingModel::Smooth, 0},
                  Case{Scene::House, true, false, true, ShadingModel::Smooth})
    ->Apply(pairs);
// Coloured light: the lamp white (a) and warm white (b), shadows prepared once.
BENCHMARK_CAPTURE(effects_pair, Effects_coloured_light, Case{Scene::Lamp, true, true}, Case{Scene::Coloured, true, true})
    ->Apply(pairs);
