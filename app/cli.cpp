// Avenues — the command line of the `avenues` executable (app/main.cpp calls run_cli).
//
//   avenues [PLAN]                                  the main job
//   avenues cells PLAN [--json] [--svg F] [--save F.cells]
//   avenues export PLAN -o FILE.obj
//   avenues path [PLAN] --through ROOM,ROOM,... [-o DIR] [--format png|svg]   (also under mpirun / srun)
//   avenues view PLAN [--eye X,Y,Z --look X,Y,Z] [--kernel K] [--stats-json F] [--overlay F.svg]
//   avenues drawing PLAN --plan S | --section X1,Y1,X2,Y2 | --elevation D | --axonometric AZ,ALT -o FILE
//   avenues walk [PLAN] [--script FILE] [--frames N --screenshot F.png] ...
//   avenues bench papers | accuracy [--quick] | walk [PLAN...]
//   avenues generate office --rooms ROWSxCOLS -o FILE.toml
//
// Exit status: 0 on success, 2 for a bad command line or bad input (a plan mistake,
// a file that cannot be read or written), with "avenues: <message>" on stderr.
#include <exception>
#include <iostream>
#include <new>
#include <string>

#include <CLI/CLI.hpp>

#include "app/accuracy.h"
#include "app/cli.h"
#include "app/commands.h"
#include "app/option_checks.h"
#include "cells/gmp_memory.h"
#include "app/plan_source.h"
#include "plans/mesh.h"
#include "plans/plan.h"

namespace {
constexpr int kBadInput = 2;
}

namespace avenues::app {

namespace {
constexpr const char* kSearchHelp =
    "merged (avenues into a cell joined where their union is convex: the same view, fewer avenues), hull "
    "(joined into their convex hull: one avenue per cell, a conservative view the half-tone resolves by depth; line "
    "drawings take the merged search) or jones (Jones's tree, one avenue per chain of portals)";
constexpr const char* kDetailHelp =
    "[samples] furniture far enough away is drawn in a coarser version that moves no point of its picture by more "
    "than this; 0: always in full";

/// The options that say how a plan from elsewhere is understood (docs/PLAN_FORMAT.md,
/// "Plans from elsewhere"), on every subcommand that reads a PLAN.
/// (`drawing`, whose --scale is the paper's, takes floor-plan annotations at their default scale.)
void add_import_options(CLI::App* app, ImportOptions& o, bool with_scale = true) {
  if (with_scale)
    app->add_option("--scale", o.scale, "floor-plan annotations (.txt): metres per pixel (default 0.04)")
        ->check(CLI::PositiveNumber)->type_name("M_PER_PIXEL");
  app->add_option("--layers", o.layers, "DXF: which layers hold what, overriding the usual names")
      ->type_name("walls=NAME,...;doors=...;windows=...");
  // One --unit for every file that does not say its unit: a DXF drawing (overriding its
  // $INSUNITS) and a mesh scene in a format without one (OBJ, PLY, STL, OFF).
  app->add_option("--unit", o.unit, "the file's length unit where it does not say: DXF (overrides $INSUNITS), OBJ, PLY, STL, OFF, Irrlicht's .irr and .irrmesh, VRML97")
      ->check(CLI::IsMember({"m", "cm", "mm", "in", "ft"}));
  // How a mesh scene in a format that declares no axes (OBJ, PLY, STL, OFF) becomes z-up
  // metres; formats that declare theirs (glTF, COLLADA, FBX, 3DS, IFC) are read as they say.
  app->add_option("--up", o.up, "mesh scenes: the file's up axis where its format has none (OBJ, PLY, STL, OFF), or against VRML's y for a world that does not keep to it")
      ->check(CLI::IsMember({"x", "y", "z"}));
  app->add_option("--storey-height", o.storey_height, "[m] 2D drawings: floor to ceiling")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app->add_option("--save-plan", o.save_plan, "also write the plan as understood, in Avenues' TOML")
      ->type_name("FILE.toml");
}
}  // namespace

int run_cli(int argc, char** argv) {
  use_throwing_gmp_allocator();  // GMP's exhaustion as std::bad_alloc, not abort()
  CLI::App app{
      "Avenues: an architectural walkthrough tool. It decomposes a building plan's free\n"
      "space into convex cells joined by convex portals (Jones 1971).\n"
      "Without a subcommand it runs the main job on PLAN (default: the bundled\n"
      "plans/jones-house.toml): prints a summary and opens the walkthrough window when\n"
      "there is a display; without one it writes avenues-out/<plan>-plan.svg and the view.",
      "avenues"};
  app.set_version_flag("--version", "avenues 0.1");
  app.require_subcommand(0, 1);

  MainJobOptions main_opt;
  app.add_option("PLAN", main_opt.plan, "plan (.toml) or saved cells (.cells); default: the bundled plan");
  add_import_options(&app, main_opt.import);
  app.add_option("--out-dir", main_opt.out_dir, "where the main job writes its files")
      ->capture_default_str()->check(file_name());

  CellsOptions cells_opt;
  CLI::App* cells = app.add_subcommand("cells", "decompose PLAN into cells and print a summary");
  cells->add_option("PLAN", cells_opt.plan, "plan (.toml) or saved cells (.cells)")->required();
  add_import_options(cells, cells_opt.import);
  cells->add_flag("--json", cells_opt.json, "print the summary as one JSON object");
  cells->add_option("--svg", cells_opt.svg, "also write the plan drawing (SVG) to FILE")->type_name("FILE")->check(file_name());
  cells->add_option("--save", cells_opt.save, "also save the complex to FILE.cells (loads fast)")
      ->type_name("FILE.cells")->check(file_name());

  ExportOptions export_opt;
  CLI::App* exp = app.add_subcommand("export", "write the opaque surfaces as a Wavefront OBJ mesh");
  exp->add_option("PLAN", export_opt.plan, "plan (.toml) or saved cells (.cells)")->required();
  add_import_options(exp, export_opt.import);
  exp->add_option("-o,--output", export_opt.output, "the OBJ file to write")->required()->type_name("FILE.obj")->check(file_name());

  ViewOptions view_opt;
  CLI::App* view = app.add_subcommand("view", "find what the eye sees from one viewpoint (Jones's avenues of sight)");
  view->add_option("PLAN", view_opt.plan, "plan (.toml) or saved cells (.cells); default: the bundled plan");
  add_import_options(view, view_opt.import);
  view->add_option("--eye", view_opt.eye, "eye position; default: the plan's viewpoint")->type_name("X,Y,Z");
  view->add_option("--look", view_opt.look, "centre of interest")->type_name("X,Y,Z");
  view->add_option("--yaw", view_opt.yaw, "heading in degrees anticlockwise from +x (instead of --look)")
      ->check(finite_number());
  view->add_option("--pitch", view_opt.pitch, "degrees above the horizontal (with --yaw)")
      ->check(number_in(-89, 89));
  view->add_option("--fov", view_opt.fov, "horizontal field of view in degrees, (0, 179]")->check(number_in(0, 179, true));
  view->add_option("--size", view_opt.size, "picture size in pixels")->type_name("WxH")->capture_default_str()->check(size_wxh());
  view->add_option("--kernel", view_opt.kernel, "arithmetic: float, double, filtered or exact")->capture_default_str()->check(kernel_name());
  view->add_option("--search", view_opt.search, kSearchHelp)->capture_default_str()->check(search_name());
  view->add_option("--stats-json", view_opt.stats_json, "write the view's statistics as JSON")->type_name("FILE")->check(file_name());
  view->add_option("--overlay", view_opt.overlay, "draw masks, plan and avenue tree as SVG")->type_name("FILE.svg")->check(file_name());
  view->add_option("-o,--output", view_opt.outputs,
                   "the picture of the view, by extension: .svg .pdf .eps .dxf .hpgl .plt (hidden-line drawing) or "
                   ".png .pgm .ppm .pbm (half-tone picture); repeat for several files of the one view")
      ->allow_extra_args(false)
      ->type_name("FILE")
      ->check(file_name());
  view->add_option("--stereo", view_opt.stereo,
                   "a stereo pair: parallel or cross (side by side), pair (two drawings) or anaglyph (pictures)");
  view->add_option("--samples", view_opt.samples, "half-tone: samples per pixel, 1, 4 or 16")->capture_default_str()->check(samples_count());
  view->add_option("--shading", view_opt.shading, "half-tone: flat (Bouknight), smooth (Wylie) or auto (smooth on curved meshes only)")->capture_default_str();
  view->add_option("--dither", view_opt.dither, "half-tone: none, bayer or fs (1-bit for print)")->capture_default_str();
  view->add_option("--lights", view_opt.lights, "plan (its point lights, casting shadows) or eye (the light at the eye)")
      ->capture_default_str();
  view->add_option("--object-shadows", view_opt.object_shadows, "objects' shadows from the plan's point lights: auto (when object triangles x lights <= 20000), on or off")
      ->capture_default_str();
  view->add_option("--falloff", view_opt.falloff, "[m] smooth shading: things farther than this are dimmed; 0: off")
      ->capture_default_str()->check(number_in(0, 1e6));
  view->add_flag("--shadow-lines", view_opt.shadow_lines, "drawings: outline the shadows of the plan's point lights");
  view->add_flag("--explain", view_opt.explain, "list each effect (depth, implicit lines, shadows, ...) as on or off, and why");
  view->add_option("--interocular", view_opt.interocular, "[m] distance between the eyes")->capture_default_str()->check(number_in(0, 10));
  view->add_option("--converge", view_opt.converge, "[m] distance at which the two views coincide")
      ->capture_default_str()->check(positive_number());
  view->add_option("--frames", view_opt.frames, "write N frames of a straight walk to --to-eye/--to-look")
      ->check(whole_at_least(0));
  view->add_option("--to-eye", view_opt.to_eye, "where the walk ends")->type_name("X,Y,Z");
  view->add_option("--to-look", view_opt.to_look, "what the walk's last frame looks at")->type_name("X,Y,Z");

  view->add_option("--projection", view_opt.projection, "perspective or parallel (rays along the direction of view)")
      ->capture_default_str();
  view->add_option("--view-width", view_opt.view_width, "[m] with --projection parallel: the picture's width");

  DrawingOptions drawing_opt;
  CLI::App* drawing = app.add_subcommand("drawing", "an architect's drawing: plan, section, elevation or axonometric");
  drawing->add_option("PLAN", drawing_opt.plan, "the plan, in any format the other subcommands read")->required();
  add_import_options(drawing, drawing_opt.import, false);
  auto* kind_plan = drawing->add_option("--plan", drawing_opt.storey, "a plan of this storey (name or index; 0 for a mesh scene, which has none), cut at --cut-height")
                        ->type_name("STOREY");
  auto* kind_section = drawing->add_option("--section", drawing_opt.section, "a vertical cut along the line, looking to its left")
                           ->type_name("X1,Y1,X2,Y2");
  auto* kind_elevation = drawing->add_option("--elevation", drawing_opt.elevation,
                                             "from outside: north, south, east, west or DEG (where the viewer stands, "
                                             "anticlockwise from +x)");
  auto* kind_axo = drawing->add_option("--axonometric", drawing_opt.axonometric,
                                       "parallel from above: viewer's azimuth (anticlockwise from +x) and altitude [deg]")
                       ->type_name("AZ,ALT");
  kind_plan->excludes(kind_section, kind_elevation, kind_axo);
  kind_section->excludes(kind_elevation, kind_axo);
  kind_elevation->excludes(kind_axo);
  drawing->add_option("--cut-height", drawing_opt.cut_height,
                      "[m] plan: above the storey's floor (default 1.2); axonometric: a horizontal cut above the first "
                      "storey's floor");
  drawing->add_option("--scale", drawing_opt.scale, "paper scale, 1:20 to 1:500")->capture_default_str();
  drawing->add_option("--kernel", drawing_opt.kernel, "arithmetic: float, double, filtered or exact")->capture_default_str();
  drawing->add_option("--search", drawing_opt.search, kSearchHelp)->capture_default_str()->check(search_name());
  drawing->add_option("--samples", drawing_opt.samples, "pictures: the half-tone's samples per pixel, 1, 4 or 16")
      ->capture_default_str()
      ->check(samples_count());
  drawing->add_option("-o,--output", drawing_opt.outputs,
                      "by extension: .svg .pdf .eps .dxf .hpgl .plt (vector) or .png .pgm .ppm .pbm (the half-tone "
                      "with the drawing over it); repeat for several files of the one drawing")
      ->required()
      ->allow_extra_args(false)
      ->type_name("FILE");
  drawing->add_option("--stats-json", drawing_opt.stats_json, "write visible cells, timings and the picture's frame as JSON")
      ->type_name("FILE");

  PathOptions path_opt;
  CLI::App* path = app.add_subcommand("path", "write the frames of a walk through named rooms (a batch walkthrough)");
  path->add_option("PLAN", path_opt.plan, "plan (.toml) or saved cells (.cells); default: the bundled plan");
  add_import_options(path, path_opt.import);
  path->add_option("--through", path_opt.through, "rooms to walk through, in order")->type_name("ROOM,ROOM,...");
  path->add_option("--keys", path_opt.keys, "keyframes to follow: one 'EX EY EZ LX LY LZ' per line")->type_name("FILE")->check(file_name());
  path->add_option("-o,--output", path_opt.out_dir, "directory for the numbered frames")->capture_default_str()->check(file_name());
  path->add_option("--format", path_opt.format, "png (half-tone) or svg (hidden-line drawing)")->capture_default_str();
  path->add_option("--step", path_opt.step, "[m] between frames")->capture_default_str()->check(positive_number());
  path->add_option("--size", path_opt.size, "frame size in pixels")->type_name("WxH")->capture_default_str()->check(size_wxh());
  path->add_option("--fov", path_opt.fov, "horizontal field of view in degrees")->capture_default_str()->check(number_in(0, 179, true));
  path->add_option("--kernel", path_opt.kernel, "arithmetic of the traversal")->capture_default_str()->check(kernel_name());
  path->add_option("--search", path_opt.search, kSearchHelp)->capture_default_str()->check(search_name());
  path->add_option("--detail", path_opt.detail, kDetailHelp)->capture_default_str()->check(number_in(0, 16));
  path->add_option("--samples", path_opt.samples, "half-tone: samples per pixel, 1, 4 or 16")->capture_default_str()->check(samples_count());
  path->add_option("--shading", path_opt.shading, "half-tone: flat, smooth or auto")->capture_default_str();
  path->add_option("--lights", path_opt.lights, "plan (its point lights, casting shadows) or eye (the light at the eye; faster in a home full of lamps)")->capture_default_str();
  path->add_option("--object-shadows", path_opt.object_shadows, "objects' shadows from the plan's point lights: auto (when object triangles x lights <= 20000), on or off")
      ->capture_default_str();
  path->add_option("--stereo", path_opt.stereo, "stereo frames: anaglyph, parallel or cross (drawings: parallel or cross)");
  path->add_option("--interocular", path_opt.interocular, "[m] distance between the eyes")->capture_default_str()->check(number_in(0, 10));
  path->add_option("--converge", path_opt.converge, "[m] distance at which the two views coincide")->capture_default_str()->check(positive_number());
  path->add_option("--threads", path_opt.threads, "rendering threads of a process (0: all cores; under MPI each rank its share)")->check(whole_at_least(0));
  path->add_flag("--resume", path_opt.resume, "keep the frames already in the directory; render only the missing ones");
  path->add_option("--max-frames", path_opt.max_frames, "refuse a walk of more frames than this")->capture_default_str()->check(whole_at_least(1));

  WalkOptions walk_opt;
  CLI::App* walk = app.add_subcommand("walk", "walk through PLAN in a window (H in the window lists the controls)");
  walk->add_option("PLAN", walk_opt.plan, "plan (.toml, .cells, FILE.wad:MAP01, ...); default: the bundled plan");
  add_import_options(walk, walk_opt.import);
  walk->add_option("--size", walk_opt.size, "the window's size in pixels")->type_name("WxH")->capture_default_str()->check(size_wxh());
  walk->add_option("--eye", walk_opt.eye, "where to start; default: the plan's viewpoint")->type_name("X,Y,Z");
  walk->add_option("--look", walk_opt.look, "what to look at first")->type_name("X,Y,Z");
  walk->add_option("--fov", walk_opt.fov, "horizontal field of view in degrees")->check(number_in(0, 179, true));
  walk->add_flag("--fly", walk_opt.fly, "start in fly mode (anywhere in free space) instead of walk mode");
  walk->add_flag("--lines", walk_opt.lines, "start with the hidden-line drawing instead of the half-tone picture");
  walk->add_option("--stereo", walk_opt.stereo, "start in mono, side-by-side or anaglyph")->capture_default_str();
  walk->add_flag("--progressive", walk_opt.progressive, "progressive display: the view builds up cell by cell");
  walk->add_option("--progressive-rate", walk_opt.progressive_rate, "avenues added per frame in progressive display")
      ->capture_default_str()->check(whole_at_least(1));
  walk->add_flag_callback("--no-hud", [&] { walk_opt.hud = false; }, "start without the status line");
  walk->add_flag_callback("--no-vsync", [&] { walk_opt.vsync = false; }, "do not wait for the display's refresh");
  walk->add_option("--script", walk_opt.script, "replay a key-event file (one 'FRAME EVENT ARGS' per line)")
      ->type_name("FILE")->check(file_name());
  walk->add_option("--random-input", walk_opt.random_input, "replay random input from this seed (with --frames)")
      ->type_name("SEED");
  walk->add_option("--frames", walk_opt.frames, "quit after N frames")->check(whole_at_least(0));
  walk->add_option("--dt", walk_opt.dt, "[s] fixed time step (default 1/60 with --script or --frames, else real time)")
      ->check(number_in(0, 3600));
  walk->add_option("--screenshot", walk_opt.screenshot, "at the end, write the last frame shown as PNG")
      ->type_name("FILE.png")->check(file_name());
  walk->add_option("--stats-json", walk_opt.stats_json, "at the end, write frame times, memory and the pose as JSON")
      ->type_name("FILE")->check(file_name());
  walk->add_option("--out-dir", walk_opt.out_dir, "where F2, F3 and F4 write the view")->capture_default_str()->check(file_name());
  walk->add_option("--record", walk_opt.record, "keyframe file K appends to (default OUT_DIR/<plan>-keys.txt)")
      ->type_name("FILE")->check(file_name());
  walk->add_option("--samples", walk_opt.samples, "half-tone: samples per pixel, 1, 4 or 16")->capture_default_str()->check(samples_count());
  walk->add_option("--shading", walk_opt.shading, "half-tone: flat or smooth")->capture_default_str();
  walk->add_option("--lights", walk_opt.lights, "plan (its point lights, casting shadows) or eye (the light at the eye; faster in a home full of lamps)")->capture_default_str();
  walk->add_option("--object-shadows", walk_opt.object_shadows, "objects' shadows from the plan's point lights: auto (when object triangles x lights <= 20000), on or off")
      ->capture_default_str();
  walk->add_option("--kernel", walk_opt.kernel, "arithmetic of the traversal")->capture_default_str()->check(kernel_name());
  walk->add_option("--search", walk_opt.search, kSearchHelp)->capture_default_str()->check(search_name());
  walk->add_option("--detail", walk_opt.detail, kDetailHelp)->capture_default_str()->check(number_in(0, 16));
  walk->add_option("--interocular", walk_opt.interocular, "[m] distance between the eyes")->capture_default_str()->check(number_in(0, 10));
  walk->add_option("--frame-budget", walk_opt.frame_budget_ms,
                   "[ms] while the eye moves, drop samples, then resolution, then far objects, to keep frames under this; "
                   "full detail again when it stops (0: never)")
      ->capture_default_str()->check(number_in(0, 10000));
  walk->add_option("--converge", walk_opt.converge, "[m] distance at which the two views coincide")
      ->capture_default_str()->check(positive_number());

  int bench_threads = 0, bench_repeats = 5;
  CLI::App* bench = app.add_subcommand("bench", "measure Avenues against the source papers");
  bench->require_subcommand(1);
  CLI::App* papers = bench->add_subcommand("papers", "render Bouknight's and Wylie's scenes at 512x512 beside their figures");
  papers->add_option("--threads", bench_threads, "threads for the scanline bands (0: all)")->check(whole_at_least(0));
  papers->add_option("--repeats", bench_repeats, "renders per scene (the median is reported)")->capture_default_str()->check(whole_at_least(1));
  AccuracyOptions accuracy;
  CLI::App* bench_accuracy = bench->add_subcommand(
      "accuracy", "what accuracy costs in time: kernels, renderer quality, tessellation; writes docs/ACCURACY.md");
  bench_accuracy->add_flag("--quick", accuracy.quick, "a small version of each study (under a minute)");
  bench_accuracy->add_option("--report", accuracy.report, "the Markdown report; plots go beside it in accuracy/")
      ->capture_default_str()->check(file_name());
  bench_accuracy->add_option("--seed", accuracy.seed, "for the random eyes")->capture_default_str();
  std::vector<std::string> bench_walk_plans;
  long bench_walk_frames = 600;
  std::string bench_walk_size = "1280x720";
  CLI::App* bench_walk = bench->add_subcommand("walk", "frame times of the walkthrough window (needs a display, e.g. xvfb-run)");
  bench_walk->add_option("PLAN", bench_walk_plans, "plans to walk through; default: the bundled plans");
  bench_walk->add_option("--frames", bench_walk_frames, "frames per plan")->capture_default_str()->check(whole_at_least(1));
  bench_walk->add_option("--size", bench_walk_size, "the window's size")->type_name("WxH")->capture_default_str()->check(size_wxh());
  double bench_walk_budget = 1000.0 / 60;
  std::string bench_walk_lights = "plan";
  bench_walk->add_option("--lights", bench_walk_lights, "plan or eye, as for walk")->capture_default_str()->check(CLI::IsMember({"plan", "eye"}));
  bench_walk->add_option("--frame-budget", bench_walk_budget, "[ms] the walkthrough's frame budget; 0: none")
      ->capture_default_str()->check(number_in(0, 10000));
  std::string bench_walk_search = "hull";
  bench_walk->add_option("--search", bench_walk_search, "merged, hull or jones, as for walk")->capture_default_str()->check(search_name());
  double bench_walk_detail = 0.5;
  bench_walk->add_option("--detail", bench_walk_detail, "as for walk")->capture_default_str()->check(number_in(0, 16));

  GenerateOfficeOptions office_opt;
  CLI::App* generate = app.add_subcommand("generate", "write a generated plan");
  generate->require_subcommand(1);
  CLI::App* office = generate->add_subcommand("office", "an office floor: a grid of rooms off corridors");
  office->add_option("--rooms", office_opt.rooms, "grid size, e.g. 10x10")->required()->type_name("ROWSxCOLS");
  office->add_option("-o,--output", office_opt.output, "the plan file to write")->required()->type_name("FILE.toml")->check(file_name());

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);  // --help, --version
    std::cerr << "avenues: " << e.what() << "\nRun 'avenues --help' (or 'avenues SUBCOMMAND --help') for usage.\n";
    return kBadInput;
  }

  try {
    if (*cells) return run_cells(cells_opt);
    if (*exp) return run_export(export_opt);
    if (*view) return run_view(view_opt);
    if (*drawing) return run_drawing(drawing_opt);
    if (*papers) return run_bench_papers(bench_threads, bench_repeats);
    if (*bench_accuracy) return run_bench_accuracy(accuracy);
    if (*bench_walk)
      return run_bench_walk(bench_walk_plans, bench_walk_frames, bench_walk_size, bench_walk_budget, bench_walk_lights,
                            bench_walk_search, bench_walk_detail);
    if (*walk) return run_walk(walk_opt);
    if (*path) return run_path(path_opt);
    if (*office) return run_generate_office(office_opt);
    return run_main_job(main_opt);
  } catch (const avenues::PlanError& e) {
    std::cerr << "avenues: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::bad_alloc&) {
    std::cerr << "avenues: out of memory\n";
    return kBadInput;
  } catch (const std::exception& e) {
    std::cerr << "avenues: " << e.what() << "\n";
    return kBadInput;
  }
}
}  // namespace avenues::app
