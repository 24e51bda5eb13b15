// Avenues — the subcommands of the `avenues` executable, one file each.
//
// main.cpp declares the command line (CLI11) and calls one of these; each returns
// the process's exit status and may throw PlanError / std::runtime_error, which
// main() reports as "avenues: <message>" with exit status 2.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "app/plan_source.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues::app {

/// `avenues cells PLAN [--json] [--svg FILE] [--save FILE.cells]`
struct CellsOptions {
  std::string plan;
  bool json = false;
  std::string svg;
  std::string save;
};
int run_cells(const CellsOptions& opt);

/// `avenues export PLAN -o FILE.obj`
struct ExportOptions {
  std::string plan;
  std::string output;
};
int run_export(const ExportOptions& opt);

/// `avenues generate office --rooms ROWSxCOLS -o FILE.toml`
struct GenerateOfficeOptions {
  std::string rooms;  ///< "ROWSxCOLS", validated by run_generate_office
  std::string output;
};
int run_generate_office(const GenerateOfficeOptions& opt);

/// `avenues view PLAN [--eye X,Y,Z] [--look X,Y,Z] ... [--stats-json FILE] [--overlay FILE.svg] [-o FILE]`
struct ViewOptions {
  std::string plan;
  std::string eye, look;               ///< "X,Y,Z"; empty: the plan's default viewpoint
  std::optional<double> yaw, pitch;    ///< [deg] instead of --look
  double fov = -1;                     ///< [deg]; <= 0: the viewpoint's
  std::string size = "1920x1080";
  std::string kernel = "double";
  std::string stats_json, overlay, output;
  std::string stereo;                  ///< "", parallel, cross or pair
  double interocular = 0.065;          ///< [m]
  double converge = 2.0;               ///< [m]
  int frames = 0;                      ///< > 0: a straight walk to to_eye/to_look
  std::string to_eye, to_look;         ///< "X,Y,Z"
  int samples = 1;                     ///< half-tone: samples per pixel, 1, 4 or 16
  std::string shading = "flat";        ///< half-tone: flat or smooth
  std::string dither = "none";         ///< half-tone: none, bayer or fs
};

/// `avenues path PLAN --through ROOM,ROOM,... -o DIR`: a batch walkthrough through named rooms.
struct PathOptions {
  std::string plan;
  std::string through;            ///< "ROOM,ROOM,..."; or
  std::string keys;               ///< a keyframe file: "EX EY EZ LX LY LZ" per line
  std::string out_dir = "avenues-path";
  std::string format = "png";     ///< png (half-tone) or svg (hidden-line)
  double step = 0.25;             ///< [m] between frames
  std::string size = "640x360";
  double fov = 70;                ///< [deg]
  std::string kernel = "double";
};
int run_path(const PathOptions& opt);

/// `avenues bench papers [--threads N] [--repeats N]`: the papers' scenes beside their figures.
int run_bench_papers(int threads, int repeats);
/// The camera and eye cell a view option set resolves to.
struct ViewSetup {
  Viewpoint viewpoint;
  Camera camera;
  Kernel kernel = Kernel::Double;
  CellId eye_cell = kNoCell;
};
/// Resolves options against the plan: default viewpoint, camera, and the eye's cell.
/// Throws PlanError when the eye is inside a solid or outside the far box.
ViewSetup set_up_view(const LoadedPlan& plan, const ViewOptions& opt);
bool parse_size(const std::string& s, int& w, int& h);
nlohmann::json view_stats(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs);
int run_view(const ViewOptions& opt);
/// Writes the view's picture to opt.output by its extension (stereo, walk frames as asked);
/// adds what it measured to `stats`.
void write_view_output(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs, const ViewOptions& opt,
                       nlohmann::json& stats);
/// "X,Y,Z" → Vec3; throws std::runtime_error naming the option otherwise.
Vec3 parse_vec3(const std::string& s, const char* option);

/// No subcommand: the main job on PLAN (default: the bundled plan).
struct MainJobOptions {
  std::string plan;
  std::string out_dir = "avenues-out";
};
int run_main_job(const MainJobOptions& opt);

/// The text summary `avenues cells` and the main job print.
void print_summary(std::ostream& out, const LoadedPlan& plan);

}  // namespace avenues::app
