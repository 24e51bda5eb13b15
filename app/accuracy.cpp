// Avenues — `avenues bench accuracy` (see accuracy.h): studies of error against time.
#include "app/accuracy.h"
#include "core/number_format.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/subprocess.h"
#include "cells/build_cells.h"
#include "plans/formats/doom_map.h"
#include "plans/plan.h"
#include "render/halftone.h"
#include "render/raster_srgb.h"
#include "render/view_lines.h"
#include "visibility/camera.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

#ifndef AVENUES_SOURCE_DIR
#define AVENUES_SOURCE_DIR ""
#endif

namespace avenues::app {
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

fs::path source_dir() {
  const fs::path here = AVENUES_SOURCE_DIR;
  if (!here.empty() && fs::is_directory(here / "plans")) return here;
  return fs::current_path();
}

struct Subject {
  std::string name;
  CellComplex complex;
};

/// The bundled plans (and, for the kernel study, their far copies and Freedoom maps).
std::vector<Subject> subjects(bool quick, bool far_copies, bool doom) {
  std::vector<Subject> out;
  std::vector<fs::path> plans;
  for (const auto& e : fs::directory_iterator(source_dir() / "plans"))
    if (e.path().extension() == ".toml") plans.push_back(e.path());
  std::sort(plans.begin(), plans.end());
  if (quick && plans.size() > 3) plans.resize(3);
  for (const fs::path& p : plans) {
    Plan plan = read_plan(p.string());
    out.push_back({p.stem().string(), build_cells(plan)});
    if (far_copies) out.push_back({p.stem().string() + " at (500000, 5400000)", build_cells(moved(plan, {500000, 5400000}))});
  }
  if (doom) {
    const std::string wad = "/usr/share/games/doom/freedoom2.wad";
    if (fs::exists(wad)) {
      std::vector<std::string> maps = doom_map_names(wad);
      if (maps.size() > (quick ? 1u : 4u)) maps.resize(quick ? 1 : 4);
      for (const std::string& m : maps) out.push_back({"freedoom2 " + m, build_cells(read_doom_map(wad, m))});
    } else {
      std::cout << "  (Freedoom not installed: " << wad << " missing; its maps are left out)\n";
    }
  }
  return out;
}

/// A random eye in a random free cell of a room (or of any kind if there is no room),
/// 20 cm or more from its faces, looking anywhere level-ish.
bool random_camera(const CellComplex& c, std::mt19937& rng, Camera& cam, CellId& cell) {
  std::vector<CellId> rooms;
  for (CellId i = 0; i < CellId(c.cells.size()); ++i)
    if (c.cells[size_t(i)].kind == CellKind::Room && c.cells[size_t(i)].z1 - c.cells[size_t(i)].z0 > 0.6) rooms.push_back(i);
  if (rooms.empty())
    for (CellId i = 0; i < CellId(c.cells.size()); ++i) rooms.push_back(i);
  std::uniform_real_distribution<double> u(0, 1);
  for (int attempt = 0; attempt < 200; ++attempt) {
    const CellId id = rooms[size_t(u(rng) * double(rooms.size())) % rooms.size()];
    const Cell& k = c.cells[size_t(id)];
    const Box3 b = k.bounds();
    const double zspan = std::min(k.z1 - k.z0 - 0.4, 1.6);
    if (zspan <= 0) continue;
    const Vec3 p{b.lo.x + u(rng) * (b.hi.x - b.lo.x), b.lo.y + u(rng) * (b.hi.y - b.lo.y), k.z0 + 0.2 + u(rng) * zspan};
    if (!k.contains(p, -0.2)) continue;
    cam = Camera::yaw_pitch(p, 360 * u(rng), -15 + 30 * u(rng), u(rng) < 0.5 ? 60 : 90, 1280, 720);
    cell = id;
    return true;
  }
  return false;
}

/// Distance [px] from p to the boundary of polygon q.
double to_boundary(Vec2 p, const std::vector<Vec2>& q) {
  double best = HUGE_VAL;
  for (size_t i = 0; i < q.size(); ++i) best = std::min(best, distance_to_segment(p, q[i], q[(i + 1) % q.size()]));
  return best;
}

std::vector<Vec2> to_raster(const Camera& cam, const std::vector<Vec2>& mask) {
  std::vector<Vec2> out;
  out.reserve(mask.size());
  for (Vec2 v : mask) out.push_back(cam.raster_from_image(v));
  return out;
}

double drawn_length(const Drawing& d) {
  double s = 0;
  for (const Stroke& k : d.strokes) s += length(k.b - k.a);
  return s;
}

/// An avenue's identity across kernels: its cell and the portals crossed to reach it.
std::vector<int32_t> avenue_key(const VisibleSet& v, int a) {
  std::vector<int32_t> key = v.path(a);
  key.push_back(v.avenues[size_t(a)].cell);
  return key;
}

// --- study 1: kernels ---------------------------------------------------------------

struct KernelRow {
  Kernel kernel;
  std::vector<double> micros;   ///< per view
  long views = 0;
  long cells_wrong = 0;         ///< missing or extra, summed over views
  long avenues_wrong = 0;       ///< avenues missing or extra
  long vertices = 0;            ///< mask vertices compared
  long vertices_off = 0;        ///< of those, off by more than 0.5 px
  double worst_px = 0;          ///< largest vertex error [px]
  long drawings_differ = 0;     ///< views whose drawn line length differs by > 0.5 px
  double worst_line_px = 0;     ///< largest difference in drawn line length [px]
  std::map<std::string, long> wrong_by_subject;
};

std::vector<KernelRow> kernel_study(const std::vector<Subject>& subs, int eyes, unsigned seed) {
  const Kernel kernels[] = {Kernel::Float, Kernel::Double, Kernel::Filtered, Kernel::Exact};
  std::vector<KernelRow> rows;
  for (Kernel k : kernels) rows.push_back({k, {}, 0, 0, 0, 0, 0, 0, 0, 0, {}});
  std::mt19937 rng(seed);
  for (const Subject& s : subs) {
    const LineScene scene = prepare_line_scene(s.complex);
    for (int e = 0; e < eyes; ++e) {
      Camera cam;
      CellId cell = kNoCell;
      if (!random_camera(s.complex, rng, cam, cell)) break;
      const VisibleSet ref = find_visible(s.complex, cam, cell, Kernel::Exact);
      std::map<std::vector<int32_t>, int> ref_avenues;
      for (int a = 0; a < int(ref.avenues.size()); ++a) ref_avenues[avenue_key(ref, a)] = a;
      const double ref_lines = drawn_length(draw_view(s.complex, scene, cam, ref));
      for (KernelRow& row : rows) {
        const VisibleSet v = find_visible(s.complex, cam, cell, row.kernel);
        row.micros.push_back(v.micros);
        ++row.views;
        std::vector<CellId> diff;
        std::set_symmetric_difference(v.cells.begin(), v.cells.end(), ref.cells.begin(), ref.cells.end(),
                                      std::back_inserter(diff));
        row.cells_wrong += long(diff.size());
        row.wrong_by_subject[s.name] += long(diff.size());
        long matched = 0;
        for (int a = 0; a < int(v.avenues.size()); ++a) {
          auto it = ref_avenues.find(avenue_key(v, a));
          if (it == ref_avenues.end()) continue;
          ++matched;
          const auto mine = to_raster(cam, v.avenues[size_t(a)].mask);
          const auto theirs = to_raster(cam, ref.avenues[size_t(it->second)].mask);
          if (mine.size() < 3 || theirs.size() < 3) continue;
          for (Vec2 p : mine) {
            const double d = to_boundary(p, theirs);
            ++row.vertices;
            row.vertices_off += d > 0.5;
            row.worst_px = std::max(row.worst_px, d);
          }
          for (Vec2 p : theirs) {
            const double d = to_boundary(p, mine);
            ++row.vertices;
            row.vertices_off += d > 0.5;
            row.worst_px = std::max(row.worst_px, d);
          }
        }
        row.avenues_wrong += long(v.avenues.size() - size_t(matched)) + long(ref.avenues.size() - size_t(matched));
        const double dl = std::fabs(drawn_length(draw_view(s.complex, scene, cam, v)) - ref_lines);
        row.drawings_differ += dl > 0.5;
        row.worst_line_px = std::max(row.worst_line_px, dl);
      }
    }
  }
  return rows;
}

// --- study 2: the half-tone renderer ------------------------------------------------

struct RenderRow {
  std::string view;
  int width = 0, height = 0, samples = 1;
  ShadingModel shading = ShadingModel::Flat;
  double ms = 0;         ///< median render time
  double rms = 0;        ///< [8-bit sRGB levels] against the 64-sample reference
  double off_pct = 0;    ///< % of samples off by more than 2 levels
};

/// The 64-sample reference: 16 samples at twice the resolution, averaged 2 × 2 in linear light.
Image reference(const CellComplex& c, const Camera& cam, const HalftoneOptions& base) {
  Camera big = cam;
  big.width = 2 * cam.width;
  big.height = 2 * cam.height;
  const VisibleSet v = find_visible(c, big, c.locate(cam.eye).cell, Kernel::Double);
  HalftoneOptions o = base;
  o.samples = 16;
  const Image hi = render_view(c, big, v, o);
  Image out;
  out.resize(cam.width, cam.height, hi.channels);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      for (int ch = 0; ch < hi.channels; ++ch) {
        double s = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx)
            s += linear_from_srgb(hi.data[(size_t(2 * y + dy) * size_t(hi.width) + size_t(2 * x + dx)) * size_t(hi.channels) + size_t(ch)] / 255.0);
        out.data[(size_t(y) * size_t(cam.width) + size_t(x)) * size_t(hi.channels) + size_t(ch)] =
            uint8_t(std::lround(255 * srgb_from_linear(s / 4)));
      }
  return out;
}

std::vector<RenderRow> render_study(const std::vector<Subject>& subs, bool quick) {
  std::vector<RenderRow> rows;
  const std::vector<std::pair<int, int>> sizes =
      quick ? std::vector<std::pair<int, int>>{{320, 180}, {640, 360}}
            : std::vector<std::pair<int, int>>{{640, 360}, {1280, 720}, {1920, 1080}};
  const int repeats = quick ? 3 : 5;
  for (const Subject& s : subs) {
    const Viewpoint vp = default_viewpoint(s.complex);
    for (auto [w, h] : sizes)
      for (ShadingModel m : {ShadingModel::Flat, ShadingModel::Smooth}) {
        const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, w, h);
        HalftoneOptions base;
        base.shading.model = m;
        base.threads = 1;  // one thread: the curve is about arithmetic, not the machine's cores
        const Image ref = reference(s.complex, cam, base);
        const VisibleSet v = find_visible(s.complex, cam, s.complex.locate(cam.eye).cell, Kernel::Double);
        for (int samples : {1, 4, 16}) {
          HalftoneOptions o = base;
          o.samples = samples;
          std::vector<double> times;
          Image img;
          for (int r = 0; r < repeats; ++r) {
            const auto t0 = Clock::now();
            img = render_view(s.complex, cam, v, o);
            times.push_back(ms_since(t0));
          }
          double sq = 0;
          long off = 0;
          for (size_t i = 0; i < img.data.size(); ++i) {
            const double d = double(img.data[i]) - double(ref.data[i]);
            sq += d * d;
            off += std::fabs(d) > 2;
          }
          const double n = double(img.data.size());
          rows.push_back({s.name, w, h, samples, m, median(times), std::sqrt(sq / n), 100.0 * double(off) / n});
        }
      }
  }
  return rows;
}

// --- study 3: tessellation of curved walls ------------------------------------------

struct TessRow {
  double tolerance = 0;   ///< [m] asked
  double sagitta = 0;     ///< [m] largest measured
  int pieces = 0;         ///< straight pieces from arcs
  double build_ms = 0;    ///< median decomposition time
  size_t cells = 0, portals = 0;
  double traverse_us = 0; ///< median traversal of the default view
};

/// Largest sagitta of the arc pieces: for three consecutive points of one arc (equal
/// chords), the circle through them is the arc's, and a chord c of radius r leaves
/// r − √(r² − c²/4) between itself and the circle.
double largest_sagitta(const Plan& p, int& pieces) {
  double worst = 0;
  pieces = 0;
  for (const Wall& w : p.walls)
    for (size_t i = 0; i + 1 < w.centre.size(); ++i) {
      if (!w.from_arc[i]) continue;
      ++pieces;
      if (i + 2 >= w.centre.size() || !w.from_arc[i + 1]) continue;
      const Vec2 a = w.centre[i], b = w.centre[i + 1], c = w.centre[i + 2];
      const double ab = length(b - a), bc = length(c - b), ca = length(a - c);
      if (std::fabs(ab - bc) > 1e-9 * std::max(ab, bc)) continue;  // two different arcs meet at b
      const double area2 = std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
      if (area2 <= 0) continue;
      const double r = ab * bc * ca / (2 * area2);
      worst = std::max(worst, r - std::sqrt(std::max(0.0, r * r - ab * ab / 4)));
    }
  return worst;
}

std::vector<TessRow> tessellation_study(bool quick) {
  const fs::path path = source_dir() / "plans" / "curved-walls.toml";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const std::string key = "arc_tolerance = 0.01";
  const size_t at = text.find(key);
  if (at == std::string::npos) throw std::runtime_error(path.string() + ": no line '" + key + "' to vary");
  const std::vector<double> tolerances =
      quick ? std::vector<double>{0.1, 0.01, 0.001} : std::vector<double>{0.1, 0.03, 0.01, 0.003, 0.001, 0.0003};
  std::vector<TessRow> rows;
  for (double tol : tolerances) {
    std::string t = text;
    t.replace(at, key.size(), "arc_tolerance = " + format_number("%.6g", tol));
    const Plan plan = parse_plan(t, path.string());
    TessRow row;
    row.tolerance = tol;
    row.sagitta = largest_sagitta(plan, row.pieces);
    std::vector<double> builds, walks;
    CellComplex c;
    for (int r = 0; r < (quick ? 2 : 5); ++r) {
      const auto t0 = Clock::now();
      c = build_cells(plan);
      builds.push_back(ms_since(t0));
    }
    const Viewpoint vp = default_viewpoint(c);
    const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 1280, 720);
    const CellId eye = c.locate(cam.eye).cell;
    for (int r = 0; r < 50; ++r) walks.push_back(find_visible(c, cam, eye, Kernel::Double).micros);
    row.build_ms = median(builds);
    row.cells = c.cells.size();
    row.portals = c.portals.size();
    row.traverse_us = median(walks);
    rows.push_back(row);
  }
  return rows;
}

// --- study 4: the hull search's pictures ----------------------------------------------

struct HullRow {
  std::string plan;
  int views = 0;
  std::vector<double> merged_ms, hull_ms;  ///< per view: search and half-tone
  long samples = 0, differ = 0, off = 0;   ///< samples compared, differing at all, by more than 2 levels
  double sq = 0;                           ///< sum of squared differences [levels²]
  long merged_cells = 0, hull_cells = 0, merged_avenues = 0, hull_avenues = 0;
};

/// Each view searched and drawn twice, one thread, one sample: the merged search and its
/// masked half-tone, then the hull search and its picture resolved by depth.
std::vector<HullRow> hull_study(const std::vector<Subject>& subs, int eyes, unsigned seed, bool quick) {
  std::vector<HullRow> rows;
  std::mt19937 rng(seed + 4);
  for (const Subject& s : subs) {
    HullRow row;
    row.plan = s.name;
    std::vector<std::pair<Camera, CellId>> views;
    const Viewpoint vp = default_viewpoint(s.complex);
    const Camera first = Camera::look_at(vp.eye, vp.look, vp.fov_deg, quick ? 320 : 1280, quick ? 180 : 720);
    views.push_back({first, s.complex.locate(first.eye).cell});
    for (int e = 0; e < eyes; ++e) {
      Camera cam;
      CellId cell = kNoCell;
      if (!random_camera(s.complex, rng, cam, cell)) break;
      if (quick) cam.width = 320, cam.height = 180;
      views.push_back({cam, cell});
    }
    HalftoneOptions o;
    o.threads = 1;
    for (const auto& [cam, cell] : views) {
      if (cell == kNoCell) continue;
      TraverseParams p;
      p.merge_pieces = true;
      Image pictures[2];
      for (int h = 0; h < 2; ++h) {
        p.hull_pieces = h == 1;
        const auto t0 = Clock::now();
        const VisibleSet v = find_visible(s.complex, cam, cell, p);
        pictures[h] = render_view(s.complex, cam, v, o);
        (h ? row.hull_ms : row.merged_ms).push_back(ms_since(t0));
        (h ? row.hull_cells : row.merged_cells) += long(v.cells.size());
        (h ? row.hull_avenues : row.merged_avenues) += long(v.avenues.size());
      }
      for (size_t i = 0; i < pictures[0].data.size(); ++i) {
        const double d = double(pictures[0].data[i]) - double(pictures[1].data[i]);
        row.sq += d * d;
        row.differ += d != 0;
        row.off += std::fabs(d) > 2;
      }
      row.samples += long(pictures[0].data.size());
      ++row.views;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

// --- plots ---------------------------------------------------------------------------

void write_text(const fs::path& p, const std::string& text) { write_file_atomically(p.string(), text); }

/// Runs gnuplot on `script` (written beside its data), which writes `svg`. By argv, in the
/// script's folder: the scripts name their files without a folder, so no path the user chose
/// reaches gnuplot's command language (which can run shell commands) or a shell.
void gnuplot(const fs::path& script, const fs::path& svg) {
  const fs::path dir = script.has_parent_path() ? script.parent_path() : fs::path(".");
  ProgramResult r;
  try {
    r = run_program({"gnuplot", script.filename().string()}, dir.string());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) + " (.ci/install-deps installs gnuplot-nox)");
  }
  if (r.status != 0 || !fs::exists(svg))
    throw std::runtime_error("gnuplot failed on " + script.string() + (r.output.empty() ? "" : ": " + r.output));
}

std::string plot_head(const fs::path& svg, const std::string& title, const std::string& xlabel, const std::string& ylabel) {
  return "set terminal svg size 720,440 dynamic font 'sans,11' background '#ffffff'\n"
         "set output '" + svg.filename().string() + "'\n"
         "set title '" + title + "'\nset xlabel '" + xlabel + "'\nset ylabel '" + ylabel + "'\n"
         "set grid\nset key outside right top\nset logscale x\nset format x '%g'\nset format y '%g'\n";
}

}  // namespace

int run_bench_accuracy(const AccuracyOptions& opt) {
  const auto t_all = Clock::now();
  const fs::path report = opt.report;
  const fs::path figs = (report.has_parent_path() ? report.parent_path() : fs::path(".")) / "accuracy";
  fs::create_directories(figs);
  const std::string command = std::string("avenues bench accuracy") + (opt.quick ? " --quick" : "") +
                              (opt.report != "docs/ACCURACY.md" ? " --report " + opt.report : "");

  std::cout << "kernels: reading plans ...\n";
  const int eyes = opt.quick ? 6 : 40;
  const std::vector<Subject> ksubs = subjects(opt.quick, true, true);
  std::cout << "kernels: " << ksubs.size() << " plans and maps, " << eyes << " random eyes each\n";
  const std::vector<KernelRow> krows = kernel_study(ksubs, eyes, opt.seed);
  std::cout << "renderer: ...\n";
  const std::vector<Subject> rsubs = subjects(true, false, false);
  const std::vector<Subject> rsel(rsubs.begin(), rsubs.begin() + std::min<size_t>(rsubs.size(), opt.quick ? 1 : 3));
  const std::vector<RenderRow> rrows = render_study(rsel, opt.quick);
  std::cout << "tessellation: ...\n";
  const std::vector<TessRow> trows = tessellation_study(opt.quick);
  std::cout << "the hull search's pictures: ...\n";
  const int hull_eyes = opt.quick ? 2 : 10;
  const std::vector<Subject> hsubs = subjects(opt.quick, false, true);
  const std::vector<HullRow> hrows = hull_study(hsubs, hull_eyes, opt.seed, opt.quick);

  // Data and plots.
  {
    std::string dat = "# kernel median_us errors_per_view\n";
    for (const KernelRow& r : krows) {
      const double errs = double(r.cells_wrong + r.vertices_off + r.drawings_differ) / double(std::max(1L, r.views));
      dat += std::string(to_string(r.kernel)) + " " + format_number("%.4g", median(r.micros)) + " " + format_number("%.6g", std::max(errs, 1e-4)) + "\n";
    }
    write_text(figs / "kernels.dat", dat);
    const fs::path svg = figs / "kernels.svg";
    write_text(figs / "kernels.gp",
               plot_head(svg, "Visibility kernels: time against error (0 errors drawn at 1e-4)",
                         "median traversal time per view [µs]", "errors per view (cells + mask vertices > 0.5 px + drawings)") +
                   "set logscale y\nset offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1\n"
                   "plot 'kernels.dat' using 2:3 with points pt 7 ps 1.5 notitle, '' using 2:3:1 with labels offset 0,1 notitle\n");
    gnuplot(figs / "kernels.gp", svg);
  }
  {
    std::string dat;
    std::string plots;
    int block = 0;
    for (ShadingModel m : {ShadingModel::Flat, ShadingModel::Smooth})
      for (const RenderRow& r : rrows) {
        if (r.shading != m || r.samples != 1) continue;
        // One series per (view, size, shading): samples 1, 4, 16 along it.
        dat += "# " + r.view + " " + std::to_string(r.width) + "x" + std::to_string(r.height) + " " + to_string(m) + "\n";
        for (const RenderRow& q : rrows)
          if (q.view == r.view && q.width == r.width && q.shading == m)
            dat += format_number("%.4g", q.ms) + " " + format_number("%.4g", std::max(q.rms, 1e-3)) + " " + std::to_string(q.samples) + "\n";
        dat += "\n\n";
        // Colour by view, dashes by shading, point by size: 18 series stay told apart.
        int view_index = 0, size_index = 0;
        std::vector<std::string> views;
        std::vector<int> widths;
        for (const RenderRow& q : rrows) {
          if (std::find(views.begin(), views.end(), q.view) == views.end()) views.push_back(q.view);
          if (std::find(widths.begin(), widths.end(), q.width) == widths.end()) widths.push_back(q.width);
        }
        view_index = int(std::find(views.begin(), views.end(), r.view) - views.begin());
        size_index = int(std::find(widths.begin(), widths.end(), r.width) - widths.begin());
        plots += std::string(plots.empty() ? "plot " : ", ") + "'render.dat' index " +
                 std::to_string(block) + " using 1:2 with linespoints lc " + std::to_string(view_index + 1) + " dt " +
                 (m == ShadingModel::Flat ? "1" : "2") + " pt " + std::to_string(5 + 2 * size_index) + " title '" +
                 r.view + " " + std::to_string(r.width) + "×" + std::to_string(r.height) + " " + to_string(m) +
                 "', '' index " + std::to_string(block) + " using 1:2:3 with labels offset 1,0.6 notitle";
        ++block;
      }
    write_text(figs / "render.dat", dat);
    const fs::path svg = figs / "render.svg";
    write_text(figs / "render.gp",
               plot_head(svg, "Half-tone renderer: time against error (labels: samples per pixel)", "render time [ms], 1 thread",
                         "RMS error against 64 samples [8-bit sRGB levels]") +
                   "set logscale y\n" + plots + "\n");
    gnuplot(figs / "render.gp", svg);
  }
  {
    std::string dat = "# tolerance_m build_ms sagitta_mm cells\n";
    for (const TessRow& r : trows)
      dat += format_number("%.6g", r.tolerance) + " " + format_number("%.4g", r.build_ms) + " " + format_number("%.6g", std::max(r.sagitta * 1000, 1e-6)) + " " +
             std::to_string(r.cells) + "\n";
    write_text(figs / "tessellation.dat", dat);
    const fs::path svg = figs / "tessellation.svg";
    write_text(figs / "tessellation.gp",
               plot_head(svg, "Curved walls: decomposition time against geometric error (labels: tolerance [m])",
                         "decomposition time [ms]", "largest sagitta [mm]") +
                   "set logscale y\nset offsets graph 0.1, graph 0.1, graph 0.1, graph 0.1\n"
                   "plot 'tessellation.dat' using 2:3 with linespoints pt 7 title 'curved-walls', '' using 2:3:1 with labels offset 0,1 notitle\n");
    gnuplot(figs / "tessellation.gp", svg);
  }

  // The report.
  const fs::path rel = fs::path("accuracy");
  std::ostringstream md;
  md << "# What accuracy costs in time\n\n"
     << "Generated by `" << command << "` (" << (opt.quick ? "the quick version" : "the full version")
     << "; seed " << opt.seed << ") in " << format_number("%.0f", ms_since(t_all) / 1000) << " s. Every figure below is "
     << "regenerated by that one command; the plots' data and gnuplot scripts are beside them in `" << (figs).string()
     << "/`. Times are medians on the machine that ran it and vary with its load; compare rows with one another, "
     << "not with another run.\n\n";

  md << "## 1. Visibility kernels\n\n"
     << "Random eyes (" << eyes << " per plan, in room cells, 20 cm or more from their faces, looking anywhere within "
     << "±15° of level, 60° or 90° wide, 1280 × 720) in: ";
  for (size_t i = 0; i < ksubs.size(); ++i) md << (i ? ", " : "") << ksubs[i].name;
  md << ". Each view is traversed by every kernel and compared with the exact one (GMP rationals): cells visible "
        "in one and not the other; avenues (a cell reached by one sequence of portals) found by one only; for the "
        "avenues both found, every mask vertex's distance to the other mask's outline in pixels; and the hidden-line "
        "drawing, by total drawn length.\n\n"
     << "![kernels](" << (rel / "kernels.svg").string() << ")\n\n"
     << "| kernel | views | median µs/view | cells missing or extra | avenues missing or extra | mask vertices off > 0.5 px | worst vertex [px] | drawings differing > 0.5 px | worst drawing difference [px] |\n"
     << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  const double exact_us = median(krows.back().micros);
  for (const KernelRow& r : krows)
    md << "| " << to_string(r.kernel) << " | " << r.views << " | " << format_number("%.2f", median(r.micros)) << " ("
       << format_number("%.3g", median(r.micros) / std::max(exact_us, 1e-9)) << " of exact's) | " << r.cells_wrong << " | "
       << r.avenues_wrong << " | " << r.vertices_off << " of " << r.vertices << " | " << format_number("%.3g", r.worst_px) << " | "
       << r.drawings_differ << " | " << format_number("%.3g", r.worst_line_px) << " |\n";
  md << "\nCells wrong, by plan (kernels with any):\n\n";
  bool any = false;
  for (const KernelRow& r : krows)
    for (const auto& [name, n] : r.wrong_by_subject)
      if (n > 0) {
        md << "- " << to_string(r.kernel) << ", " << name << ": " << n << "\n";
        any = true;
      }
  if (!any) md << "- none: every kernel saw exactly the cells the exact kernel saw.\n";

  md << "\n## 2. The half-tone renderer\n\n"
     << "The default view of ";
  for (size_t i = 0; i < rsel.size(); ++i) md << (i ? ", " : "") << rsel[i].name;
  md << ", rendered on one thread with 1, 4 and 16 samples per pixel, flat (Bouknight) and smooth (Wylie) shading. "
        "The reference for each size and shading is 64 samples per pixel: 16 samples at twice the resolution, "
        "averaged 2 × 2 in linear light. Error: root mean square difference of the 8-bit sRGB samples, and the share "
        "of samples more than 2 levels off.\n\n"
     << "![renderer](" << (rel / "render.svg").string() << ")\n\n"
     << "| view | size | shading | samples | median ms | RMS error [levels] | samples > 2 levels off |\n"
     << "| --- | --- | --- | ---: | ---: | ---: | ---: |\n";
  for (const RenderRow& r : rrows)
    md << "| " << r.view << " | " << r.width << " × " << r.height << " | " << to_string(r.shading) << " | " << r.samples
       << " | " << format_number("%.2f", r.ms) << " | " << format_number("%.2f", r.rms) << " | " << format_number("%.2f", r.off_pct) << " % |\n";

  md << "\n## 3. Tessellation of curved walls\n\n"
     << "`plans/curved-walls.toml` (a rotunda, a curved wing and a garden wall) read with each `arc_tolerance`: "
        "the largest sagitta actually left between a straight piece and its circle (measured from three consecutive "
        "points of one arc), the pieces made, the decomposition's median time, the cells and portals it gives, and the "
        "median traversal of the plan's default view (1280 × 720, double kernel).\n\n"
     << "![tessellation](" << (rel / "tessellation.svg").string() << ")\n\n"
     << "| arc_tolerance [m] | largest sagitta [mm] | arc pieces | build ms | cells | portals | traversal µs |\n"
     << "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const TessRow& r : trows)
    md << "| " << format_number("%.4g", r.tolerance) << " | " << format_number("%.3g", r.sagitta * 1000) << " | " << r.pieces << " | "
       << format_number("%.1f", r.build_ms) << " | " << r.cells << " | " << r.portals << " | " << format_number("%.2f", r.traverse_us) << " |\n";
  md << "\nCurved objects (meshes) carry their own tessellation, made by whoever exported them; Avenues reads them as "
        "they are and has no tolerance of its own to vary, so they are not in this study.\n";
  md << "\n## 4. Half-tones of parallel views\n\n"
     << "A parallel view's half-tone (`avenues drawing` pictures, `avenues view --projection parallel` pictures) is rendered by the perspective pipeline from a distant eye: D behind the picture plane along the view, the window the same size at the picture plane, every polygon cut in 3D where the view's rays start (its cut plane, or the picture plane), so that lights, shadows, smooth shading and furniture are those of every other picture. A point z metres beyond the picture plane is then drawn D / (D + z) of its parallel size: with D = 256 × (samples across the picture) × (the far box's depth from the picture plane), a point of the far box is off its parallel place by at most 1/512 of a sample, and the exact parallel masks (the avenues' clip regions) by as much, inside the 1/64 of a sample by which deeper masks are grown. The test `ArchitecturalHalftone.EachSampleShowsTheFaceARayFromTheCutMeetsFirst` casts an independent parallel ray from the cut for every third sample of a plan, a section, an elevation and a cut axonometric of two plans, and finds the face each sample shows is the one the ray meets first (samples on an edge between two faces may take either). In doubles the distant eye costs nothing measurable: coordinates of 10^9 m carry errors of about 10^-7 m.\n";
  md << "\n## 5. Coarser furniture in walkthroughs and films\n\n"
     << "Walkthroughs and films (`avenues walk`, `avenues path`; `--detail SAMPLES`, default 0.5, 0: always in full) draw furniture far enough from the eye in a coarser version. Each distinct model of 500 triangles or more is made coarser once, by OpenMesh's decimater (edge collapses in the order of their quadric error; its Hausdorff module refuses any collapse that would leave an original vertex farther than the tolerance from the faces replacing it; no face may flip), at tolerances of 1/1000, 1/250 and 1/60 of the model's bounding box diagonal, all three in one pass so that each is bounded against the original, not against the level before (plans/mesh_detail.h; the walkthrough makes them on a thread of its own and draws in full until they are ready). A level is drawn only where its tolerance τ (times the object's largest scale factor) moves no point of the object by more than the stated fraction of a sample: a point at depth Z and picture position (x, y) moved by at most τ moves on the picture plane by at most τ·√2·(1 + max(|x|, |y|))/Z, Z taken at the nearest corner of the object's box and |x|, |y| at the raster's edge; an object reaching the near plane is drawn in full. So no edge of the picture moves by more than half a sample, which is within the renderer's own sampling error at 1 sample per pixel (§2). What changes besides are the shades of curved surfaces, a triangle's flat shade where its polygon's was. Measured by `MeshDetail.AFurnishedHomeDrawnWithCoarserFurnitureDiffersOnlyAlongEdges` on Sweet Home 3D's 1BedroomApartmentWithRoundWall (221,187 furniture triangles), 1280 × 720, one sample, four views: 21,514 polygons drawn instead of 36,105 in its stored view (17,781 for 30,481, 16,854 for 22,650 in two others; nothing changes in a view without furniture); 0.04–0.09 % of the samples more than 2 levels off, RMS difference 0.7–1.2 levels (the test allows 0.5 % and 2 levels). A model's levels take about 1.2 s for that home's 74 models (2 threads).\n";
  md << "\n## 6. The hull search's pictures\n\n"
     << "The hull search (`--search hull`, the walkthrough's and films' default for half-tones) joins every piece of "
        "view reaching a cell into their convex hull, so a cell is searched about once; its masks may hold rays that "
        "reach nothing of the cell, so its picture is resolved by depth (Bouknight's sort among every face's opaque "
        "pieces and object) where the merged search's masks decide which cell shows. The two pictures can differ only "
        "in samples centred within a rounding of an edge: a mask's edge (grown by 1/64 of a sample) against the "
        "nearest surface's own. Each plan's default view and " << hull_eyes << " random eyes (as in §1), "
     << (opt.quick ? "320 × 180" : "1280 × 720") << ", one sample, flat shading, one thread; time is the search and "
        "the half-tone together (median per view). The tests (`AvenuePruning.*`, `SoupBsp.*`) check on every oracle "
        "view of the bundled plans, three Sweet Home homes, MAP01 and the soups that every differing pixel lies beside "
        "an edge and that at most 0.5 % differ, or 2 % of the pixels on an edge where edges fill the picture (a stair "
        "seen through its balusters at 96 × 64: 41 % of its pixels on an edge). Both pictures draw an object in every "
        "cell it meets, cut in 3D to "
        "the cell where it reaches beyond it (render/scene_view.cpp): drawn only in the cell holding its centroid, an "
        "object reaching past a portal showed over what stands nearer beyond it in the merged search's picture (a box "
        "under a wall's top in 4BedroomHouse's attic: 2 % of a view) and lost its parts in other cells in both; "
        "`Scanline.ObjectsReachingBeyondTheirCellShowWhereARayMeetsThemFirst` casts a ray per sample against every "
        "face and object.\n\n"
        "Resolved by depth alone, the hull search's picture does not put on the raster what lies wholly behind "
        "polygons already drawn (render/occlusion_buffer.h: per pixel, the least 1/Z a polygon drawn there is known "
        "to reach at every sample centre, counted only where the centres lie strictly inside the polygon's rounded "
        "outline and its clip region). A polygon goes only where its largest 1/Z at any sample it could colour (at "
        "its corners, plus its plane's slope over the 1/128 of a sample its rounded outline may reach beyond them) "
        "is below that at every pixel it could colour, with a margin of 1e-6: the same picture, byte for byte "
        "(`Occlusion.*` against a brute force over every sample centre; `AvenuePruning.*` and `SoupDetail.*` compare "
        "the pictures with and without dropping). A run of about 16 of a mesh's triangles (a soup's detail, "
        "furniture) goes at once when its box lies behind what is drawn by 1e-3 of 1/Z: the box bounds every "
        "polygon inside but not the 1/128 of a sample by which rounding may carry a polygon's plane past its corners, "
        "which 1e-3 covers for every plane turned more than about a quarter of a degree from edge-on. A plane nearer "
        "edge-on than that, within 1e-3 of the depth of the surface in front of it, may lose a sample that rounding "
        "alone would have shown through that surface.\n\n"
     << "| plan | views | merged ms | hull ms | cells merged → hull | avenues merged → hull | samples differing | > 2 levels off | RMS [levels] |\n"
     << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n";
  for (const HullRow& r : hrows) {
    const double n = double(std::max(1L, r.samples));
    md << "| " << r.plan << " | " << r.views << " | " << format_number("%.2f", median(r.merged_ms)) << " | "
       << format_number("%.2f", median(r.hull_ms)) << " | " << r.merged_cells << " → " << r.hull_cells << " | "
       << r.merged_avenues << " → " << r.hull_avenues << " | " << format_number("%.3f", 100.0 * double(r.differ) / n)
       << " % | " << format_number("%.3f", 100.0 * double(r.off) / n) << " % | " << format_number("%.2f", std::sqrt(r.sq / n))
       << " |\n";
  }

  write_text(report, md.str());
  std::cout << "wrote " << report.string() << " and its plots in " << figs.string() << "/ in "
            << format_number("%.1f", ms_since(t_all) / 1000) << " s\n";
  return 0;
}

}  // namespace avenues::app
