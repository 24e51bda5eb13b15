// Avenues — the main job: what `avenues [PLAN]` does with no subcommand.
//
// With a display ($DISPLAY set and a window opens) it prints the summary and opens the
// walkthrough window (run_walkthrough, app/cmd_walk.cpp) at the plan's default viewpoint.
// Without one (CI, ssh) it is the offline job: decompose the plan, print the summary, draw
// the plan, and show the avenues of sight from the plan's default viewpoint as drawings
// and a picture in the output directory. run_main_job() stays a small dispatcher.
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "app/commands.h"
#include "render/halftone.h"
#include "render/overlay_drawing.h"
#include "render/raster.h"
#include "render/plan_drawing.h"
#include "render/view_lines.h"

namespace avenues::app {
namespace fs = std::filesystem;

namespace {

/// The job without a window: summary on stdout, drawings in the output directory.
int run_offline(const LoadedPlan& plan, const MainJobOptions& opt, bool summary_printed) {
  std::error_code ec;
  fs::create_directories(opt.out_dir, ec);
  if (ec) throw std::runtime_error("cannot create the output directory " + opt.out_dir + ": " + ec.message());
  const std::string svg = (fs::path(opt.out_dir) / (plan.stem + "-plan.svg")).string();
  write_plan_svg(plan.complex, svg);

  // The plan's default view: what the eye sees, and why (the avenues of sight).
  ViewOptions view_opt;
  view_opt.size = "1280x720";
  ViewSetup view = set_up_view(plan, view_opt);
  VisibleSet visible = find_visible(plan.complex, view.camera, view.eye_cell, view.search);
  const std::string overlay = (fs::path(opt.out_dir) / (plan.stem + "-avenues.svg")).string();
  write_overlay_svg(plan.complex, view.camera, visible, overlay);
  // The furniture, read and placed once for both pictures.
  std::vector<std::string> said;  // what reading the objects' meshes let pass
  const std::vector<PlacedObject> objects = place_objects(plan.complex, &said);
  print_warnings(plan.path, said);
  // What the eye sees, as a hidden-line drawing (Jones's perspective line drawing).
  const std::string drawing = (fs::path(opt.out_dir) / (plan.stem + "-view.svg")).string();
  const DrawingStats lines =
      write_drawing(draw_view(plan.complex, prepare_line_scene(plan.complex, objects), view.camera, visible), drawing);
  // And as a half-tone picture (Wylie, Bouknight), four samples per pixel.
  const std::string picture = (fs::path(opt.out_dir) / (plan.stem + "-view.png")).string();
  HalftoneOptions halftone;
  halftone.samples = 4;
  Image image;
  render_view(plan.complex, objects, view.camera, visible, halftone, image);
  write_image(image, picture);

  if (!summary_printed) print_summary(std::cout, plan);
  const Cell& eye_cell = plan.complex.cells[size_t(view.eye_cell)];
  std::cout << "\ndefault view: eye (" << view.viewpoint.eye.x << ", " << view.viewpoint.eye.y << ", "
            << view.viewpoint.eye.z << ") in "
            << (eye_cell.room >= 0 ? plan.complex.rooms[size_t(eye_cell.room)].name : to_string(eye_cell.kind))
            << ": " << visible.cells.size() << " cells seen through " << visible.avenues.size() << " avenues in "
            << visible.micros << " us\n";
  std::cout << "\nplan drawing: " << svg << "\n";
  std::cout << "avenues of sight (masks, plan, avenue tree): " << overlay << "\n";
  std::cout << "hidden-line drawing of the view (" << lines.lines << " strokes): " << drawing << "\n";
  std::cout << "half-tone picture of the view: " << picture << "\n";
  std::cout << "(open them in a web browser or an image viewer; `avenues --help` lists what else avenues can do)\n";
  return 0;
}

}  // namespace

int run_main_job(const MainJobOptions& opt) {
  LoadedPlan plan = load_plan_source(opt.plan, opt.import);
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display && *display) || (wayland && *wayland)) {
    print_summary(std::cout, plan);
    std::cout << "\nopening the walkthrough window (H shows the controls; F2, F3 and F4 write the view to "
              << opt.out_dir << ")\n"
              << std::flush;
    WalkOptions walk;
    walk.plan = opt.plan;
    walk.out_dir = opt.out_dir;
    int status = 0;
    std::string why;
    if (run_walkthrough(plan, walk, status, why)) return status;
    std::cout << "no walkthrough window (" << why << "); writing the views instead\n";
    return run_offline(plan, opt, true);
  }
  return run_offline(plan, opt, false);
}

}  // namespace avenues::app
