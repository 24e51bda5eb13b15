// Avenues — `avenues walk [PLAN]`: the interactive walkthrough window.
//
// Jones 1971 hoped for "the illusion of continuous motion" from a new view drawn for every
// move of the sense switches. Every frame here: the window's events (or a replayed script)
// go to the controls (app/controls.h); their motion moves the eye through the walker
// (visibility/walker.h: walk mode keeps to the floors and through doors, fly mode anywhere
// in free space); the eye's avenues of sight are found afresh from its cell; Avenues renders
// the view itself — the scanline half-tone picture, or the hidden-line drawing rasterised
// by Cairo — mono, side by side or as an anaglyph; and the window shows that picture pixel
// for pixel (app/viewer.h), with the status line and the help over it (app/hud.h). A frame
// is rendered again only when the view changed, and while the eye moves at the detail the
// frame budget allows (app/frame_budget.h), at full detail once it stops. Progressive display (Jones tried it: the
// picture builds up as the lines are computed) shows the avenues' cells one swap at a time.
//
// From the window: F2 writes the picture as shown (PNG), F3 the hidden-line drawing (SVG),
// F4 a stereo pair, through the same code as `avenues view -o`; K appends a keyframe that
// `avenues path --keys` follows.
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>

#include <GLFW/glfw3.h>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/angles.h"
#include "app/controls.h"
#include "app/frame_budget.h"
#include "app/hud.h"
#include "render/line_raster.h"
#include "app/script.h"
#include "app/viewer.h"
#include "app/walk_exports.h"
#include "app/walk_state.h"
#include "app/walk_stats.h"
#include "core/atomic_file.h"
#include "plans/formats/doom_map.h"
#include "render/halftone.h"
#include "render/raster.h"
#include "render/effects.h"
#include "render/scene_objects.h"
#include "render/view_lines.h"
#include "visibility/stereo.h"
#include "visibility/strips.h"
#include "visibility/walker.h"

namespace avenues::app {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {

enum class StereoMode : uint8_t { Mono, SideBySide, Anaglyph };
const char* to_string(StereoMode m) {
  return m == StereoMode::Mono ? "mono" : m == StereoMode::SideBySide ? "side-by-side" : "anaglyph";
}

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

/// One window session: the walking state (app/walk_state.h), the exports and keyframes
/// (app/walk_exports.h) and the frame statistics (app/walk_stats.h) are parts of their own;
/// the session holds the view on screen, its controls, budget and panels, and runs the loop.
class Session {
 public:
  Session(const LoadedPlan& plan, const WalkOptions& opt, Viewer& viewer)
      : plan_(plan), c_(plan.complex), opt_(opt), viewer_(viewer), budget_(opt.frame_budget_ms, opt.samples, lit_by_lamps(plan.complex, opt.lights)),
        state_(plan, opt), exports_(plan, opt) {
    kernel_ = kernel_option(opt.kernel);
    search_ = search_option(opt.search, kernel_);
    halftone_.samples = samples_option(opt.samples);
    if (!parse_shading(opt.shading, halftone_.shading.model))
      throw std::runtime_error("--shading wants flat or smooth, not '" + opt.shading + "'");
    halftone_.lights = lights_option(opt.lights);
    halftone_.object_shadows = object_shadows_option(opt.object_shadows);
    halftone_.detail_samples = opt.detail;
    searches_ = FrameSearches(halftone_.threads);
    if (opt.stereo == "mono") stereo_ = StereoMode::Mono;
    else if (opt.stereo == "side-by-side" || opt.stereo == "parallel") stereo_ = StereoMode::SideBySide;
    else if (opt.stereo == "anaglyph") stereo_ = StereoMode::Anaglyph;
    else throw std::runtime_error("--stereo wants mono, side-by-side or anaglyph, not '" + opt.stereo + "'");
    if (opt.progressive_rate < 1) throw std::runtime_error("--progressive-rate must be at least 1");
    if (!(opt.frame_budget_ms >= 0 && opt.frame_budget_ms < 1e6))
      throw std::runtime_error("--frame-budget wants a time in milliseconds, 0 or more (0: no budget)");
    stereo_opt_ = {opt.interocular, opt.converge};
    if (!(opt.interocular > 0 && opt.converge > 0))
      throw std::runtime_error("--interocular and --converge must be positive lengths");
    lines_ = opt.lines;
    progressive_ = opt.progressive;
    hud_on_ = opt.hud;
    std::vector<std::string> said;  // what reading the objects' meshes let pass
    ObjectModels models;  // as read, for their coarser versions
    objects_ = place_objects(c_, &said, false, &models);
    print_warnings(plan.path, said);
    // The furniture's coarser versions take a second or two in a furnished home: made on a
    // thread of their own while the first frames are drawn in full, handed over when ready
    // (at once, before the first frame, when a script or --frames drives the walk, so that
    // its frames do not depend on how fast this machine is).
    if (opt.detail > 0 && !objects_.empty())
      coarser_ = std::async(std::launch::async,
                            [this, models = std::move(models)] { return coarser_versions(c_, models); });
    // Which effects the scene calls for, decided once (and its shadows cast once): deciding
    // means testing the furniture's triangles for crossings, far too dear for every frame.
    effects_ = prepare_effects(c_, objects_, halftone_, kernel_);
    // The same scene lit from the eye, for frames the budget makes cheaper (no shadows to cast).
    if (lit_by_lamps(c_, opt.lights)) effects_at_eye_ = prepare_effects(c_, objects_, lit_at_eye(halftone_), kernel_);
  }

  /// The same options with the light at the eye instead of the plan's.
  static HalftoneOptions lit_at_eye(HalftoneOptions o) {
    o.lights = Lights::Eye;
    return o;
  }

  /// Whether the walk's full detail is lit by the plan's own point lights.
  static bool lit_by_lamps(const CellComplex& c, const std::string& lights) {
    if (lights != "plan") return false;
    for (const Light& l : c.lights)
      if (l.kind == LightKind::Point) return true;
    return false;
  }

  /// Runs until the window closes, the script quits or the frame limit is reached.
  void run(const std::vector<ScriptEvent>& events, WalkReport& report) {
    const bool scripted = !events.empty() || opt_.frames > 0;
    const double fixed_dt = opt_.dt > 0 ? opt_.dt : scripted ? 1.0 / 60 : 0;
    ScriptPlayer script(events);
    bool quit = false, final_shot = false;
    Clock::time_point last_start = Clock::now();
    double smoothed_work = 0, smoothed_render = 0;
    Clock::time_point hud_refreshed = Clock::now() - std::chrono::seconds(1);
    for (long frame = 0; !quit && !viewer_.should_close(); ++frame) {
      if (opt_.frames > 0 && frame >= opt_.frames) break;
      adopt_coarser(scripted);
      // Wait for input only when nothing would change without it.
      const bool busy = scripted || controls_.active() || moving_ || progressive_pending() || !message_.empty();
      const Clock::time_point start = Clock::now();
      WindowInput in = viewer_.poll(busy ? 0 : 0.25);
      const Clock::time_point polled = Clock::now();
      if (frame > 0) report.frame_ms.push_back(std::chrono::duration<double, std::milli>(start - last_start).count());
      const double dt = fixed_dt > 0 ? fixed_dt : std::min(0.1, std::chrono::duration<double>(polled - last_start).count());
      last_start = start;
      if (in.focus_lost) controls_.release_all();
      for (const auto& [key, down] : in.keys) controls_.key(key, down);
      controls_.look(in.look_dx, in.look_dy);
      // The script's events for this frame.
      const ScriptPlayer::Requests asked = script.play(frame, controls_);
      for (const auto& [rw, rh] : asked.resizes) resize_window(rw, rh);
      for (int k = 0; k < asked.poses; ++k) std::cout << "pose: " << view_options() << "\n";
      quit |= asked.quit;
      const std::vector<std::string>& shots = asked.screenshots;
      // A scripted pad stands in for a real one, as GLFW would report it.
      controls_.gamepad(script.pad().present && !in.gamepad.present ? script.pad() : in.gamepad);
      for (Action a : controls_.take_commands()) command(a, quit);
      moving_ = state_.step(controls_.motion(dt), dt);

      int w = 0, h = 0;
      viewer_.framebuffer_size(w, h);
      if (w <= 0 || h <= 0) continue;  // minimised: nothing to draw
      const Clock::time_point r0 = Clock::now();
      const bool rendered = render(w, h);
      if (rendered) {
        if (shown_detail_ != budget_.full()) ++report.reduced_frames;
        else if (refining_) ++report.refined_frames;
        report.render_ms.push_back(ms_since(r0));
        smoothed_render = smoothed_render == 0 ? report.render_ms.back() : 0.9 * smoothed_render + 0.1 * report.render_ms.back();
      }
      // The status line: a few times a second, or every frame of a script (its screenshots
      // show the frame's own figures).
      if (scripted || Clock::now() - hud_refreshed > std::chrono::milliseconds(250) || state_changed_) {
        refresh_panels(w, h, smoothed_work, smoothed_render);
        hud_refreshed = Clock::now();
        state_changed_ = false;
      }
      const Clock::time_point d0 = Clock::now();
      draw(rendered);
      report.show_ms.push_back(ms_since(d0));
      for (const std::string& path : shots) screenshot(path, report);
      if (!opt_.screenshot.empty() && (quit || (opt_.frames > 0 && frame + 1 == opt_.frames))) {
        screenshot(opt_.screenshot, report);
        final_shot = true;
      }
      const Clock::time_point s0 = Clock::now();
      viewer_.swap();
      report.swap_ms.push_back(ms_since(s0));
      const double work = ms_since(polled);
      report.work_ms.push_back(work);
      if (rendered) budget_.measured(work, moving_, frame_.width, frame_.height);
      smoothed_work = smoothed_work == 0 ? work : 0.9 * smoothed_work + 0.1 * work;
      report.sample_process(frame);
      if (!message_.empty() && Clock::now() > message_until_) message_.clear(), state_changed_ = true;
    }
    if (!opt_.screenshot.empty() && !final_shot && frame_w_ > 0) {  // the window was closed: draw the last frame again
      draw(false);
      screenshot(opt_.screenshot, report);
    }
    report.finish();
    report.last = pose_json();
  }

 private:
  void draw(bool rendered) {
    std::vector<const OverlayPanel*> panels;
    // The help, while shown, stands in for the status line (it would cover it).
    if (hud_on_ && !help_on_) panels.push_back(&hud_panel_);
    if (help_on_) panels.push_back(&help_panel_);
    viewer_.draw(frame_, rendered, panels, shown_detail_.scale);
  }

  bool progressive_pending() const { return progressive_ && shown_ < full_.avenues.size(); }

  void say(const std::string& m) {
    std::cout << m << "\n" << std::flush;
    message_ = m;
    message_until_ = Clock::now() + std::chrono::seconds(4);
    state_changed_ = true;
  }

  void resize_window(int w, int h) {
    viewer_.resize(w, h);
    // Let the framebuffer follow before this frame is drawn (a script's next screenshot
    // should show the new size).
    for (int i = 0; i < 100; ++i) {
      int fw = 0, fh = 0;
      viewer_.framebuffer_size(fw, fh);
      if (fw == w && fh == h) break;
      WindowInput in = viewer_.poll(0.01);
      for (const auto& [key, down] : in.keys) controls_.key(key, down);
    }
  }

  void command(Action a, bool& quit) {
    state_changed_ = true;
    switch (a) {
      case Action::Switch1: case Action::Switch2: case Action::Switch3: case Action::Switch4:
      case Action::Switch5: case Action::Switch6: case Action::Switch7: case Action::Switch8: {
        const int i = int(a) - int(Action::Switch1);
        controls_.flip_switch(i);
        break;
      }
      case Action::SwitchesOff: controls_.switches_off(); break;
      case Action::ToggleFly: state_.toggle_mode(); break;
      case Action::ToggleLines: lines_ = !lines_; break;
      case Action::CycleStereo:
        stereo_ = stereo_ == StereoMode::Mono ? StereoMode::SideBySide
                  : stereo_ == StereoMode::SideBySide ? StereoMode::Anaglyph : StereoMode::Mono;
        break;
      case Action::ToggleProgressive: progressive_ = !progressive_; break;
      case Action::ToggleHelp: help_on_ = !help_on_; break;
      case Action::ToggleHud: hud_on_ = !hud_on_; break;
      case Action::CaptureMouse: viewer_.capture_mouse(!viewer_.mouse_captured()); break;
      case Action::LevelView: state_.level(); break;
      case Action::ExportPicture: export_picture(); break;
      case Action::ExportDrawing: export_view(".svg", ""); break;
      case Action::ExportStereo: export_stereo(); break;
      case Action::RecordKeyframe: record_keyframe(); break;
      case Action::Quit:
        if (viewer_.mouse_captured()) viewer_.capture_mouse(false);
        else quit = true;
        break;
      default: break;
    }
    force_render_ = true;
  }

  /// The first k avenues of a visible set (depth-first order: every parent comes first).
  static VisibleSet prefix(const VisibleSet& vs, size_t k) {
    VisibleSet out;
    out.eye_cell = vs.eye_cell;
    out.portals_tested = vs.portals_tested;
    out.micros = vs.micros;
    out.conservative = vs.conservative;
    out.avenues.assign(vs.avenues.begin(), vs.avenues.begin() + long(std::min(k, vs.avenues.size())));
    out.collect_cells();
    return out;
  }

  const LineScene& line_scene() {
    if (!scene_) scene_ = prepare_line_scene(c_, objects_);
    return *scene_;
  }

  /// One eye's picture of `vs` into `out`: its first `shown` avenues in progressive display.
  void picture(const Camera& cam, const VisibleSet& vs, size_t shown, Image& out) {
    const bool partial = progressive_ && shown < vs.avenues.size();
    const VisibleSet part = partial ? prefix(vs, shown) : VisibleSet{};
    const VisibleSet& use = partial ? part : vs;
    if (lines_) raster_of_drawing(draw_view(c_, line_scene(), cam, use), out);
    else if (!shown_detail_.lamps && effects_at_eye_)
      render_view(c_, objects_, *effects_at_eye_, cam, use, lit_at_eye(halftone_), out, storage_);
    else render_view(c_, objects_, effects_, cam, use, halftone_, out, storage_);
  }

  /// Renders the view when it changed (or its detail did); false when the last frame still stands.
  bool render(int window_w, int window_h) {
    const Detail detail = budget_.next(moving_);
    refining_ = !moving_ && shown_detail_ != detail;
    const bool view_changed = moving_ || force_render_ || window_w != frame_w_ || window_h != frame_h_ || first_ ||
                              detail != shown_detail_;
    if (!view_changed && !progressive_pending()) return false;
    first_ = false;
    force_render_ = false;
    frame_w_ = window_w, frame_h_ = window_h;
    // Rendered at 1/scale of the window along each side, each pixel shown as a block.
    shown_detail_ = detail;
    halftone_.samples = detail.samples;
    halftone_.objects_within = detail.reach;
    const int w = std::max(1, window_w / detail.scale), h = std::max(1, window_h / detail.scale);
    const CellId cell = state_.cell();
    StereoMode mode = stereo_;
    if (view_changed) {
      if (mode != StereoMode::Mono) {
        const Camera centre = state_.camera(mode == StereoMode::SideBySide ? std::max(1, w / 2) : w, h);
        rig_ = stereo_rig(c_, centre, stereo_opt_);
        if (rig_.problem != StereoRig::Problem::None) {
          if (stereo_problem_ != rig_.message()) say("stereo: " + rig_.message() + "; showing one eye");
          stereo_problem_ = rig_.message();
          mode = StereoMode::Mono;
        } else {
          stereo_problem_.clear();
        }
      }
      shown_mode_ = mode;
      TraverseParams search = lines_ ? exact_masks(search_) : search_;  // lines need exact masks
      // A half-tone: pieces of view between its samples show nothing, and are not followed.
      if (!lines_) search.samples_per_side = samples_per_side(halftone_.samples);
      // A long search last frame: this one on every thread the pictures use (strips.h).
      if (mode == StereoMode::Mono) {
        cam_ = state_.camera(w, h);
        full_ = searches_.find(c_, cam_, cell, search);
      } else {
        cam_ = rig_.left;
        searches_.find_pair(c_, rig_.left, rig_.left_at.cell, rig_.right, rig_.right_at.cell, search, full_, right_);
      }
      shown_ = progressive_ ? std::min<size_t>(size_t(opt_.progressive_rate), full_.avenues.size()) : full_.avenues.size();
    } else {
      shown_ = std::min(full_.avenues.size(), shown_ + size_t(opt_.progressive_rate));
    }
    if (shown_mode_ == StereoMode::Mono) {
      picture(cam_, full_, shown_, frame_);
    } else {
      picture(rig_.left, full_, shown_, left_);
      picture(rig_.right, right_, std::min(shown_, right_.avenues.size()), right_img_);
      frame_ = stereo_composite(left_, right_img_,
                                shown_mode_ == StereoMode::Anaglyph ? StereoComposite::Anaglyph : StereoComposite::Parallel);
    }
    return true;
  }

  void refresh_panels(int w, int h, double work_ms, double render_ms) {
    std::vector<std::string> lines;
    std::string l1 = plan_.stem + " | " + to_string(state_.mode()) + " | " + (lines_ ? "hidden lines" : "half-tone") +
                     " | " + to_string(shown_mode_);
    if (progressive_) l1 += " | progressive " + std::to_string(shown_) + "/" + std::to_string(full_.avenues.size());
    lines.push_back(l1 + "    H: help");
    if (shown_detail_ != budget_.full())
      lines.push_back("over the " + fixed(budget_.budget_ms(), 1) + " ms frame budget (" + fixed(budget_.last_ms(), 1) +
                      " ms): " + to_string(shown_detail()) + " while moving, full detail when the eye stops");
    // The hull search's cells are not all seen: it says so, and on how many threads it ran.
    std::string cells = " cells seen";
    if (full_.conservative)
      cells = searches_.threads_used() > 1 ? " cells (hull search on " + std::to_string(searches_.threads_used()) + " threads)"
                                           : " cells (hull search)";
    lines.push_back("frame " + fixed(work_ms, 1) + " ms, render " + fixed(render_ms, 1) + " ms | " +
                    std::to_string(full_.cells.size()) + cells + " through " + std::to_string(full_.avenues.size()) +
                    " avenues");
    const Vec3 e = state_.eye();
    lines.push_back(state_.place() + " | eye (" + fixed(e.x, 2) + ", " + fixed(e.y, 2) + ", " + fixed(e.z, 2) +
                    ") heading " + fixed(state_.yaw(), 0) + " pitch " + fixed(state_.pitch(), 0) + " fov " +
                    fixed(state_.fov(), 0));
    const std::string sw = controls_.switches_on();
    if (!sw.empty()) lines.push_back("sense switches on: " + sw);
    if (!message_.empty()) lines.push_back(message_);
    set_text_panel(hud_panel_, lines, 8, 8);
    status_ = lines;
    if (help_on_) set_centred_text_panel(help_panel_, help_lines(), w, h);
  }

  /// The walking state's pose and the view on screen, as JSON.
  nlohmann::json pose_json() const {
    nlohmann::json j = state_.pose_json();
    j["style"] = lines_ ? "lines" : "halftone";
    j["stereo"] = to_string(shown_mode_);
    j["visible_cells"] = full_.cells.size();
    j["avenues"] = full_.avenues.size();
    j["search_threads"] = searches_.threads_used();
    j["size"] = {frame_w_, frame_h_};
    j["detail"] = {{"samples", shown_detail_.samples}, {"scale", shown_detail_.scale}};
    if (shown_detail().reach < HUGE_VAL) j["detail"]["objects_within_m"] = shown_detail().reach;
    j["status"] = status_;
    return j;
  }

  void screenshot(const std::string& path, WalkReport& report) {
    try {
      write_image(viewer_.read_back(), path);
      nlohmann::json shot = pose_json();
      shot["file"] = path;
      shot["view_options"] = view_options();
      report.shots.push_back(shot);
      std::cout << "screenshot " << path << ": " << view_options() << "\n";
    } catch (const std::exception& e) {
      say(std::string("screenshot: ") + e.what());
    }
  }

  /// `avenues view` options that draw the view on screen: the pose, and the search where
  /// it is not view's own default (the hull search's half-tone).
  std::string view_options() const {
    return state_.pose_text(frame_w_, frame_h_) + (search_.hull_pieces && !lines_ ? " --search hull" : "");
  }

  ViewSetup view_setup() const {
    ViewSetup v;
    v.camera = state_.camera(frame_w_, frame_h_);
    v.viewpoint.eye = state_.eye();
    v.viewpoint.look = state_.eye() + v.camera.forward;
    v.viewpoint.fov_deg = state_.fov();
    v.kernel = kernel_;
    v.search = search_;
    v.eye_cell = state_.cell();
    return v;
  }

  /// Runs one export (app/walk_exports.h) and shows what it said, or why it failed.
  template <class F>
  void export_by(const char* what, F&& f) {
    try {
      say(f());
    } catch (const std::exception& e) {
      say(std::string(what) + ": " + e.what());
    }
  }
  void export_picture() {
    export_by("export", [&] { return exports_.picture(frame_); });
  }
  void export_view(const std::string& ext, const std::string& stereo) {
    export_by("export", [&] { return exports_.view(view_setup(), ext, stereo); });
  }
  void export_stereo() {
    export_view(".png", "parallel");
    export_view(".svg", "pair");
  }
  void record_keyframe() {
    export_by("keyframe", [&] { return exports_.keyframe(state_.eye(), state_.eye() + state_.camera(16, 9).forward); });
  }

  const LoadedPlan& plan_;
  const CellComplex& c_;
  const WalkOptions& opt_;
  Viewer& viewer_;
  FrameBudget budget_;
  Detail shown_detail_;   ///< what the frame on screen was rendered at
  /// What the frame on screen shows of shown_detail_ (the status line, the stats): a
  /// hidden-line drawing draws every object at any step.
  Detail shown_detail() const {
    Detail d = shown_detail_;
    if (lines_) d.reach = HUGE_VAL;
    return d;
  }
  bool refining_ = false; ///< this frame renders the still view again at full detail
  WalkState state_;
  WalkExports exports_;
  Controls controls_;
  Kernel kernel_ = Kernel::Double;
  TraverseParams search_;
  FrameSearches searches_;  ///< the frames' searches, side by side when long; on the pictures' threads
  HalftoneOptions halftone_;
  SceneEffects effects_;
  std::optional<SceneEffects> effects_at_eye_;  ///< lit from the eye: the budget's cheaper frames in a plan with lamps
  StereoOptions stereo_opt_;
  std::vector<PlacedObject> objects_;
  /// The objects' coarser versions while they are being made (coarser_versions).
  std::future<std::vector<std::vector<MeshLevel>>> coarser_;

  /// Hands the coarser versions to the objects once they are made (`wait`: waits for them).
  /// Between frames, so no drawing is using the objects meanwhile.
  void adopt_coarser(bool wait) {
    if (!coarser_.valid()) return;
    if (!wait && coarser_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
    std::vector<std::vector<MeshLevel>> levels;
    try {
      levels = coarser_.get();
    } catch (const std::exception& e) {
      say(std::string("the furniture stays in full detail: ") + e.what());
      return;
    }
    for (size_t i = 0; i < objects_.size() && i < levels.size(); ++i) set_coarser(objects_[i], std::move(levels[i]));
  }
  std::optional<LineScene> scene_;
  bool lines_ = false, progressive_ = false, hud_on_ = true, help_on_ = false;
  StereoMode stereo_ = StereoMode::Mono, shown_mode_ = StereoMode::Mono;
  // The view on screen.
  bool first_ = true, moving_ = false, force_render_ = false, state_changed_ = true;
  int frame_w_ = 0, frame_h_ = 0;
  Camera cam_;
  StereoRig rig_;
  std::string stereo_problem_;
  VisibleSet full_, right_;
  size_t shown_ = 0;  ///< avenues drawn (progressive display)
  Image frame_, left_, right_img_;
  FrameStorage storage_;  ///< the half-tone's arrays, kept from frame to frame
  OverlayPanel hud_panel_, help_panel_;
  std::vector<std::string> status_;  ///< the status line's text, as last set
  std::string message_;
  Clock::time_point message_until_;
};

bool run_session(const LoadedPlan& plan, const WalkOptions& opt, const std::vector<ScriptEvent>& events,
                 WalkReport& report, std::string& why) {
  int w = 0, h = 0;
  size_option(opt.size, w, h);
  std::unique_ptr<Viewer> viewer = Viewer::open(w, h, "Avenues - " + plan.stem, opt.vsync, why);
  if (!viewer) return false;
  Session session(plan, opt, *viewer);
  session.run(events, report);
  return true;
}

std::vector<ScriptEvent> script_events(const WalkOptions& opt) {
  if (!opt.script.empty() && opt.random_input)
    throw std::runtime_error("give either --script FILE or --random-input SEED, not both");
  if (!opt.script.empty()) return read_script(opt.script);
  if (!opt.random_input) return {};
  if (opt.frames <= 0) throw std::runtime_error("--random-input needs --frames N");
  const fs::path tmp = fs::temp_directory_path() / ("avenues-random-" + std::to_string(::getpid()) + ".txt");
  write_file_atomically(tmp.string(), random_script(*opt.random_input, opt.frames));
  std::vector<ScriptEvent> events = read_script(tmp.string());
  fs::remove(tmp);
  return events;
}

}  // namespace

bool run_walkthrough(const LoadedPlan& plan, const WalkOptions& opt, int& status, std::string& why) {
  const std::vector<ScriptEvent> events = script_events(opt);
  WalkReport report;
  if (!run_session(plan, opt, events, report, why)) return false;
  if (!opt.stats_json.empty()) write_stats(opt.stats_json, plan.path, report);
  status = 0;
  return true;
}

int run_walk(const WalkOptions& opt) {
  LoadedPlan plan = load_plan_source(opt.plan, opt.import);
  int status = 0;
  std::string why;
  if (!run_walkthrough(plan, opt, status, why))
    throw std::runtime_error("cannot open the walkthrough window: " + why +
                             " (`avenues view` and `avenues path` write pictures without one)");
  return status;
}

int run_bench_walk(const std::vector<std::string>& plans, long frames, const std::string& size, double frame_budget_ms,
                   const std::string& lights, const std::string& search, double detail) {
  if (frames < 20) throw std::runtime_error("--frames must be at least 20");
  std::vector<std::string> files = plans;
  if (files.empty())
    for (const char* p : {"jones-house", "two-storey-house", "office-corridor", "furnished-room", "curved-walls"})
      files.push_back((fs::path(default_plan_path()).parent_path() / (std::string(p) + ".toml")).string());
  const char* display = std::getenv("DISPLAY");
  std::cout << "walkthrough window, " << size << " half-tone, flat shading, 1 sample, status line on, no vsync; "
            << frames << " frames per plan walking forward while turning 90 deg/s (the first 10 not counted); frame budget "
            << (frame_budget_ms > 0 ? fixed(frame_budget_ms, 1) + " ms" : std::string("off")) << "; lights " << lights
            << "; search " << search << "; detail " << (detail > 0 ? fixed(detail, 2) + " samples" : std::string("full")) << "; DISPLAY="
            << (display ? display : "") << "\n"
            << "frame: period from one frame's start to the next (percentiles); render: visibility and half-tone;\n"
            << "show: texture upload, blit and status line; swap: glfwSwapBuffers (medians); CPU/frame: this\n"
            << "process's CPU time (all threads, Mesa's included; not the X server's) per frame; reduced: frames\n"
            << "rendered below full detail to keep to the budget\n\n";
  std::cout << std::left << std::setw(24) << "plan" << std::right << std::setw(10) << "median" << std::setw(10) << "p95"
            << std::setw(10) << "p99" << std::setw(8) << "fps" << std::setw(12) << "render" << std::setw(10) << "show"
            << std::setw(10) << "swap" << std::setw(12) << "CPU/frame" << std::setw(9) << "reduced" << "\n";
  // Walk forward and turn right the whole time: a new view every frame, sliding along walls.
  std::vector<ScriptEvent> events(2);
  events[0].what = events[1].what = ScriptEvent::What::Down;
  events[0].key = key_code("W");
  events[1].key = key_code("RIGHT");
  for (const std::string& file : files) {
    LoadedPlan plan = load_plan_source(file);
    WalkOptions opt;
    opt.size = size;
    opt.frames = frames + 10;
    opt.vsync = false;
    opt.frame_budget_ms = frame_budget_ms;
    opt.lights = lights;
    opt.search = search;
    opt.detail = detail;
    WalkReport report;
    std::string why;
    if (!run_session(plan, opt, events, report, why)) throw std::runtime_error("cannot open the walkthrough window: " + why);
    std::vector<double> period(report.frame_ms.begin() + std::min<long>(10, long(report.frame_ms.size())), report.frame_ms.end());
    std::vector<double> render(report.render_ms.begin() + std::min<long>(10, long(report.render_ms.size())), report.render_ms.end());
    const Percentiles f = percentiles(period), r = percentiles(render), sh = percentiles(report.show_ms),
                      sw = percentiles(report.swap_ms);
    std::cout << std::left << std::setw(24) << plan.stem << std::right << std::setw(7) << fixed(f.median, 2) << " ms"
              << std::setw(7) << fixed(f.p95, 2) << " ms" << std::setw(7) << fixed(f.p99, 2) << " ms" << std::setw(8)
              << fixed(1000 / f.median, 0) << std::setw(9) << fixed(r.median, 2) << " ms" << std::setw(7)
              << fixed(sh.median, 2) << " ms" << std::setw(7) << fixed(sw.median, 2) << " ms" << std::setw(9)
              << fixed(1000 * (report.cpu_s_last - report.cpu_s_10) / double(frames), 2) << " ms" << std::setw(8)
              << fixed(100.0 * double(report.reduced_frames) / double(report.work_ms.size()), 0) << "%\n";
  }
  return 0;
}

}  // namespace avenues::app
