// Avenues — the subcommands of the `avenues` executable, one file each.
//
// main.cpp declares the command line (CLI11) and calls one of these; each returns
// the process's exit status and may throw PlanError / std::runtime_error, which
// main() reports as "avenues: <message>" with exit status 2.
#pragma once

#include <iosfwd>
#include <optional>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "app/option_checks.h"
#include "app/plan_source.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues::app {

/// `avenues cells PLAN [--json] [--svg FILE] [--save FILE.cells]`
struct CellsOptions {
  std::string plan;
  ImportOptions import;  ///< how a plan from elsewhere is understood
  bool json = false;
  std::string svg;
  std::string save;
};
int run_cells(const CellsOptions& opt);

/// `avenues export PLAN -o FILE.obj`
struct ExportOptions {
  std::string plan;
  ImportOptions import;  ///< how a plan from elsewhere is understood
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
  ImportOptions import;  ///< how a plan from elsewhere is understood
  std::string eye, look;               ///< "X,Y,Z"; empty: the plan's default viewpoint
  std::optional<double> yaw, pitch;    ///< [deg] instead of --look
  double fov = -1;                     ///< [deg]; <= 0: the viewpoint's
  std::string size = "1920x1080";
  std::string kernel = "double";
  std::string search = "merged";       ///< merged, hull or jones (TraverseParams::merge_pieces, hull_pieces)
  std::string stats_json, overlay;
  std::vector<std::string> outputs;    ///< each -o: a drawing or a picture of the one view, by extension
  std::string stereo;                  ///< "", parallel, cross or pair
  double interocular = 0.065;          ///< [m]
  double converge = 2.0;               ///< [m]
  int frames = 0;                      ///< > 0: a straight walk to to_eye/to_look
  std::string to_eye, to_look;         ///< "X,Y,Z"
  int samples = 1;                     ///< half-tone: samples per pixel, 1, 4 or 16
  std::string shading = "flat";        ///< half-tone: flat or smooth
  std::string dither = "none";         ///< half-tone: none, bayer or fs
  std::string lights = "plan";         ///< plan (its point lights, with shadows) or eye (the light at the eye only)
  std::string object_shadows = "auto"; ///< objects' shadows from the plan's lights: auto, on or off
  double falloff = 5;                  ///< [m] smooth shading: the distance law from here; <= 0: off
  bool shadow_lines = false;           ///< drawings: outline the shadows of the plan's point lights
  bool explain = false;                ///< list which effects the view calls for, and why
  std::string projection = "perspective";  ///< perspective or parallel
  double view_width = 0;               ///< [m] > 0 with a parallel projection: the picture's width
};

/// `avenues drawing PLAN (--plan STOREY | --section X1,Y1,X2,Y2 | --elevation DIR | --axonometric AZ,ALT) -o FILE
/// [-o FILE ...]`: one drawing, in as many files and formats as asked.
struct DrawingOptions {
  std::string plan, stats_json;
  std::vector<std::string> outputs;    ///< each -o: the drawing (vector) or the half-tone with it (picture)
  ImportOptions import;                ///< how a plan from elsewhere is understood
  std::string storey;                  ///< --plan: a storey's name or index
  std::string section;                 ///< "X1,Y1,X2,Y2"
  std::string elevation;               ///< north, south, east, west or degrees
  std::string axonometric;             ///< "AZIMUTH,ALTITUDE" [deg]
  std::optional<double> cut_height;    ///< [m] above the storey's floor (plan: default 1.2)
  std::string scale = "1:50";          ///< paper scale 1:20 ... 1:500
  std::string kernel = "double";
  std::string search = "merged";       ///< merged, hull or jones (TraverseParams::merge_pieces, hull_pieces)
  int samples = 4;                     ///< pictures: the half-tone's samples per pixel, 1, 4 or 16
};
int run_drawing(const DrawingOptions& opt);

/// `avenues path PLAN --through ROOM,ROOM,... -o DIR`: a batch walkthrough through named rooms.
struct PathOptions {
  std::string plan;
  ImportOptions import;  ///< how a plan from elsewhere is understood
  std::string through;            ///< "ROOM,ROOM,..."; or
  std::string keys;               ///< a keyframe file: "EX EY EZ LX LY LZ" per line
  std::string out_dir = "avenues-path";
  std::string format = "png";     ///< png (half-tone) or svg (hidden-line)
  double step = 0.25;             ///< [m] between frames
  std::string size = "640x360";
  double fov = 70;                ///< [deg]
  std::string kernel = "double";
  std::string search = "hull";  ///< hull, merged or jones (TraverseParams): hull for half-tones at walking speed; lines take merged
  double detail = 0.5;            ///< [samples] furniture's coarser versions where they move the picture less (0: full)
  int samples = 4;                ///< half-tone: samples per pixel, 1, 4 or 16
  std::string shading = "flat";   ///< half-tone: flat, smooth or auto
  std::string lights = "plan";    ///< plan (its point lights, with shadows) or eye (the light at the eye only)
  std::string object_shadows = "auto";  ///< objects' shadows from the plan's lights: auto, on or off
  std::string stereo;             ///< "": mono; pictures: anaglyph, parallel, cross; drawings: parallel, cross
  double interocular = 0.065;     ///< [m]
  double converge = 2.0;          ///< [m]
  int threads = 0;                ///< a process's rendering threads; 0: all cores (under MPI: each rank its share)
  bool resume = false;            ///< keep the frames already in out_dir and render only the others
  int64_t max_frames = 1000000;   ///< refuse a longer walk
};
/// Under mpirun or srun, the frames are spread over the ranks (app/mpi_walk.h).
int run_path(const PathOptions& opt);

/// Keyframes from a text file: one per line, "EX EY EZ LX LY LZ" (eye, then the point it
/// looks at, in metres), '#' starts a comment (cmd_path.cpp). Throws PlanError naming the file and line.
std::vector<std::pair<Vec3, Vec3>> read_keys(const std::string& file);

/// `avenues walk [PLAN]`: the interactive walkthrough window.
struct WalkOptions {
  std::string plan;
  ImportOptions import;  ///< how a plan from elsewhere is understood
  std::string size = "1280x720";       ///< the window's first size; frames follow the window
  std::string eye, look;               ///< "X,Y,Z"; empty: the plan's default viewpoint
  double fov = -1;                     ///< [deg]; <= 0: the viewpoint's
  bool fly = false;                    ///< start in fly mode (else walk)
  bool lines = false;                  ///< start with the hidden-line drawing (else half-tone)
  std::string stereo = "mono";         ///< start in mono, side-by-side or anaglyph
  bool progressive = false;            ///< start with progressive display (cell by cell)
  int progressive_rate = 1;            ///< avenues added per swap in progressive display, >= 1
  bool hud = true;                     ///< the status line
  bool vsync = true;
  std::string script;                  ///< a key-event file to replay (app/script.h)
  std::optional<uint32_t> random_input;  ///< replay random input from this seed instead
  long frames = 0;                     ///< > 0: quit after this many frames
  double dt = 0;                       ///< [s] > 0: fixed time step; 0: 1/60 with a script or --frames, else real time
  std::string screenshot;              ///< write the last frame shown (PNG) at the end
  std::string stats_json;              ///< frame times, memory, the last pose, as JSON
  std::string out_dir = "avenues-out"; ///< where F2, F3 and F4 write
  std::string record;                  ///< keyframe file for K; default OUT_DIR/<plan>-keys.txt
  int samples = 1;                     ///< half-tone: 1, 4 or 16
  std::string shading = "flat";
  std::string lights = "plan";         ///< plan (its point lights, with shadows) or eye (the light at the eye only)
  std::string object_shadows = "auto"; ///< objects' shadows from the plan's lights: auto, on or off
  std::string kernel = "double";
  std::string search = "hull";       ///< hull, merged or jones (TraverseParams): hull for half-tones at walking speed; lines take merged
  double detail = 0.5;                 ///< [samples] furniture's coarser versions where they move the picture less (0: full)
  double interocular = 0.065;          ///< [m]
  double converge = 2.0;               ///< [m]
  double frame_budget_ms = 1000.0 / 60;  ///< [ms] >= 0: while moving, less detail to keep frames under it (app/frame_budget.h); 0: never
};
int run_walk(const WalkOptions& opt);
/// The walkthrough window on a loaded plan. Returns false, with the reason in `why`, when no
/// window could be opened (no display); otherwise the exit status in `status`.
bool run_walkthrough(const LoadedPlan& plan, const WalkOptions& opt, int& status, std::string& why);

/// `avenues bench papers [--threads N] [--repeats N]`: the papers' scenes beside their figures.
int run_bench_papers(int threads, int repeats);
/// `avenues bench walk [PLAN...] [--frames N] [--size WxH]`: frame times of the walkthrough window.
int run_bench_walk(const std::vector<std::string>& plans, long frames, const std::string& size, double frame_budget_ms,
                   const std::string& lights = "plan", const std::string& search = "hull", double detail = 0.5);
/// The camera and eye cell a view option set resolves to.
struct ViewSetup {
  Viewpoint viewpoint;
  Camera camera;
  Kernel kernel = Kernel::Double;
  TraverseParams search;  ///< the kernel and the kind of search (--search)
  CellId eye_cell = kNoCell;
};
/// Resolves options against the plan: default viewpoint, camera, and the eye's cell.
/// Throws PlanError when the eye is inside a solid or outside the far box.
ViewSetup set_up_view(const LoadedPlan& plan, const ViewOptions& opt);
nlohmann::json view_stats(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs);
int run_view(const ViewOptions& opt);
/// A one-shot view's picture (no stereo, no frames) is rendered into a buffer whose pages
/// were first touched on a thread of its own while the plan was read: a new 6 MB picture's
/// page faults cost a 1920 × 1080 frame about 2 ms, three times its scan. Starts that
/// (run_view calls it where a picture is among the outputs).
void warm_view_picture(const ViewOptions& opt);
/// Throws naming `path` when its extension is neither a drawing's nor a picture's, or when
/// `stereo` (--stereo; "" for none) is not a layout its kind takes.
void check_view_output(const std::string& path, const std::string& stereo);
/// Writes the view's picture to `path` by its extension (stereo, walk frames as asked by
/// `opt`); adds what it measured to `stats`.
void write_view_output(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs, const ViewOptions& opt,
                       const std::string& path, nlohmann::json& stats);
/// Writes the view to every file of opt.outputs, each as write_view_output() would alone;
/// returns each file's figures ({"file": path, ...}). One view (no stereo, no frames): its
/// picture rendered and its drawing drawn once, whatever the files, and the files written
/// all or none. Walk frames and stereo pairs: each frame or pair rendered once and drawn
/// once, and written to every file of its kind (frames as they are made, not all or none).
nlohmann::json write_view_outputs(const LoadedPlan& plan, const ViewSetup& v, const VisibleSet& vs,
                                  const ViewOptions& opt);
/// With --explain: each effect of the half-tone on or off and why (render/effects.h), one
/// per line, and for drawings among opt.outputs whether shadow outlines are drawn.
std::string explain_view_effects(const LoadedPlan& plan, const ViewOptions& opt);
/// "X,Y,Z" → Vec3; throws std::runtime_error naming the option otherwise.
Vec3 parse_vec3(const std::string& s, const char* option);

/// No subcommand: the main job on PLAN (default: the bundled plan).
struct MainJobOptions {
  std::string plan;
  ImportOptions import;  ///< how a plan from elsewhere is understood
  std::string out_dir = "avenues-out";
};
int run_main_job(const MainJobOptions& opt);

/// The text summary `avenues cells` and the main job print.
void print_summary(std::ostream& out, const LoadedPlan& plan);

}  // namespace avenues::app
