// Avenues — loading PLAN for the executable (see plan_source.h).
#include "app/plan_source.h"

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "cells/build_cells.h"
#include "plans/plan.h"

#ifndef AVENUES_SOURCE_DIR
#define AVENUES_SOURCE_DIR ""
#endif

namespace avenues::app {
namespace fs = std::filesystem;

namespace {

constexpr const char* kDefaultPlan = "jones-house.toml";

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

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

LoadedPlan load_plan_source(const std::string& plan) {
  LoadedPlan out;
  out.path = plan.empty() ? default_plan_path() : plan;
  fs::path p(out.path);
  out.stem = p.stem().string();
  std::error_code ec;
  if (!fs::exists(p, ec)) throw std::runtime_error(out.path + ": no such file");
  if (fs::is_directory(p, ec)) throw std::runtime_error(out.path + ": is a directory, not a plan");

  if (p.extension() == ".cells" || looks_like_cells(out.path)) {
    auto t0 = std::chrono::steady_clock::now();
    out.complex = load_cells(out.path);
    out.stages.push_back({"load cells", since(t0)});
    return out;
  }
  auto t0 = std::chrono::steady_clock::now();
  Plan parsed = read_plan(out.path);
  out.stages.push_back({"read plan", since(t0)});
  out.complex = build_cells(parsed);
  for (const StageTime& t : out.complex.timings) out.stages.push_back(t);
  return out;
}

}  // namespace avenues::app
