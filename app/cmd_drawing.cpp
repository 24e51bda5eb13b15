// Avenues — `avenues drawing PLAN KIND -o FILE`: an architect's drawing, exactly, from the cells.
//
//   --plan STOREY            cut at --cut-height (default 1.2 m) above the storey's floor, looking down
//   --section X1,Y1,X2,Y2    a vertical cut along the line, looking to its left
//   --elevation DIR          north, south, east, west or DEG: from outside, looking at the building
//   --axonometric AZ,ALT     parallel from above; --cut-height removes what is above it
//
// Each is a parallel projection searched from a cut plane (render/architectural_drawing.h).
// A picture (.png .pgm .ppm .pbm) is the scanline half-tone of the same view with the
// drawing over it. The page follows --scale: 4 raster pixels to a paper millimetre, the picture fitted to the
// building (plan, elevation, axonometric) or to the section line, 1 m of margin around.
// --stats-json gives the visible cells, the cut cells, the timings and the picture's frame in
// world coordinates on the plane the rays start from (the cut plane): origin (lower-left),
// right and up (spanning the picture) and direction (unit, the way the drawing looks).
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/file_name.h"
#include "core/thread_arena.h"
#include "render/line_raster.h"
#include "core/atomic_file.h"
#include "render/architectural_drawing.h"
#include "render/halftone.h"
#include "render/raster.h"

namespace avenues::app {

namespace {

constexpr double kPixelsPerPaperMm = 4;
constexpr double kPageMarginMm = 10;

std::vector<double> parse_numbers(const std::string& s, size_t n, const char* option, const char* what) {
  std::vector<double> v;
  std::istringstream in(s);
  std::string part;
  while (std::getline(in, part, ',')) {
    size_t used = 0;
    double x = 0;
    try {
      x = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != part.size() || !std::isfinite(x)) v.clear(), v.resize(n + 1);
    v.push_back(x);
  }
  if (v.size() != n) throw std::runtime_error(std::string(option) + " wants " + what + ", not '" + s + "'");
  return v;
}

double parse_scale(const std::string& s) {
  size_t used = 0;
  double n = 0;
  if (s.rfind("1:", 0) == 0) {
    try {
      n = std::stod(s.substr(2), &used);
    } catch (const std::exception&) {
      used = 0;
    }
  }
  if (used == 0 || used != s.size() - 2 || !(n >= 20 && n <= 500))
    throw std::runtime_error("--scale wants 1:N with N from 20 to 500, not '" + s + "'");
  return n;
}

StoreyId find_storey(const CellComplex& c, const std::string& s) {
  // A scene of meshes has no storeys: its plan is the whole model's, cut above its lowest point.
  if (c.storeys.empty()) {
    if (s == "0") return -1;
    throw std::runtime_error("--plan: no storey '" + s + "': " + c.plan_name +
                             " has no storeys (a mesh scene); --plan 0 cuts the whole model --cut-height above its lowest point");
  }
  for (size_t i = 0; i < c.storeys.size(); ++i)
    if (c.storeys[i].name == s) return StoreyId(i);
  try {
    size_t used = 0;
    const long k = std::stol(s, &used);
    if (used == s.size() && k >= 0 && size_t(k) < c.storeys.size()) return StoreyId(k);
  } catch (const std::exception&) {
  }
  std::string names;
  for (const Storey& st : c.storeys) names += (names.empty() ? "" : ", ") + st.name;
  throw std::runtime_error("--plan: no storey '" + s + "' (the plan has " + (names.empty() ? "none" : names) +
                           "; or give its index)");
}

/// The view asked for, its picture fitted around what it shows at --scale.
ArchitecturalView fitted_drawing(const CellComplex& c, const DrawingOptions& opt) {
  const int kinds = !opt.storey.empty() + !opt.section.empty() + !opt.elevation.empty() + !opt.axonometric.empty();
  if (kinds != 1) throw std::runtime_error("give one of --plan, --section, --elevation or --axonometric");
  const double px_per_m = kPixelsPerPaperMm * 1000 / parse_scale(opt.scale);
  if (opt.cut_height && !std::isfinite(*opt.cut_height)) throw std::runtime_error("--cut-height wants a height in metres");
  if (!opt.storey.empty()) return plan_view(c, find_storey(c, opt.storey), opt.cut_height.value_or(1.2), px_per_m);
  if (opt.cut_height && opt.axonometric.empty())
    throw std::runtime_error("--cut-height goes with --plan or --axonometric");
  if (!opt.section.empty()) {
    const auto v = parse_numbers(opt.section, 4, "--section", "X1,Y1,X2,Y2 (the cut line)");
    if (!(length(Vec2{v[2] - v[0], v[3] - v[1]}) > 1e-6)) throw std::runtime_error("--section: the line's two ends must differ");
    return section_view(c, {v[0], v[1]}, {v[2], v[3]}, px_per_m);
  }
  if (!opt.elevation.empty()) {
    double deg = 0;
    if (opt.elevation == "east") deg = 0;
    else if (opt.elevation == "north") deg = 90;
    else if (opt.elevation == "west") deg = 180;
    else if (opt.elevation == "south") deg = 270;
    else deg = parse_numbers(opt.elevation, 1, "--elevation", "north, south, east, west or degrees")[0];
    return elevation_view(c, deg, px_per_m);
  }
  const auto v = parse_numbers(opt.axonometric, 2, "--axonometric", "AZIMUTH,ALTITUDE in degrees");
  if (!(v[1] > 0 && v[1] <= 90)) throw std::runtime_error("--axonometric: the altitude must lie in (0, 90] degrees");
  std::optional<double> cut_z;
  if (opt.cut_height) cut_z = (c.storeys.empty() ? 0 : c.storeys[0].elevation) + *opt.cut_height;
  return axonometric_view(c, v[0], v[1], cut_z, px_per_m);
}

/// The view asked for; too large for the page at its scale, an error that says which
/// scale would fit, or, where none would, how large the model is (a mesh in millimetres
/// read as metres, say).
ArchitecturalView set_up_drawing(const CellComplex& c, const DrawingOptions& opt) {
  try {
    return fitted_drawing(c, opt);
  } catch (const DrawingTooLarge& e) {
    const double fits = std::ceil(kPixelsPerPaperMm * 1000 * e.metres / kMaxDrawingPixels);  // the least N of 1:N
    std::ostringstream why;
    why << "--scale " << opt.scale << ": " << e.what() << " (" << std::fixed << std::setprecision(1) << e.metres
        << " m across); ";
    if (fits <= 500) {
      // The first of the usual architect's scales that fits.
      long usual = 500;
      for (long n : {20, 25, 50, 100, 200, 250, 500})
        if (double(n) >= fits) {
          usual = n;
          break;
        }
      why << "1:" << usual << " fits";
    } else {
      why << "not even 1:500 fits";
      if (c.storeys.empty()) why << "; if the model's unit is not the metre, give it with --unit (mm, cm, in, ft)";
    }
    throw std::runtime_error(why.str());
  }
}

/// The picture's frame on the cut plane: where the rays through its corners start.
nlohmann::json frame_json(const Camera& cam, const Plane& cut) {
  const double hw = cam.half_width(), hh = cam.half_height();
  const double nf = dot(cut.n, cam.forward);
  auto onto_cut = [&](Vec3 p) { return p + (-cut.eval(p) / nf) * cam.forward; };
  const Vec3 o = onto_cut(cam.eye + (cam.shift_x - hw) * cam.right + (cam.shift_y - hh) * cam.up);
  const Vec3 r = onto_cut(cam.eye + (cam.shift_x + hw) * cam.right + (cam.shift_y - hh) * cam.up) - o;
  const Vec3 u = onto_cut(cam.eye + (cam.shift_x - hw) * cam.right + (cam.shift_y + hh) * cam.up) - o;
  auto arr = [](Vec3 v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  return {{"origin", arr(o)}, {"right", arr(r)}, {"up", arr(u)}, {"direction", arr(cam.forward)}};
}

}  // namespace

int run_drawing(const DrawingOptions& opt) {
  Kernel kernel;
  if (!parse_kernel(opt.kernel, kernel))
    throw std::runtime_error("--kernel wants float, double, filtered or exact, not '" + opt.kernel + "'");
  const TraverseParams search = search_option(opt.search, kernel);
  if (search.hull_pieces)  // told before the plan is read
    throw std::runtime_error("--search hull is for walks and films; an architect's drawing takes merged or jones");
  // Every file's format, and that it can be written, known before the plan is read.
  bool any_picture = false;
  for (const std::string& out : opt.outputs) {
    if (!is_raster_path(out) && !is_drawing_path(out))
      throw std::runtime_error("cannot write '" + out + "': unknown format '" + lower_extension(out) +
                               "' (drawings: " + drawing_extensions() + "; pictures: " + raster_extensions() + ")");
    check_output_path(out);
    any_picture = any_picture || is_raster_path(out);
  }
  std::vector<std::string> named = opt.outputs;
  named.push_back(opt.stats_json);
  check_named_once(named);  // no file twice, nor the stats over a drawing
  start_threads(0);  // the drawing's (and half-tone's) threads start while the plan is read
  LoadedPlan plan = load_plan_source(opt.plan, opt.import);
  const CellComplex& c = plan.complex;
  ArchitecturalView s = set_up_drawing(c, opt);
  s.options.threads = 0;  // every core, as the half-tone
  const VisibleSet vs = find_visible_from_cut(c, s.camera, s.cut, search);
  const auto t0 = std::chrono::steady_clock::now();
  const LineScene scene = prepare_line_scene(c);
  Drawing d = draw_architectural(c, scene, s.camera, s.cut, vs, s.options);
  d.title = c.plan_name + " — " + s.kind;
  const size_t lines = d.strokes.size();
  const double scale = parse_scale(opt.scale);
  // The half-tone of the same parallel view (the scanline renderer, fed by the same
  // avenues), white where nothing is seen, and the drawing over it: the cut's poché and
  // outlines, the lines beyond, the room names. Made once for every picture asked for.
  Image img;
  if (any_picture) {
    HalftoneOptions ho;
    ho.samples = opt.samples;
    ho.background = {1, 1, 1};
    raster_of_drawing(d, render_view(c, s.camera, vs, ho), img);
  }
  PageOptions page;
  page.margin_mm = kPageMarginMm;
  page.width_mm = d.width / kPixelsPerPaperMm + 2 * kPageMarginMm;
  std::vector<std::pair<std::string, std::string>> files;
  for (const std::string& out : opt.outputs)
    files.emplace_back(out, is_raster_path(out) ? encode_image(img, out) : encode_drawing(d, out, page).bytes);
  write_files_atomically(files);  // all of them or none
  const double render_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  size_t cut_strokes = 0;
  for (const Stroke& st : d.strokes) cut_strokes += st.layer == Layer::Cut;
  if (!opt.stats_json.empty()) {
    nlohmann::json j;
    j["plan"] = plan.path;
    j["kind"] = s.kind;
    j["outputs"] = opt.outputs;
    j["scale"] = opt.scale;
    j["kernel"] = to_string(kernel);
    j["size"] = {s.camera.width, s.camera.height};
    j["page_mm"] = {d.width / kPixelsPerPaperMm + 2 * kPageMarginMm, d.height / kPixelsPerPaperMm + 2 * kPageMarginMm};
    j["visible"] = vs.cells;
    j["cells_cut"] = vs.cut_cells.size();
    j["cut_cells"] = vs.cut_cells;
    j["avenues"] = vs.avenues.size();
    j["portals_tested"] = vs.portals_tested;
    j["visibility_us"] = vs.micros;
    j["render_us"] = render_us;
    j["lines"] = lines;
    j["cut_lines"] = cut_strokes;
    j["frame"] = frame_json(s.camera, s.cut);
    j["cut"] = {s.cut.n.x, s.cut.n.y, s.cut.n.z, s.cut.d};
    write_file_atomically(opt.stats_json, j.dump(2) + "\n");
  }
  std::cout << s.kind << " of " << plan.path << " at 1:" << scale << ": " << vs.cut_cells.size() << " cells cut, "
            << vs.cells.size() << " visible through " << vs.avenues.size() << " avenues, " << vs.micros << " us ("
            << to_string(kernel) << "); " << lines << " lines\n";
  for (const std::string& out : opt.outputs) std::cout << "wrote " << out << "\n";
  if (!opt.stats_json.empty()) std::cout << "wrote " << opt.stats_json << "\n";
  return 0;
}

}  // namespace avenues::app
