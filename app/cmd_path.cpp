// Avenues — `avenues path PLAN --through ROOM,ROOM,... | --keys FILE -o DIR`: a batch walkthrough.
//
// The route runs through the named rooms on the portal graph (visibility/route.h: doorway
// centres as waypoints, a Catmull–Rom curve through them), one frame every --step metres,
// each looking a metre ahead along the path; or it follows recorded keyframes (eye and
// point looked at), straight between them. Frames are PNG half-tone pictures or SVG
// drawings, numbered in DIR; on a terminal a progress bar shows the frame and the time
// left. With PNG frames and ffmpeg on the PATH, DIR/walk.mp4 as well.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "app/commands.h"
#include "render/effects.h"
#include "render/drawing.h"
#include "render/halftone.h"
#include "render/raster.h"
#include "render/scene_objects.h"
#include "render/view_lines.h"
#include "render/walkthrough.h"
#include "visibility/route.h"

namespace avenues::app {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> split_names(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string name; std::getline(in, name, ',');)
    if (!name.empty()) out.push_back(name);
  return out;
}

bool have_ffmpeg() { return std::system("command -v ffmpeg >/dev/null 2>&1") == 0; }

/// "[#####.....]  12/40  0:03 left" on one terminal line, redrawn in place.
void progress(int done, int total, double seconds) {
  const int width = 30, filled = total > 0 ? done * width / total : width;
  const double left = done > 0 ? seconds / done * (total - done) : 0;
  std::fprintf(stderr, "\r[%s%s] %d/%d  %d:%02d left ", std::string(size_t(filled), '#').c_str(),
               std::string(size_t(width - filled), '.').c_str(), done, total, int(left) / 60, int(left) % 60);
  if (done == total) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace

/// Keyframes from a text file: one per line, "EX EY EZ LX LY LZ" (eye, then the point it
/// looks at, in metres), '#' starts a comment. Throws PlanError naming the file and line.
std::vector<std::pair<Vec3, Vec3>> read_keys(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read keyframes " + file);
  std::vector<std::pair<Vec3, Vec3>> keys;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    Vec3 e, l;
    if (!(words >> std::ws).good()) continue;  // blank or comment
    if (!(words >> e.x >> e.y >> e.z >> l.x >> l.y >> l.z) || !(words >> std::ws).eof() || !std::isfinite(e.x + e.y + e.z + l.x + l.y + l.z))
      throw PlanError({file, n, 0, "keyframe"}, "a keyframe is six numbers: the eye X Y Z, then the point looked at X Y Z");
    if (!(length(l - e) > 0)) throw PlanError({file, n, 0, "keyframe"}, "the eye looks at itself");
    keys.push_back({e, l});
  }
  if (keys.size() < 2) throw std::runtime_error("keyframes " + file + ": a walk needs at least two keyframes");
  return keys;
}

int run_path(const PathOptions& opt) {
  LoadedPlan plan = load_plan_source(opt.plan, opt.import);
  const CellComplex& c = plan.complex;
  if (opt.format != "png" && opt.format != "svg") throw std::runtime_error("--format wants png or svg, not '" + opt.format + "'");
  int w = 0, h = 0;
  if (!parse_size(opt.size, w, h)) throw std::runtime_error("--size wants WIDTHxHEIGHT in pixels, not '" + opt.size + "'");
  if (!(opt.fov > 0 && opt.fov <= 179)) throw std::runtime_error("--fov must lie in (0, 179] degrees");
  Kernel kernel;
  if (!parse_kernel(opt.kernel, kernel)) throw std::runtime_error("--kernel wants float, double, filtered or exact");
  if (opt.through.empty() == opt.keys.empty()) throw std::runtime_error("give either --through ROOMS or --keys FILE");
  if (!(opt.step > 0)) throw std::runtime_error("--step must be a positive length");
  std::vector<Vec3> eyes, looks;  // looks: empty for a route (look ahead along it)
  if (!opt.through.empty()) {
    eyes = smooth_path(c, route_through(c, split_names(opt.through)), opt.step);
  } else {
    // Recorded keyframes: straight between them, one frame every --step metres of eye travel.
    const auto keys = read_keys(opt.keys);
    eyes.push_back(keys[0].first);
    looks.push_back(keys[0].second);
    for (size_t i = 0; i + 1 < keys.size(); ++i) {
      const int n = std::max(1, int(std::ceil(length(keys[i + 1].first - keys[i].first) / opt.step)));
      for (int s = 1; s <= n; ++s) {
        const double t = double(s) / n;
        eyes.push_back(keys[i].first + t * (keys[i + 1].first - keys[i].first));
        looks.push_back(keys[i].second + t * (keys[i + 1].second - keys[i].second));
      }
    }
  }
  if (eyes.size() < 2) throw std::runtime_error("--through names rooms that are already where the walk starts");

  // Every frame's camera first (a frame whose eye would leave free space is an error
  // before anything is written), looking a metre ahead along the path.
  std::vector<WalkFrame> frames;
  CellId hint = kNoCell;
  Vec3 last_dir = eyes[1] - eyes[0];
  for (size_t k = 0; k < eyes.size(); ++k) {
    size_t j = k;
    while (j + 1 < eyes.size() && length(eyes[j] - eyes[k]) < 1.0) ++j;
    Vec3 dir = eyes[j] - eyes[k];
    dir.z = 0;
    if (length(dir) > 1e-6) last_dir = dir;
    const Location at = c.locate(eyes[k], hint);
    if (at.what != Location::What::Cell)
      throw std::runtime_error("frame " + std::to_string(k + 1) + " of the path: the eye is " +
                               (at.what == Location::What::Solid ? "inside " + at.solid : std::string("outside the far box")));
    WalkFrame f;
    f.camera = Camera::look_at(eyes[k], looks.empty() ? eyes[k] + last_dir : looks[k], opt.fov, w, h);
    f.cell = hint = at.cell;
    frames.push_back(f);
  }

  std::error_code ec;
  fs::create_directories(opt.out_dir, ec);
  if (ec) throw std::runtime_error("cannot create the output directory " + opt.out_dir + ": " + ec.message());
  const std::string pattern = (fs::path(opt.out_dir) / ("frame." + opt.format)).string();
  const bool terminal = ::isatty(STDERR_FILENO);
  const LineScene scene = opt.format == "svg" ? prepare_line_scene(c) : LineScene{};
  const std::vector<PlacedObject> objects = opt.format == "png" ? place_objects(c) : std::vector<PlacedObject>{};
  HalftoneOptions halftone;
  halftone.samples = 4;
  const SceneEffects effects = prepare_effects(c, objects, halftone, kernel);  // once for every frame
  Image picture;
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t k = 0; k < frames.size(); ++k) {
    const VisibleSet vs = find_visible(c, frames[k].camera, frames[k].cell, kernel);
    const std::string file = frame_path(pattern, int(k), int(frames.size()));
    if (opt.format == "svg") {
      write_drawing(draw_view(c, scene, frames[k].camera, vs), file);
    } else {
      render_view(c, objects, effects, frames[k].camera, vs, halftone, picture);
      write_image(picture, file);
    }
    if (terminal)
      progress(int(k + 1), int(frames.size()),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::cout << "wrote " << frames.size() << " frames: " << frame_path(pattern, 0, int(frames.size())) << " ... "
            << frame_path(pattern, int(frames.size()) - 1, int(frames.size())) << "\n";
  if (opt.format == "png" && have_ffmpeg()) {
    const fs::path dir(opt.out_dir);
    const std::string digits = std::to_string(std::max(4, int(std::to_string(frames.size()).size())));
    // Written under another name and renamed when whole: never a partial walk.mp4.
    const fs::path mp4 = dir / "walk.mp4", part = dir / "walk.mp4.part";
    const std::string cmd = "ffmpeg -loglevel error -y -framerate 25 -i '" + (dir / ("frame-%0" + digits + "d.png")).string() +
                            "' -pix_fmt yuv420p -vf 'scale=trunc(iw/2)*2:trunc(ih/2)*2' -f mp4 '" + part.string() +
                            "' </dev/null";
    std::error_code mp4_error;
    if (std::system(cmd.c_str()) == 0 && (fs::rename(part, mp4, mp4_error), !mp4_error)) {
      std::cout << "wrote " << mp4.string() << "\n";
    } else {
      fs::remove(part, mp4_error);
      std::cerr << "avenues: ffmpeg could not make the MP4; the frames are there\n";
    }
  }
  return 0;
}

}  // namespace avenues::app
