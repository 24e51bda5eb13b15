// Avenues — `avenues path PLAN --through ROOM,ROOM,... | --keys FILE -o DIR`: a batch walkthrough.
//
// The route runs through the named rooms on the portal graph (visibility/route.h: doorway
// centres as waypoints, a Catmull–Rom curve through them), one frame every --step metres,
// each looking a metre ahead along the path; or it follows recorded keyframes (eye and
// point looked at), straight between them. Frames are PNG half-tone pictures or SVG
// drawings (or stereo pairs of them), numbered in DIR; on a terminal a progress bar shows
// the frames done and the time left. With PNG frames, DIR/walk.mp4 as well (render/film.h).
//
// A walk owns its output: the frames, film and leftover temporary files of an earlier walk
// in DIR are removed before the first frame is written (with --resume, the frames this
// walk would write are kept and not rendered again). Under mpirun or srun the frames are
// spread over the ranks (app/mpi_walk.h); they are the same files, byte for byte.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <thread>
#include <type_traits>

#include "app/commands.h"
#include "app/mpi_walk.h"
#include "app/option_checks.h"
#include "cells/build_cells.h"
#include "render/effects.h"
#include "render/drawing.h"
#include "render/film.h"
#include "render/halftone.h"
#include "render/raster.h"
#include "render/scene_objects.h"
#include "render/stereo_drawing.h"
#include "render/view_lines.h"
#include "render/walkthrough.h"
#include "visibility/route.h"
#include "visibility/stereo.h"
#include "visibility/strips.h"

namespace avenues::app {

namespace fs = std::filesystem;

namespace {

constexpr double kMinStep = 0.001;  ///< [m] the shortest --step: a millimetre

std::vector<std::string> split_names(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string name; std::getline(in, name, ',');)
    if (!name.empty()) out.push_back(name);
  return out;
}

/// "[#####.....]  12/40  0:03 left": on a terminal one line redrawn in place; otherwise
/// (a rank of an MPI job, whose output goes to the launcher or a log) a line each time.
void progress(int64_t done, int64_t total, double seconds, bool terminal) {
  const int64_t width = 30, filled = total > 0 ? done * width / total : width;
  const double left = done > 0 ? seconds / double(done) * double(total - done) : 0;
  std::fprintf(stderr, "%s[%s%s] %lld/%lld  %d:%02d left%s", terminal ? "\r" : "", std::string(size_t(filled), '#').c_str(),
               std::string(size_t(width - filled), '.').c_str(), static_cast<long long>(done),
               static_cast<long long>(total), int(left) / 60, int(left) % 60, terminal && done < total ? " " : "\n");
  std::fflush(stderr);
}

}  // namespace

/// Keyframes from a text file: one per line, "EX EY EZ LX LY LZ" (eye, then the point it
/// looks at, in metres), '#' starts a comment. Throws PlanError naming the file and line.
std::vector<std::pair<Vec3, Vec3>> read_keys(const std::string& file) {
  if (std::error_code ec; !std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error("cannot read keyframes " + file + (std::filesystem::exists(file, ec) ? ": not a regular file" : ": no such file"));
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

namespace {

/// How a walk's frames are drawn: the options, checked once (by every rank alike).
struct PathSettings {
  bool svg = false;                ///< hidden-line drawings, else half-tone pictures
  int width = 0, height = 0;       ///< [px]
  Kernel kernel = Kernel::Double;
  TraverseParams search;
  HalftoneOptions halftone;
  bool stereo = false;
  StereoComposite composite = StereoComposite::Anaglyph;  ///< pictures
  StereoLayout layout = StereoLayout::Parallel;           ///< drawings
  StereoOptions eyes;
};

PathSettings path_settings(const PathOptions& opt, const MpiWalk& mpi) {
  PathSettings s;
  if (opt.format != "png" && opt.format != "svg") throw std::runtime_error("--format wants png or svg, not '" + opt.format + "'");
  s.svg = opt.format == "svg";
  size_option(opt.size, s.width, s.height);
  if (!(opt.fov > 0 && opt.fov <= 179)) throw std::runtime_error("--fov must lie in (0, 179] degrees");
  s.kernel = kernel_option(opt.kernel);
  s.search = search_option(opt.search, s.kernel);
  s.halftone.samples = samples_option(opt.samples);
  if (!parse_shading(opt.shading, s.halftone.shading.model))
    throw std::runtime_error("--shading wants flat, smooth or auto, not '" + opt.shading + "'");
  s.halftone.lights = lights_option(opt.lights);
  s.halftone.object_shadows = object_shadows_option(opt.object_shadows);
  s.halftone.detail_samples = opt.detail;
  if (opt.threads < 0) throw std::runtime_error("--threads wants a number of threads (0: as many as there are cores)");
  // A process's threads; in an MPI job each rank takes its share of its machine's cores.
  s.halftone.threads = opt.threads;
  if (opt.threads == 0 && mpi.ranks() > 1)
    s.halftone.threads = std::max(1, int(std::thread::hardware_concurrency()) / std::max(1, mpi.local_ranks()));
  if (!opt.stereo.empty()) {
    s.stereo = true;
    if (s.svg ? !parse_stereo_layout(opt.stereo, s.layout) || s.layout == StereoLayout::Pair
              : !parse_stereo_composite(opt.stereo, s.composite))
      throw std::runtime_error(std::string("--stereo wants ") +
                               (s.svg ? "parallel or cross for drawn frames" : "anaglyph, parallel or cross for pictures") +
                               ", not '" + opt.stereo + "'");
    if (!(std::isfinite(opt.interocular) && opt.interocular > 0))
      throw std::runtime_error("--interocular must be a positive length in metres");
    if (!(std::isfinite(opt.converge) && opt.converge > 0))
      throw std::runtime_error("--converge must be a positive length in metres");
    s.eyes = {opt.interocular, opt.converge};
  }
  return s;
}

/// Every frame's camera (and with --stereo each eye's), worked out once, on rank 0.
struct Walk {
  std::vector<WalkFrame> frames;
  std::vector<WalkFrame> left, right;  ///< --stereo: the eyes of each frame; else empty
};
static_assert(std::is_trivially_copyable_v<WalkFrame>, "a walk is broadcast as its bytes");

void append_frames(std::string& out, const std::vector<WalkFrame>& frames) {
  const uint64_t n = frames.size();
  out.append(reinterpret_cast<const char*>(&n), sizeof n);
  out.append(reinterpret_cast<const char*>(frames.data()), frames.size() * sizeof(WalkFrame));
}

/// Reads what append_frames wrote at `at`, moving `at` past it.
std::vector<WalkFrame> take_frames(std::string_view bytes, size_t& at) {
  uint64_t n = 0;
  if (bytes.size() - at < sizeof n) throw std::runtime_error("the walk's bytes are cut short");
  std::memcpy(&n, bytes.data() + at, sizeof n);
  at += sizeof n;
  if (n > (bytes.size() - at) / sizeof(WalkFrame)) throw std::runtime_error("the walk's bytes are cut short");
  std::vector<WalkFrame> frames(static_cast<size_t>(n));
  std::memcpy(static_cast<void*>(frames.data()), bytes.data() + at, size_t(n) * sizeof(WalkFrame));
  at += size_t(n) * sizeof(WalkFrame);
  return frames;
}

/// The frames of the walk the options ask for. Throws naming the option or the frame.
Walk plan_walk(const CellComplex& c, const PathOptions& opt, const PathSettings& s) {
  if (opt.through.empty() == opt.keys.empty()) throw std::runtime_error("give either --through ROOMS or --keys FILE");
  if (!(std::isfinite(opt.step) && opt.step >= kMinStep))
    throw std::runtime_error("--step must be a length of at least 0.001 m (1 mm), not " + std::to_string(opt.step));
  if (opt.max_frames < 2 || opt.max_frames > std::numeric_limits<int>::max())
    throw std::runtime_error("--max-frames wants a number of frames from 2 to " +
                             std::to_string(std::numeric_limits<int>::max()));
  // The frame count first, in 64 bits, before any frame is made.
  auto check_count = [&](int64_t n) {
    if (n > opt.max_frames)
      throw std::runtime_error("a walk with --step " + std::to_string(opt.step) + " would have " + std::to_string(n) +
                               " frames, more than --max-frames " + std::to_string(opt.max_frames) +
                               "; lengthen --step, or raise --max-frames to make it");
  };
  std::vector<Vec3> eyes, looks;  // looks: empty for a route (look ahead along it)
  if (!opt.through.empty()) {
    const std::vector<Vec3> waypoints = route_through(c, split_names(opt.through));
    check_count(path_points(waypoints, opt.step));
    eyes = smooth_path(c, waypoints, opt.step);
  } else {
    // Recorded keyframes: straight between them, one frame every --step metres of eye travel.
    const auto keys = read_keys(opt.keys);
    std::vector<Vec3> key_eyes;
    for (const auto& k : keys) key_eyes.push_back(k.first);
    check_count(path_points(key_eyes, opt.step));
    eyes.push_back(keys[0].first);
    looks.push_back(keys[0].second);
    for (size_t i = 0; i + 1 < keys.size(); ++i) {
      const int64_t n = stretch_points(keys[i].first, keys[i + 1].first, opt.step);
      for (int64_t k = 1; k <= n; ++k) {
        const double t = double(k) / double(n);
        eyes.push_back(keys[i].first + t * (keys[i + 1].first - keys[i].first));
        looks.push_back(keys[i].second + t * (keys[i + 1].second - keys[i].second));
      }
    }
  }
  if (eyes.size() < 2) throw std::runtime_error("--through names rooms that are already where the walk starts");

  // Every frame's camera first (a frame whose eye would leave free space is an error
  // before anything is written), looking a metre ahead along the path.
  Walk walk;
  CellId hint = kNoCell;
  Vec3 last_dir = eyes[1] - eyes[0];
  for (size_t k = 0; k < eyes.size(); ++k) {
    size_t j = k;
    while (j + 1 < eyes.size() && length(eyes[j] - eyes[k]) < 1.0) ++j;
    Vec3 dir = eyes[j] - eyes[k];
    dir.z = 0;
    if (length(dir) > 1e-6) last_dir = dir;
    const Location at = c.locate(eyes[k], hint);
    const std::string frame = "frame " + std::to_string(k + 1) + " of the path: ";
    if (at.what != Location::What::Cell)
      throw std::runtime_error(frame + "the eye is " +
                               (at.what == Location::What::Solid ? "inside " + at.solid : std::string("outside the far box")));
    WalkFrame f;
    f.camera = Camera::look_at(eyes[k], looks.empty() ? eyes[k] + last_dir : looks[k], opt.fov, s.width, s.height);
    f.cell = hint = at.cell;
    walk.frames.push_back(f);
    if (s.stereo) {
      const StereoRig rig = stereo_rig(c, f.camera, s.eyes);
      if (rig.problem != StereoRig::Problem::None) throw std::runtime_error(frame + rig.message());
      walk.left.push_back({rig.left, rig.left_at.cell});
      walk.right.push_back({rig.right, rig.right_at.cell});
    }
  }
  return walk;
}

/// Draws frames and writes them: what every rank prepares once (the line scene, or the
/// placed objects and the scene's effects) and then does for each frame it is given.
class FrameWriter {
 public:
  FrameWriter(const CellComplex& c, const PathSettings& s, const Walk& walk, const std::string& pattern)
      : c_(c), s_(s), walk_(walk), pattern_(pattern) {
    if (s.svg) {
      scene_ = prepare_line_scene(c, place_objects(c, &said_));
    } else {
      objects_ = place_objects(c, &said_, s.halftone.detail_samples > 0);
      effects_.emplace(prepare_effects(c, objects_, s.halftone, s.kernel));  // once for every frame
    }
  }

  std::string file(int64_t k) const { return frame_path(pattern_, int(k), int(walk_.frames.size())); }
  /// What reading the objects' meshes let pass (a missing MTL, an unreadable model).
  const std::vector<std::string>& warnings() const { return said_; }

  void write(int64_t k) {
    const size_t i = size_t(k);
    if (s_.svg && s_.stereo) {
      write_stereo_drawing(draw(walk_.left[i]), draw(walk_.right[i]), s_.layout, file(k));
    } else if (s_.svg) {
      write_drawing(draw(walk_.frames[i]), file(k));
    } else if (s_.stereo) {
      render(walk_.left[i], picture_);
      render(walk_.right[i], second_);
      write_image(stereo_composite(picture_, second_, s_.composite), file(k));
    } else {
      render(walk_.frames[i], picture_);
      write_image(picture_, file(k));
    }
  }

 private:
  Drawing draw(const WalkFrame& f) const {
    return draw_view(c_, scene_, f.camera, find_visible(c_, f.camera, f.cell, exact_masks(s_.search)));
  }
  void render(const WalkFrame& f, Image& out) {
    TraverseParams search = s_.search;  // for this half-tone: pieces of view between its samples show nothing
    search.samples_per_side = samples_per_side(s_.halftone.samples);
    render_view(c_, objects_, *effects_, f.camera, searches_.find(c_, f.camera, f.cell, search), s_.halftone, out,
                storage_);
  }

  const CellComplex& c_;
  const PathSettings& s_;
  const Walk& walk_;
  std::string pattern_;
  LineScene scene_;
  std::vector<PlacedObject> objects_;
  std::vector<std::string> said_;
  std::optional<SceneEffects> effects_;
  Image picture_, second_;
  FrameStorage storage_;  ///< the half-tone's arrays, kept from frame to frame
  FrameSearches searches_{s_.halftone.threads};  ///< side by side after a long search (strips.h)
};

/// Makes DIR this walk's: removes the frames, the film and the temporary files an earlier
/// walk left there (only those: a frame is "frame-" digits ".png" or ".svg"). With
/// `resume`, the frames this walk writes are kept. Returns the frames still to render.
std::vector<int64_t> claim_output(const fs::path& dir, const std::vector<std::string>& names, bool resume) {
  static const std::regex walk_file(R"((frame-[0-9]+\.(png|svg)|walk\.mp4)|\.(frame-[0-9]+\.(png|svg)|walk\.mp4)\.tmp-[A-Za-z0-9]{6}|walk\.mp4\.part)");
  const std::set<std::string> ours(names.begin(), names.end());
  std::vector<int64_t> todo;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (!std::regex_match(name, walk_file) || !fs::is_regular_file(e.symlink_status())) continue;
    if (resume && ours.count(name)) continue;
    if (!fs::remove(e.path(), ec) || ec)
      throw std::runtime_error("cannot remove " + e.path().string() + " (left by an earlier walk): " + ec.message());
  }
  if (ec) throw std::runtime_error("cannot read the output directory " + dir.string() + ": " + ec.message());
  for (size_t k = 0; k < names.size(); ++k)
    if (!resume || !fs::is_regular_file(dir / names[k], ec)) todo.push_back(int64_t(k));
  return todo;
}

}  // namespace

int run_path(const PathOptions& opt) {
  MpiWalk mpi;  // rank 0 of 1 unless started by mpirun or srun

  // Rank 0 reads the plan, works out the walk and readies DIR; the others get the
  // complex and the walk from it, as bytes.
  std::optional<LoadedPlan> plan;
  std::optional<CellComplex> received;
  std::optional<PathSettings> settings;
  Walk walk;
  std::optional<FrameWriter> writer;
  std::vector<int64_t> todo;
  const fs::path dir(opt.out_dir);
  const std::string pattern = (dir / ("frame." + opt.format)).string();
  std::string shared;
  auto broadcast_start = std::chrono::steady_clock::now();
  double serialised_s = 0;  // of the broadcast, making the complex's bytes
  if (mpi.rank() == 0) {
    try {
      plan.emplace(load_plan_source(opt.plan, opt.import));
      settings.emplace(path_settings(opt, mpi));
      walk = plan_walk(plan->complex, opt, *settings);
      writer.emplace(plan->complex, *settings, walk, pattern);
      print_warnings(plan->path, writer->warnings());  // once, by rank 0
      std::error_code ec;
      fs::create_directories(dir, ec);
      if (ec) throw std::runtime_error("cannot create the output directory " + opt.out_dir + ": " + ec.message());
      std::vector<std::string> names;
      for (size_t k = 0; k < walk.frames.size(); ++k) names.push_back(fs::path(writer->file(int64_t(k))).filename().string());
      todo = claim_output(dir, names, opt.resume);
      if (opt.resume)
        std::cout << "resuming: " << walk.frames.size() - todo.size() << " of " << walk.frames.size()
                  << " frames are already in " << opt.out_dir << "\n";
      if (mpi.ranks() > 1) {
        broadcast_start = std::chrono::steady_clock::now();
        const std::string cells = cells_bytes(plan->complex);
        serialised_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - broadcast_start).count();
        const uint64_t n = cells.size();
        shared.append(reinterpret_cast<const char*>(&n), sizeof n);
        shared += cells;
        append_frames(shared, walk.frames);
        append_frames(shared, walk.left);
        append_frames(shared, walk.right);
      }
    } catch (...) {
      mpi.broadcast(shared, false);  // the others stop; this rank says why
      throw;
    }
  }
  // Rank 0 failed, and says so. The others leave quietly, with status 0: a rank leaving
  // with another status has mpirun end the job at once, and it could end rank 0 before it
  // has said why (it says so after MPI_Finalize). The job's status is rank 0's, 2.
  if (!mpi.broadcast(shared, true)) return 0;
  const double broadcast_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - broadcast_start).count();
  const size_t broadcast_bytes = shared.size();

  // Every other rank: the complex and the walk from rank 0's bytes. A failure here is
  // reported (by rank 0) as this rank's failure at the first frame it is given.
  std::string setup_error;
  if (mpi.rank() != 0) {
    try {
      uint64_t n = 0;
      if (shared.size() < sizeof n) throw std::runtime_error("the walk's bytes are cut short");
      std::memcpy(&n, shared.data(), sizeof n);
      if (n > shared.size() - sizeof n) throw std::runtime_error("the walk's bytes are cut short");
      received.emplace(cells_from_bytes(std::string_view(shared).substr(sizeof n, size_t(n)), "the complex from rank 0"));
      size_t at = sizeof n + size_t(n);
      walk.frames = take_frames(shared, at);
      walk.left = take_frames(shared, at);
      walk.right = take_frames(shared, at);
      shared = std::string();
      settings.emplace(path_settings(opt, mpi));
      writer.emplace(*received, *settings, walk, pattern);
    } catch (const std::exception& e) {
      setup_error = e.what();
    }
  }

  // Rank 0 makes the film from the frames in order (a frame that exists is whole). With
  // threads to spare, on a thread of its own while the ranks render: by the last frame most
  // of the film is encoded. On one thread (--threads 1, or a rank's share of a machine with
  // as many ranks as cores) between its own frames instead, the encoder on that thread too,
  // so that the process keeps to the one core it was given.
  const int n = int(walk.frames.size());
  const fs::path mp4 = dir / "walk.mp4";
  const bool films = mpi.rank() == 0 && !settings->svg;
  const int threads = settings ? settings->halftone.threads : 1;
  const bool film_between_frames = films && threads == 1;
  std::atomic<bool> walk_over{false};
  std::string film_error;
  std::optional<Film> film;
  int filmed = 0;  // frames in the film so far
  // Adds the frames from `filmed` on while they exist; with `wait`, waits for each until the
  // walk is over. False when the walk stopped short of them.
  auto film_frames = [&](bool wait) {
    for (; filmed < n; ++filmed) {
      const std::string frame = frame_path(pattern, filmed, n);
      std::error_code ec;
      while (!fs::is_regular_file(frame, ec)) {
        if (!wait) return true;
        if (walk_over && !fs::is_regular_file(frame, ec)) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      const Image picture = read_image(frame);
      if (!film) {
        FilmOptions options;
        options.threads = threads;
        film.emplace(mp4.string(), picture.width, picture.height, options);
      }
      film->add(picture);
    }
    return true;
  };
  // film_frames, its failure kept in film_error; with `to_the_end`, every frame waited for
  // and the film finished.
  auto make_film = [&](bool to_the_end) {
    try {
      if (film_frames(to_the_end) && to_the_end && film) film->finish();
    } catch (const std::exception& e) {
      film_error = e.what();
    }
  };
  std::thread filming;
  if (films && !film_between_frames) filming = std::thread([&] { make_film(true); });
  struct JoinFilm {  // on every way out, an exception from a frame included
    std::atomic<bool>& over;
    std::thread& thread;
    ~JoinFilm() {
      over = true;
      if (thread.joinable()) thread.join();
    }
  } join_film{walk_over, filming};

  const bool terminal = ::isatty(STDERR_FILENO);
  const auto t0 = std::chrono::steady_clock::now();
  auto last_line = t0;
  const int64_t total = int64_t(todo.size());
  const std::string failure = mpi.share(
      todo, int64_t(walk.frames.size()),
      [&](int64_t k) {
        if (!writer) throw std::runtime_error(setup_error);
        writer->write(k);
        if (film_between_frames && film_error.empty()) make_film(false);
      },
      [&](int64_t done) {
        const auto now = std::chrono::steady_clock::now();
        // A terminal sees every frame; a log (an MPI job's) a line every ten seconds and the last.
        if (terminal || (mpi.ranks() > 1 && (done == total || now - last_line > std::chrono::seconds(10)))) {
          progress(done, total, std::chrono::duration<double>(now - t0).count(), terminal);
          last_line = now;
        }
      });
  const double frames_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  walk_over = true;
  if (filming.joinable()) filming.join();
  if (film_between_frames && failure.empty() && film_error.empty()) make_film(true);
  if (mpi.rank() != 0) return 0;  // rank 0 reports a failure, and its status is the job's (as above)
  if (!failure.empty()) throw std::runtime_error(failure + "; the frames done are complete: run again with --resume to finish the walk");

  char took[32];
  std::snprintf(took, sizeof took, "%.2f", frames_s);
  std::cout << "wrote " << n << " frames in " << took << " s: " << frame_path(pattern, 0, n) << " ... "
            << frame_path(pattern, n - 1, n);
  if (mpi.ranks() > 1) {
    char sent[128];
    std::snprintf(sent, sizeof sent, "%.3g MB broadcast in %.3g s (%.3g s making the bytes)", double(broadcast_bytes) / 1e6,
                  broadcast_s, serialised_s);
    std::string each;
    for (int64_t r : mpi.rendered()) each += (each.empty() ? "" : " + ") + std::to_string(r);
    std::cout << " (" << todo.size() << " rendered on " << mpi.ranks() << " ranks: " << each << "; the complex and cameras, "
              << sent << ")";
  }
  std::cout << "\n";
  if (!settings->svg) {
    if (!film_error.empty()) throw std::runtime_error(film_error + " (the frames are complete)");
    std::cout << "wrote " << mp4.string() << "\n";
  }
  return 0;
}

}  // namespace avenues::app
