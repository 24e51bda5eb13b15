// Avenues — the walkthrough's exports and keyframes (see walk_exports.h).
#include "app/walk_exports.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/number_format.h"

namespace avenues::app {

namespace fs = std::filesystem;

namespace {

std::string stereo_pair_names(const std::string& path) {
  const fs::path p(path);
  const std::string base = (p.parent_path() / p.stem()).string(), ext = p.extension().string();
  return base + "-left" + ext + " and " + base + "-right" + ext;
}

}  // namespace

WalkExports::WalkExports(const LoadedPlan& plan, const WalkOptions& opt)
    : plan_(plan),
      opt_(opt),
      record_path_(opt.record.empty() ? (fs::path(opt.out_dir) / (plan.stem + "-keys.txt")).string() : opt.record) {}

std::string WalkExports::next(const std::vector<std::string>& suffixes) {
  std::error_code ec;
  fs::create_directories(opt_.out_dir, ec);
  if (ec) throw std::runtime_error("cannot create the output directory " + opt_.out_dir + ": " + ec.message());
  for (;; ++number_) {
    std::ostringstream stem;
    stem << plan_.stem << "-" << std::setw(4) << std::setfill('0') << number_;
    const std::string base = (fs::path(opt_.out_dir) / stem.str()).string();
    bool free = true;
    for (const std::string& s : suffixes) free &= !fs::exists(base + s);
    if (free) {
      ++number_;
      return base;
    }
  }
}

std::string WalkExports::picture(const Image& frame) {
  const std::string path = next({".png"}) + ".png";
  write_image(frame, path);
  return "wrote " + path + " (the picture as shown)";
}

std::string WalkExports::view(const ViewSetup& v, const std::string& ext, const std::string& stereo) {
  const std::string tag = stereo.empty() ? "" : "-stereo";
  const std::string path = next({tag + ext, tag + "-left" + ext, tag + "-right" + ext}) + tag + ext;
  ViewOptions o;
  o.outputs = {path};
  o.stereo = stereo;
  o.samples = opt_.samples;
  o.shading = opt_.shading;
  o.interocular = opt_.interocular;
  o.converge = opt_.converge;
  nlohmann::json stats;
  write_view_output(plan_, v, find_visible(plan_.complex, v.camera, v.eye_cell, v.search), o, path, stats);
  return "wrote " + (stereo == "pair" ? stereo_pair_names(path) : path);
}

std::string WalkExports::keyframe(Vec3 e, Vec3 l) {
  const fs::path p(record_path_);
  if (p.has_parent_path()) fs::create_directories(p.parent_path());
  const bool fresh = !fs::exists(p);
  std::ofstream out(record_path_, std::ios::app);
  if (fresh) out << "# avenues walk keyframes (" << plan_.stem << "): eye X Y Z, then the point looked at X Y Z\n";
  out << format_exact(e.x) << " " << format_exact(e.y) << " " << format_exact(e.z) << " " << format_exact(l.x) << " " << format_exact(l.y) << " "
      << format_exact(l.z) << "\n";
  if (!out) throw std::runtime_error("cannot write " + record_path_);
  ++keyframes_;
  return "keyframe " + std::to_string(keyframes_) + " appended to " + record_path_ + " (avenues path --keys " +
         record_path_ + ")";
}

}  // namespace avenues::app
