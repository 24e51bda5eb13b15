// Avenues — the half-tone frame against peers drawing the whole building (Google Benchmark):
// Mesa's llvmpipe with a z-buffer, and Embree casting one ray per pixel (issue 8).
//
//   ./build/bench/avenues_bench --benchmark_filter=Llvmpipe
//
// Target (the half-tone issue): Avenues' frame — Jones's traversal for the visible set, then
// the scanline half-tone (flat shading, one sample per pixel, 2 threads) — 20× faster than
// Mesa's llvmpipe (OSMesa, 2 threads) drawing every opaque triangle of the building with a
// 24-bit z-buffer and no culling, on the same 1920 × 1080 view of the generated 100 × 100
// room office. Each plan has three benchmarks, Llvmpipe/<plan>/avenues, .../llvmpipe and
// .../embree (bench/embree_peer.h: a ray per pixel centre into a BVH of every opaque
// triangle, 2 threads); the ratios are the quotients of their medians.
//
// Before timing, each plan's view is checked once: neither picture may be uniform, and the
// llvmpipe item picture (each triangle painted with the face or object polygon it
// came from) is compared pixel by pixel with Avenues' item buffer. Counters: coverage_agree
// (both see something, or both see nothing), face_agree (both see the same cell face or
// object polygon) and surface_agree (the same, counting coplanar faces as one: without
// culling the z-buffer draws both sides of a zero-thickness wall and they z-fight), as
// fractions of the frame's pixels; below 95% coverage or surface agreement, both of the
// plan's benchmarks stop with an error.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "bench/embree_peer.h"
#include "bench/llvmpipe_peer.h"
#include "cells/build_cells.h"
#include "plans/generate.h"
#include "render/halftone.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

constexpr int kWidth = 1920, kHeight = 1080;

/// A plan built once per process (the 100 × 100 office takes seconds), with its objects
/// placed and the view both renderers draw.
struct PlanView {
  CellComplex complex;
  std::vector<PlacedObject> objects;
  Camera camera;
  CellId eye_cell = kNoCell;
};

/// "office:<n>" is the generated n × n office seen from its first room; anything else a
/// bundled plan seen from its own viewpoint.
const PlanView& plan_view(const std::string& key) {
  static auto* cache = new std::map<std::string, std::unique_ptr<PlanView>>;
  auto& slot = (*cache)[key];
  if (!slot) {
    const bool office = key.rfind("office:", 0) == 0;
    const Plan plan = office ? parse_plan(generate_office_toml(std::stoi(key.substr(7)), std::stoi(key.substr(7))), key)
                             : read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans" / key).string());
    auto pv = std::make_unique<PlanView>();
    pv->complex = build_cells(plan);
    pv->objects = place_objects(pv->complex);
    if (office) {
      pv->camera = Camera::look_at({4, 1.5, 1.6}, {4, 8, 1.2}, 60, kWidth, kHeight);
    } else {
      const Viewpoint vp = default_viewpoint(pv->complex);
      pv->camera = Camera::look_at(vp.eye, vp.look, vp.fov_deg, kWidth, kHeight);
    }
    pv->eye_cell = pv->complex.locate(pv->camera.eye).cell;
    slot = std::move(pv);
  }
  return *slot;
}

HalftoneOptions avenues_options() {
  HalftoneOptions o;
  o.threads = 2;
  o.samples = 1;
  o.shading.model = ShadingModel::Flat;
  return o;
}

/// The peer's context with the plan's triangles uploaded, one per plan. Never destroyed:
/// OSMesa contexts are not torn down during static destruction.
LlvmpipePeer& peer_of(const std::string& key) {
  static auto* cache = new std::map<std::string, std::unique_ptr<LlvmpipePeer>>;
  auto& slot = (*cache)[key];
  if (!slot) {
    auto peer = std::make_unique<LlvmpipePeer>(kWidth, kHeight);
    const PlanView& pv = plan_view(key);
    peer->upload(pv.complex, pv.objects);
    std::fprintf(stderr, "llvmpipe peer: GL_RENDERER \"%s\", %s: %ld triangles\n", peer->renderer().c_str(),
                 key.c_str(), peer->triangles());
    slot = std::move(peer);
  }
  return *slot;
}

/// Avenues' picture of a plan's view with its item buffer (which polygon each pixel shows):
/// the same polygons render_view puts on the raster. Computed once per plan.
struct AvenuesItems {
  ScreenScene scene;
  Image picture;
  std::vector<int32_t> items;
  long triangles = 0;  ///< fan triangles of the polygons on the raster
};

HalftoneOptions avenues_options();

const AvenuesItems& avenues_items(const std::string& key) {
  static auto* cache = new std::map<std::string, std::unique_ptr<AvenuesItems>>;
  auto& slot = (*cache)[key];
  if (!slot) {
    const PlanView& pv = plan_view(key);
    auto a = std::make_unique<AvenuesItems>();
    const HalftoneOptions options = avenues_options();
    const VisibleSet visible = find_visible(pv.complex, pv.camera, pv.eye_cell);
    a->scene = screen_scene_of_view(pv.complex, pv.objects, pv.camera, visible, scene_options(options));
    for (const ScreenPolygon& p : a->scene.polygons) a->triangles += long(p.outline.size()) - 2;
    render_scene(a->scene, options, a->picture, nullptr, &a->items);
    slot = std::move(a);
  }
  return *slot;
}

/// What the once-per-plan check found.
struct Check {
  std::string error;          ///< non-empty: a picture was not drawn
  double coverage_agree = 0;  ///< fraction of pixels where both draw something, or both nothing
  double face_agree = 0;      ///< fraction of pixels where both show the same source (or both nothing)
  double surface_agree = 0;   ///< the same, with coplanar faces (a thin wall's two sides) counted as one
  long avenues_triangles = 0; ///< fan triangles of the polygons Avenues put on the raster
  long avenues_covered = 0, peer_covered = 0;  ///< pixels showing something
};

bool uniform(const std::vector<uint8_t>& data, int channels) {
  for (size_t i = size_t(channels); i < data.size(); ++i)
    if (data[i] != data[i % size_t(channels)]) return false;
  return true;
}

/// Compares Avenues' item buffer with a peer's per-pixel sources (either peer: they number
/// sources alike) into k's agreement fractions and covered-pixel counts.
template <class Peer>
void agree(const PlanView& pv, const AvenuesItems& av, const Peer& peer, const std::vector<int32_t>& ids, Check& k) {
  // Two faces are one surface when they lie in one plane, facing either way: the two sides
  // of a zero-thickness wall, which a z-buffer without culling draws both of.
  auto plane_of = [&](int32_t s) -> const Plane* {
    if (s < 0) return nullptr;
    const auto& [kind, cell, face] = peer.sources()[size_t(s)];
    return kind == 0 ? &pv.complex.cells[size_t(cell)].faces[size_t(face)].plane : nullptr;
  };
  auto one_surface = [&](int32_t a, int32_t p) {
    if (a == p) return true;
    const Plane *pa = plane_of(a), *pp = plane_of(p);
    if (!pa || !pp) return false;
    const double s = dot(pa->n, pp->n) > 0 ? 1 : -1;
    return std::fabs(std::fabs(dot(pa->n, pp->n)) - 1) < 1e-9 && std::fabs(pa->d - s * pp->d) < 1e-6;
  };
  long same_coverage = 0, same_face = 0, same_surface = 0;
  k.avenues_covered = k.peer_covered = 0;
  for (size_t i = 0; i < ids.size(); ++i) {
    int32_t a = -1;  // Avenues' source as the peer's source index (-2: one the peer does not have)
    if (av.items[i] >= 0) {
      const PolygonSource& s = av.scene.sources[size_t(av.items[i])];
      a = s.kind == PolygonSource::Kind::Face     ? peer.source_index({0, s.cell, s.face})
          : s.kind == PolygonSource::Kind::Object ? peer.source_index({1, s.mesh, s.polygon})
                                                  : -2;
      if (a == -1) a = -2;
      ++k.avenues_covered;
    }
    const int32_t p = ids[i];
    if (p >= 0) ++k.peer_covered;
    same_coverage += (a != -1) == (p >= 0);
    same_face += a == p;
    same_surface += one_surface(a, p);
  }
  const double n = double(ids.size());
  k.coverage_agree = double(same_coverage) / n;
  k.face_agree = double(same_face) / n;
  k.surface_agree = double(same_surface) / n;
}

const Check& check_of(const std::string& key) {
  static auto* cache = new std::map<std::string, Check>;
  auto found = cache->find(key);
  if (found != cache->end()) return found->second;
  Check& k = (*cache)[key];
  const PlanView& pv = plan_view(key);
  if (pv.eye_cell == kNoCell) {
    k.error = key + ": the eye is not in a cell";
    return k;
  }
  LlvmpipePeer& peer = peer_of(key);
  peer.draw(pv.camera);
  if (uniform(peer.read_rgba(), 4)) k.error = key + ": the llvmpipe frame is uniform";

  const AvenuesItems& av = avenues_items(key);
  k.avenues_triangles = av.triangles;
  if (k.error.empty() && uniform(av.picture.data, av.picture.channels)) k.error = key + ": the Avenues frame is uniform";
  if (av.items.size() != size_t(kWidth) * kHeight) {
    k.error = key + ": Avenues' item buffer is not one sample per pixel";
    return k;
  }
  peer.draw_ids(pv.camera);
  agree(pv, av, peer, peer.read_ids(), k);
  std::fprintf(stderr,
               "llvmpipe peer check %s: agree on coverage %.6f, face %.6f, surface %.6f (pixels covered: "
               "avenues %ld, llvmpipe %ld)\n",
               key.c_str(), k.coverage_agree, k.face_agree, k.surface_agree, k.avenues_covered, k.peer_covered);
  if (k.error.empty() && (k.coverage_agree < 0.95 || k.surface_agree < 0.95))
    k.error = key + ": the llvmpipe and Avenues pictures differ on more than 5% of the pixels";
  return k;
}

/// (a) Avenues: the visible set, then the half-tone into a frame buffer reused from frame to frame.
void avenues_frame(benchmark::State& state, const std::string& key) {
  const PlanView& pv = plan_view(key);
  const Check& check = check_of(key);
  if (!check.error.empty()) {
    state.SkipWithError(check.error.c_str());
    return;
  }
  const HalftoneOptions options = avenues_options();
  Image frame;
  RenderStats stats;
  for (auto _ : state) {
    const VisibleSet visible = find_visible(pv.complex, pv.camera, pv.eye_cell);
    render_view(pv.complex, pv.objects, pv.camera, visible, options, frame, &stats);
    benchmark::DoNotOptimize(frame.data.data());
    benchmark::ClobberMemory();
  }
  state.counters["polygons"] = double(stats.polygons);
  state.counters["triangles"] = double(check.avenues_triangles);
  state.counters["pixels"] = double(stats.pixels);
  state.counters["frame_pixels"] = double(kWidth) * kHeight;
}

/// (b) llvmpipe: the whole building through the z-buffer, every frame.
void llvmpipe_frame(benchmark::State& state, const std::string& key) {
  const PlanView& pv = plan_view(key);
  const Check& check = check_of(key);
  if (!check.error.empty()) {
    state.SkipWithError(check.error.c_str());
    return;
  }
  LlvmpipePeer& peer = peer_of(key);
  for (auto _ : state) {
    peer.draw(pv.camera);
    benchmark::ClobberMemory();
  }
  state.SetLabel(peer.renderer());
  state.counters["triangles"] = double(peer.triangles());
  state.counters["pixels"] = double(check.peer_covered);
  state.counters["frame_pixels"] = double(kWidth) * kHeight;
  state.counters["coverage_agree"] = check.coverage_agree;
  state.counters["face_agree"] = check.face_agree;
  state.counters["surface_agree"] = check.surface_agree;
}

/// The Embree peer with the plan's triangles in its BVH, one per plan (2 threads, as the others).
EmbreePeer& embree_of(const std::string& key) {
  static auto* cache = new std::map<std::string, std::unique_ptr<EmbreePeer>>;
  auto& slot = (*cache)[key];
  if (!slot) {
    auto peer = std::make_unique<EmbreePeer>(kWidth, kHeight, 2);
    const PlanView& pv = plan_view(key);
    peer->upload(pv.complex, pv.objects);
    std::fprintf(stderr, "embree peer: %s: %ld triangles\n", key.c_str(), peer->triangles());
    slot = std::move(peer);
  }
  return *slot;
}

/// The Embree frame checked once against Avenues' item buffer, as the llvmpipe one is.
const Check& embree_check_of(const std::string& key) {
  static auto* cache = new std::map<std::string, Check>;
  auto found = cache->find(key);
  if (found != cache->end()) return found->second;
  Check& k = (*cache)[key];
  const PlanView& pv = plan_view(key);
  if (pv.eye_cell == kNoCell) {
    k.error = key + ": the eye is not in a cell";
    return k;
  }
  EmbreePeer& peer = embree_of(key);
  peer.draw(pv.camera);
  if (uniform(peer.frame(), 1)) k.error = key + ": the Embree frame is uniform";
  const AvenuesItems& av = avenues_items(key);
  agree(pv, av, peer, peer.read_ids(), k);
  std::fprintf(stderr,
               "embree peer check %s: agree on coverage %.6f, face %.6f, surface %.6f (pixels covered: "
               "avenues %ld, embree %ld)\n",
               key.c_str(), k.coverage_agree, k.face_agree, k.surface_agree, k.avenues_covered, k.peer_covered);
  if (k.error.empty() && (k.coverage_agree < 0.95 || k.surface_agree < 0.95))
    k.error = key + ": the Embree and Avenues pictures differ on more than 5% of the pixels";
  return k;
}

/// (c) Embree: a ray per pixel into the BVH of the whole building, every frame.
void embree_frame(benchmark::State& state, const std::string& key) {
  const Check& check = embree_check_of(key);
  if (!check.error.empty()) {
    state.SkipWithError(check.error.c_str());
    return;
  }
  const PlanView& pv = plan_view(key);
  EmbreePeer& peer = embree_of(key);
  for (auto _ : state) {
    peer.draw(pv.camera);
    benchmark::DoNotOptimize(peer.frame().data());
    benchmark::ClobberMemory();
  }
  state.counters["triangles"] = double(peer.triangles());
  state.counters["pixels"] = double(check.peer_covered);
  state.counters["frame_pixels"] = double(kWidth) * kHeight;
  state.counters["coverage_agree"] = check.coverage_agree;
  state.counters["face_agree"] = check.face_agree;
  state.counters["surface_agree"] = check.surface_agree;
}

int register_all() {
  for (const auto& [name, key] : std::map<std::string, std::string>{
           {"jones_house", "jones-house.toml"}, {"office_corridor", "office-corridor.toml"}, {"office100x100", "office:100"}}) {
    benchmark::RegisterBenchmark(("Llvmpipe/" + name + "/avenues").c_str(),
                                 [key = key](benchmark::State& s) { avenues_frame(s, key); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(3)->ReportAggregatesOnly(true);
    benchmark::RegisterBenchmark(("Llvmpipe/" + name + "/llvmpipe").c_str(),
                                 [key = key](benchmark::State& s) { llvmpipe_frame(s, key); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(3)->ReportAggregatesOnly(true);
    benchmark::RegisterBenchmark(("Llvmpipe/" + name + "/embree").c_str(),
                                 [key = key](benchmark::State& s) { embree_frame(s, key); })
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Repetitions(3)->ReportAggregatesOnly(true);
  }
  return 0;
}

}  // namespace

const int registered = register_all();
