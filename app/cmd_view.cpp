// Avenues — `avenues view PLAN`: what the eye sees from one viewpoint.
//
//   avenues view PLAN [--eye X,Y,Z] [--look X,Y,Z | --yaw DEG --pitch DEG] [--fov DEG]
//                     [--size WxH] [--kernel float|double|filtered|exact]
//                     [--stats-json FILE] [--overlay FILE.svg] [-o FILE] [--explain]
//
// Finds the eye's cell (an eye inside a wall or slab is an error naming the wall), runs
// Jones's traversal in the chosen kernel, and writes what was asked for: the statistics
// as one JSON object, and the overlay (masks, plan and avenue tree) as SVG. --explain lists
// the effects the scene calls for (render/effects.h) before anything is drawn.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/atomic_file.h"
#include "core/thread_arena.h"
#include "render/overlay_drawing.h"
#include "render/raster.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"

namespace avenues::app {

Vec3 parse_vec3(const std::string& s, const char* option) {
  std::istringstream in(s);
  Vec3 v;
  char c1 = 0, c2 = 0;
  if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || !(in >> std::ws).eof() ||
      !std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw std::runtime_error(std::string(option) + " wants three numbers X,Y,Z, not '" + s + "'");
  return v;
}

namespace {

std::string str(Vec3 v) {
  std::ostringstream o;
  o << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return o.str();
}

/// Every file asked for, known before the plan is read: no device or FIFO in its place,
/// and no file named twice (the stats and the overlay among them); each -o's format (and,
/// with --stereo, a layout that format takes) and its folder. So a run asked for several
/// files does not write some and then refuse the next, nor write one over another.
void check_view_outputs(const ViewOptions& opt) {
  for (const std::string& f : {opt.stats_json, opt.overlay})
    if (!f.empty()) check_output_path(f);
  std::vector<std::string> files{opt.overlay, opt.stats_json};
  files.insert(files.end(), opt.outputs.begin(), opt.outputs.end());
  check_named_once(files);
  for (const std::string& out : opt.outputs) {
    check_output_path(out);  // a device or FIFO there: told first, whatever its name
    check_view_output(out, opt.stereo);
    std::error_code ec;
    const std::filesystem::path folder = std::filesystem::path(out).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder, ec))
      throw std::runtime_error("cannot write '" + out + "': there is no folder " + folder.string());
  }
}

}  // namespace

ViewSetup set_up_view(const LoadedPlan& plan, const ViewOptions& opt) {
  const CellComplex& c = plan.complex;
  ViewSetup v;
  v.kernel = kernel_option(opt.kernel);
  v.search = search_option(opt.search, v.kernel);
  int w = 0, h = 0;
  size_option(opt.size, w, h);
  Viewpoint vp = default_viewpoint(c);
  if (!opt.eye.empty()) vp.eye = parse_vec3(opt.eye, "--eye");
  if (!opt.look.empty()) vp.look = parse_vec3(opt.look, "--look");
  if (opt.fov > 0) vp.fov_deg = opt.fov;
  if (!(vp.fov_deg > 0 && vp.fov_deg <= 179)) throw std::runtime_error("--fov must lie in (0, 179] degrees");
  if (opt.yaw || opt.pitch) {
    v.camera = Camera::yaw_pitch(vp.eye, opt.yaw.value_or(0), opt.pitch.value_or(0), vp.fov_deg, w, h);
    vp.look = vp.eye + v.camera.forward;
  } else {
    if (length(vp.look - vp.eye) == 0) throw std::runtime_error("--look must differ from the eye");
    v.camera = Camera::look_at(vp.eye, vp.look, vp.fov_deg, w, h);
  }
  if (opt.projection == "parallel") {
    if (!(opt.view_width > 0 && std::isfinite(opt.view_width)))
      throw std::runtime_error("--projection parallel needs --view-width M, the picture's width in metres (> 0)");
    v.camera = Camera::parallel(vp.eye, vp.eye + v.camera.forward, opt.view_width, w, h);
  } else if (opt.projection != "perspective") {
    throw std::runtime_error("--projection wants perspective or parallel, not '" + opt.projection + "'");
  } else if (opt.view_width != 0) {
    throw std::runtime_error("--view-width needs --projection parallel");
  }
  v.viewpoint = vp;
  const Location loc = c.locate(v.camera.eye, v.camera.forward);
  if (loc.what == Location::What::OutsideBox)
    throw PlanError({plan.path, 0, 0, ""}, "the eye " + str(vp.eye) + " is outside the far box");
  if (loc.what == Location::What::Solid)
    throw PlanError({plan.path, 0, 0, ""}, "the eye " + str(vp.eye) + " is inside " + loc.solid);
  v.eye_cell = loc.cell;
  return v;
}

nlohmann::json view_stats(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs) {
  const CellComplex& c = plan.complex;
  nlohmann::json j;
  j["plan"] = plan.path;
  j["eye"] = {v.viewpoint.eye.x, v.viewpoint.eye.y, v.viewpoint.eye.z};
  j["look"] = {v.viewpoint.look.x, v.viewpoint.look.y, v.viewpoint.look.z};
  j["projection"] = v.camera.is_parallel() ? "parallel" : "perspective";
  if (v.camera.is_parallel()) {
    j["view_width"] = v.camera.view_width;
    j["cells_cut"] = vs.cut_cells.size();
  } else {
    j["fov"] = v.viewpoint.fov_deg;
  }
  j["size"] = {v.camera.width, v.camera.height};
  j["kernel"] = to_string(v.kernel);
  j["search"] = search_label(v.search);
  j["eye_cell"] = vs.eye_cell;
  const Cell& ec = c.cells[size_t(vs.eye_cell)];
  j["eye_room"] = ec.room >= 0 ? c.rooms[size_t(ec.room)].name : std::string(to_string(ec.kind));
  j["visible_cells"] = vs.cells.size();
  j["visible"] = vs.cells;
  j["avenues"] = vs.avenues.size();
  if (v.search.merge_pieces) j["avenues_merged"] = vs.avenues_merged;
  j["portals_tested"] = vs.portals_tested;
  j["max_depth"] = vs.max_depth;
  j["visibility_us"] = vs.micros;
  return j;
}

int run_view(const ViewOptions& opt) {
  lights_option(opt.lights);  // refused before the work
  object_shadows_option(opt.object_shadows);
  if (!std::isfinite(opt.falloff)) throw std::runtime_error("--falloff wants a distance in metres");
  check_view_outputs(opt);  // a device or FIFO there, a file named twice: refused before the work
  if (std::any_of(opt.outputs.begin(), opt.outputs.end(), is_raster_path)) {
    start_threads(0);        // the picture's threads start while the plan is read,
    warm_view_picture(opt);  // and its pages are touched
  }
  LoadedPlan plan = load_plan_source(opt.plan, opt.import);
  ViewSetup v = set_up_view(plan, opt);
  if (v.camera.is_parallel()) {
    if (!opt.overlay.empty() || !opt.stereo.empty() || opt.frames > 0)
      throw std::runtime_error("--overlay, --stereo and --frames need --projection perspective");
  }
  VisibleSet vs = find_visible(plan.complex, v.camera, v.eye_cell, v.search);
  nlohmann::json stats = view_stats(plan, v, vs);
  if (!opt.overlay.empty()) write_overlay_svg(plan.complex, v.camera, vs, opt.overlay);
  if ((opt.frames > 0 || !opt.stereo.empty()) && opt.outputs.empty())
    throw std::runtime_error("--stereo and --frames need -o FILE");
  if (opt.frames > 0 && (opt.to_eye.empty() || opt.to_look.empty()))
    throw std::runtime_error("--frames needs --to-eye X,Y,Z and --to-look X,Y,Z");
  if (opt.explain) std::cout << "effects:\n" << explain_view_effects(plan, opt);
  // Each file as a run of its own would write it; with several, each one's figures under "outputs".
  std::vector<std::string> wrote;
  if (opt.outputs.size() == 1) write_view_output(plan, v, vs, opt, opt.outputs[0], stats);
  if (opt.outputs.size() > 1) stats["outputs"] = write_view_outputs(plan, v, vs, opt);
  for (size_t k = 0; k < opt.outputs.size(); ++k) {
    const nlohmann::json& one = opt.outputs.size() == 1 ? stats : stats["outputs"][k];
    const std::string& out = opt.outputs[k];
    if (opt.frames > 0) wrote.push_back(one["first_frame"].get<std::string>() + " and the next " + std::to_string(opt.frames - 1));
    else if (opt.stereo == "pair") wrote.push_back("the pair " + out + " (-left, -right)");
    else wrote.push_back(out);
  }
  if (!opt.stats_json.empty()) write_file_atomically(opt.stats_json, stats.dump(2) + "\n");
  std::cout << "eye in cell " << vs.eye_cell << " (" << stats["eye_room"].get<std::string>() << "): "
            << vs.cells.size() << " cells visible through " << vs.avenues.size() << " avenues, "
            << vs.portals_tested << " portals tested, depth " << vs.max_depth << ", " << vs.micros << " us ("
            << to_string(v.kernel) << ", " << search_label(v.search) << ")\n";
  if (!opt.overlay.empty()) std::cout << "wrote " << opt.overlay << "\n";
  for (const std::string& f : wrote) std::cout << "wrote " << f << "\n";
  if (!opt.stats_json.empty()) std::cout << "wrote " << opt.stats_json << "\n";
  return 0;
}

}  // namespace avenues::app
