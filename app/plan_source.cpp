// Avenues — loading PLAN for the executable (see plan_source.h).
#include "app/plan_source.h"

#include <chrono>
#include <cctype>
#include <cstring>
#include <iostream>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "cells/build_cells.h"
#include "cells/crow.h"
#include "plans/formats/doom_map.h"
#include "plans/formats/dxf_plan.h"
#include "plans/formats/floorplan_vectors.h"
#include "cells/mesh_scene.h"
#include "plans/formats/sweet_home.h"
#include "plans/plan.h"
#include "plans/plan_writer.h"

#ifndef AVENUES_SOURCE_DIR
#define AVENUES_SOURCE_DIR ""
#endif

namespace avenues::app {
namespace fs = std::filesystem;

namespace {

constexpr const char* kDefaultPlan = "jones-house.toml";

/// A saved complex starts with the magic "AVCELLS\0", whatever its name.
bool looks_like_cells(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  return in.read(magic, sizeof magic) && std::memcmp(magic, "AVCELLS\0", 8) == 0;
}

}  // namespace

double LoadedPlan::seconds() const {
  double s = 0;
  for (const StageTime& t : stages) s += t.seconds;
  return s;
}

std::string default_plan_path() {
  std::vector<fs::path> candidates;
  if (std::string(AVENUES_SOURCE_DIR).size() > 0)
    candidates.push_back(fs::path(AVENUES_SOURCE_DIR) / "plans" / kDefaultPlan);
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share" / "avenues" / "plans" / kDefaultPlan);
  std::string looked;
  for (const fs::path& p : candidates) {
    if (fs::is_regular_file(p, ec)) return p.string();
    looked += (looked.empty() ? "" : ", ") + p.string();
  }
  throw std::runtime_error(std::string("cannot find the bundled plan ") + kDefaultPlan + " (looked in " +
                           (looked.empty() ? "nowhere" : looked) + "); name a PLAN");
}

namespace {

std::string lower(std::string s) {
  for (char& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

/// Prints what the importer and the decomposition repaired or dropped: the first few
/// lines, then how many more (a real Doom map may have dozens).
void print_warnings(const std::string& path, const std::vector<std::string>& warnings) {
  constexpr size_t kShown = 12;
  for (size_t i = 0; i < warnings.size() && i < kShown; ++i) std::cerr << path << ": warning: " << warnings[i] << "\n";
  if (warnings.size() > kShown)
    std::cerr << path << ": " << warnings.size() - kShown << " more warnings (avenues cells PLAN --json lists them all)\n";
}

}  // namespace

PlanSpec parse_plan_spec(const std::string& plan) {
  PlanSpec spec;
  spec.file = plan;
  // FILE.wad:MAP01 — the map after the last colon, when what precedes it is a WAD.
  const size_t colon = plan.rfind(':');
  if (colon != std::string::npos && colon > 4 && lower(plan.substr(colon - 4, 4)) == ".wad") {
    spec.file = plan.substr(0, colon);
    spec.map = plan.substr(colon + 1);
  }
  const std::string ext = lower(fs::path(spec.file).extension().string());
  if (ext == ".cells") spec.format = PlanFormat::Cells;
  else if (ext == ".wad") spec.format = PlanFormat::DoomMap;
  else if (ext == ".sh3d" || ext == ".xml") spec.format = PlanFormat::SweetHome;
  else if (ext == ".off" || ext == ".obj" || ext == ".ply" || ext == ".stl") spec.format = PlanFormat::MeshScene;
  else if (ext == ".crow") spec.format = PlanFormat::Crow;
  else if (ext == ".txt") spec.format = PlanFormat::FloorplanVectors;
  else if (ext == ".dxf") spec.format = PlanFormat::Dxf;
  else spec.format = PlanFormat::Toml;
  return spec;
}

LoadedPlan load_plan_source(const std::string& plan, const ImportOptions& import) {
  LoadedPlan out;
  PlanSpec spec = parse_plan_spec(plan.empty() ? default_plan_path() : plan);
  out.path = plan.empty() ? spec.file : plan;
  fs::path p(spec.file);
  out.stem = p.stem().string() + (spec.map.empty() ? "" : "-" + spec.map);
  std::error_code ec;
  if (!fs::exists(p, ec)) throw std::runtime_error(spec.file + ": no such file");
  if (fs::is_directory(p, ec)) throw std::runtime_error(spec.file + ": is a directory, not a plan");
  if (spec.format != PlanFormat::Cells && looks_like_cells(spec.file)) spec.format = PlanFormat::Cells;
  if (spec.format == PlanFormat::Toml && lower(p.extension().string()) != ".toml") {
    // No telling extension: a few lines of content tell the 2D formats.
    std::ifstream in(spec.file, std::ios::binary);
    std::string head(4096, '\0');
    head.resize(size_t(in.read(head.data(), std::streamsize(head.size())).gcount()));
    if (looks_like_floorplan_vectors(head)) spec.format = PlanFormat::FloorplanVectors;
    else if (looks_like_dxf(head)) spec.format = PlanFormat::Dxf;
  }

  auto t0 = std::chrono::steady_clock::now();
  auto decompose = [&](const Plan& parsed, const char* stage) {
    out.stages.push_back({stage, seconds_since(t0)});
    if (!import.save_plan.empty()) {
      write_plan(parsed, import.save_plan);
      std::cerr << spec.file << ": the plan as understood is in " << import.save_plan << "\n";
    }
    out.complex = build_cells(parsed);
    for (const StageTime& t : out.complex.timings) out.stages.push_back(t);
  };
  switch (spec.format) {
    case PlanFormat::Cells:
      out.complex = load_cells(spec.file);
      out.stages.push_back({"load cells", seconds_since(t0)});
      return out;
    case PlanFormat::Toml: decompose(read_plan(spec.file), "read plan"); break;
    case PlanFormat::DoomMap: {
      if (spec.map.empty()) {
        const std::vector<std::string> maps = doom_map_names(spec.file);
        if (maps.empty()) throw PlanError({spec.file, 0, 0, ""}, "the WAD holds no maps");
        spec.map = maps.front();
        out.stem += "-" + spec.map;
        std::cerr << spec.file << ": reading " << spec.map << ", the first of its " << maps.size()
                  << " maps (name one as " << spec.file << ":" << maps.back() << ")\n";
      }
      decompose(read_doom_map(spec.file, spec.map), "read map");
      break;
    }
    case PlanFormat::SweetHome: decompose(read_sweet_home(spec.file), "read home"); break;
    case PlanFormat::FloorplanVectors: {
      FloorplanVectorOptions o;
      if (import.scale > 0) o.metres_per_pixel = import.scale;
      o.storey_height = import.storey_height;
      decompose(read_floorplan_vectors(spec.file, o), "read annotations");
      break;
    }
    case PlanFormat::Dxf: {
      const DxfPlan d = read_dxf_plan(spec.file, {import.layers, import.unit, import.storey_height});
      for (const std::string& line : d.summary) std::cerr << spec.file << ": " << line << "\n";
      decompose(d.plan, "read drawing");
      break;
    }
    case PlanFormat::MeshScene:
      out.complex = read_mesh_scene(spec.file);
      for (const StageTime& t : out.complex.timings) out.stages.push_back(t);
      break;
    case PlanFormat::Crow:
      out.complex = read_crow_scene(spec.file);
      for (const StageTime& t : out.complex.timings) out.stages.push_back(t);
      break;
  }
  print_warnings(spec.file, out.complex.warnings);
  return out;
}

}  // namespace avenues::app
