// Avenues — how fast the avenues of sight are found (Google Benchmark).
//
//   ./build/bench/avenues_bench --benchmark_filter=Visibility
//
// Targets (docs/PERFORMANCE.md): median traversal per view <= 20 µs on the bundled
// plans at 1920x1080, reported beside a brute force that tests every cell against the
// view frustum; flat in building size: the same local view in a 10x10 and a 100x100
// office within 1.3x of each other.
//
// Random views (issue 18): eyes anywhere in free space (rooms, outside, above the roof)
// looking any way, in the bundled plans, Debian's nine Sweet Home 3D example homes and
// Freedoom maps; the median and p99 traversal per view and the avenues per view, pruned
// (TraverseParams::prune_covered) and unpruned, side by side in one run:
//
//   ./build/bench/avenues_bench --benchmark_filter=VisibilityRandom
//
// and the merged search (TraverseParams::merge_pieces) beside them, with two mesh scenes
// (the Viking room and the alpine cabin, whose outsides the soup BSP slices finely).
// For the meshes and IFC models, the hull search with each portal clipped on its own
// (hull_each) beside it: what a face's portals into one cell taken as one hull buy.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <random>

#include "cells/build_cells.h"
#include "cells/mesh_scene.h"
#include "plans/formats/doom_map.h"
#include "plans/formats/ifc_building.h"
#include "plans/formats/sweet_home.h"
#include "plans/generate.h"
#include "visibility/visible_set.h"

namespace fs = std::filesystem;
using namespace avenues;

namespace {

/// Complexes are built once per process and shared by the benchmarks.
/// Keys: "office:N" (a generated N × N office), "sh3d:PATH" (a Sweet Home home),
/// "wad:PATH:MAP" (a Doom map), "ifc:PATH" (an IFC building), else a bundled plan's file name.
const CellComplex& complex_of(const std::string& key) {
  static std::map<std::string, std::unique_ptr<CellComplex>> cache;
  auto& slot = cache[key];
  if (!slot) {
    Plan p;
    if (key.rfind("office:", 0) == 0) {
      p = parse_plan(generate_office_toml(std::stoi(key.substr(7)), std::stoi(key.substr(7))), key);
    } else if (key.rfind("sh3d:", 0) == 0) {
      p = read_sweet_home(key.substr(5));
    } else if (key.rfind("ifc:", 0) == 0) {
      try {
        p = read_ifc_building(key.substr(4));
      } catch (const IfcWithoutWalls& e) {  // a structural model: its faces are the scene, as `avenues` reads it
        slot = std::make_unique<CellComplex>(build_mesh_scene({*e.faces}));
        return *slot;
      }
    } else if (key.rfind("mesh:", 0) == 0) {
      slot = std::make_unique<CellComplex>(read_mesh_scene(key.substr(5)));
      return *slot;
    } else if (key.rfind("wad:", 0) == 0) {
      const size_t colon = key.rfind(':');
      p = read_doom_map(key.substr(4, colon - 4), key.substr(colon + 1));
    } else {
      p = read_plan((fs::path(AVENUES_SOURCE_DIR) / "plans" / key).string());
    }
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

/// Eyes uniform in the box of every cell but the sky, and 3 m above it, kept where they
/// are in free space; directions uniform on the sphere; 60° at 1280 × 720.
std::vector<std::pair<Camera, CellId>> free_views(const CellComplex& c, int n) {
  Box3 box;
  for (const Cell& cell : c.cells)
    if (cell.kind != CellKind::Sky) box.add(cell.bounds().lo), box.add(cell.bounds().hi);
  box.hi.z += 3;
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::pair<Camera, CellId>> out;
  for (int tries = 0; int(out.size()) < n && tries < 1000 * n; ++tries) {
    const Vec3 eye{box.lo.x + u(rng) * (box.hi.x - box.lo.x), box.lo.y + u(rng) * (box.hi.y - box.lo.y),
                   box.lo.z + u(rng) * (box.hi.z - box.lo.z)};
    const Location at = c.locate(eye);
    if (at.what != Location::What::Cell) continue;
    const double yaw = 360 * u(rng), pitch = std::asin(2 * u(rng) - 1) * 180 / M_PI;
    out.push_back({Camera::yaw_pitch(eye, yaw, std::clamp(pitch, -89.9, 89.9), 60, 1280, 720), at.cell});
  }
  return out;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const size_t k = std::min(v.size() - 1, size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + long(k), v.end());
  return v[k];
}

/// Every view once per iteration; the traversal's own time per view (VisibleSet::micros).
/// `search`: "unpruned" (Jones's tree), "pruned" (TraverseParams::prune_covered) or
/// "merged" (TraverseParams::merge_pieces) or "hull" (TraverseParams::hull_pieces: conservative,
/// its visible_cells counting cells perhaps not seen), or "hull_each": the hull search
/// clipping to each portal of a face, not to the hull of its portals into one cell
/// (CellComplex::PortalTable::hulls, set aside in a copy of the complex): what they buy.
void random_views(benchmark::State& state, const std::string& key, const std::string& search) {
  const CellComplex& shared = complex_of(key);
  std::optional<CellComplex> each;
  if (search == "hull_each") {
    each = shared;
    std::fill(each->portal_table.face_hulls.begin(), each->portal_table.face_hulls.end(), 0);
  }
  const CellComplex& c = each ? *each : shared;
  const auto vs = free_views(c, 200);
  TraverseParams params;
  params.prune_covered = search == "pruned";
  params.merge_pieces = search == "merged" || search.starts_with("hull");
  params.hull_pieces = search.starts_with("hull");
  std::vector<double> micros;
  double avenues = 0, most = 0, cells = 0, pruned = 0, merged = 0;
  for (auto _ : state) {
    for (const auto& [cam, cell] : vs) {
      VisibleSet v = find_visible(c, cam, cell, params);
      micros.push_back(v.micros);
      avenues += double(v.avenues.size());
      pruned += double(v.avenues_pruned);
      merged += double(v.avenues_merged);
      most = std::max(most, double(v.avenues.size()));
      cells += double(v.cells.size());
      benchmark::DoNotOptimize(v);
    }
  }
  const double views = double(micros.size());
  state.counters["median_us"] = quantile(micros, 0.5);
  state.counters["p99_us"] = quantile(micros, 0.99);
  state.counters["avenues"] = avenues / views;
  state.counters["avenues_max"] = most;
  state.counters["pruned"] = pruned / views;
  state.counters["merged"] = merged / views;
  state.counters["visible_cells"] = cells / views;
  state.counters["cells"] = double(c.cells.size());
  state.counters["views"] = double(vs.size());
}

int register_all() {
  {
    std::vector<std::pair<std::string, std::string>> plans;  // (name, key)
    for (const char* plan : {"jones-house", "two-storey-house", "office-corridor", "curved-walls", "furnished-room"})
      plans.push_back({plan, std::string(plan) + ".toml"});
    const fs::path homes = "/usr/local/share/avenues/sweethome3d-examples";
    for (const char* home : {"1BedroomApartmentWithRoundWall", "2BedroomApartment", "2BedroomApartmentWithBowWindow",
                             "2BedroomHouseWithBasement", "3BedroomApartment", "3BedroomHouseWithAttic",
                             "3BedroomHouseWithMezzanine", "4BedroomHouse", "Studio"})
      if (fs::exists(homes / (std::string(home) + ".xml")))
        plans.push_back({home, "sh3d:" + (homes / (std::string(home) + ".xml")).string()});
    // The homes from outside that open (some are damaged on purpose: they are skipped).
    const fs::path outside_homes = fs::path(AVENUES_OUTSIDE_DIR) / "sweethome";
    if (fs::is_directory(outside_homes)) {
      std::vector<fs::path> files;
      for (const auto& e : fs::directory_iterator(outside_homes))
        if (e.path().extension() == ".sh3d") files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const fs::path& f : files) {
        const std::string key = "sh3d:" + f.string();
        try {
          complex_of(key);
        } catch (const std::exception&) {
          continue;
        }
        plans.push_back({f.stem().string(), key});
      }
    }
    for (const char* map : {"freedoom2.wad:MAP01", "freedoom1.wad:E1M1", "freedoom2.wad:MAP12"}) {
      const std::string m(map);
      const std::string wad = "/usr/share/games/doom/" + m.substr(0, m.find(':'));
      if (fs::exists(wad)) plans.push_back({m, "wad:" + wad + m.substr(m.find(':'))});
    }
    for (const char* model : {"duplex", "Office_A_20110811", "IfcOpenHouse_IFC4", "ISSUE_044_test_IFCCOMPOSITEPROFILEDEF",
                              "ISSUE_021_Mini_Project"}) {
      const fs::path ifc = fs::path(AVENUES_OUTSIDE_DIR) / "ifc" / (std::string(model) + ".ifc");
      if (fs::exists(ifc)) plans.push_back({model, "ifc:" + ifc.string()});
    }
    if (const fs::path fzk = "/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc"; fs::exists(fzk))
      plans.push_back({"AC14-FZK-Haus", "ifc:" + fzk.string()});  // assimp-testmodels: a gabled house
    for (const char* mesh : {"meshes/viking-room/viking_room.obj", "meshes/alpine-cabin/house.obj"}) {
      const fs::path file = fs::path(AVENUES_OUTSIDE_DIR) / mesh;
      if (fs::exists(file)) plans.push_back({file.stem().string(), "mesh:" + file.string()});
    }
    for (const auto& [name, key] : plans)
      for (const char* search : {"unpruned", "pruned", "merged", "hull", "hull_each"}) {
        // Portal hulls are laid out for cells that are no prisms: a mesh's, an IFC model's
        // read as its faces.
        if (std::string(search) == "hull_each" && !key.starts_with("mesh:") && !key.starts_with("ifc:")) continue;
        benchmark::RegisterBenchmark(("VisibilityRandom/" + name + "/" + search).c_str(),
                                     [key = key, search = std::string(search)](benchmark::State& s) {
                                       random_views(s, key, search);
                                     })
            ->Unit(benchmark::kMillisecond)
            ->Iterations(3);
      }
  }
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
