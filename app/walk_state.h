// Avenues — the walkthrough's walking state: where the eye is (the walker: walk mode keeps
// to the floors and goes through doors, fly mode anywhere in free space), where it looks
// (heading, pitch) and how wide (field of view), and what one frame's motion does to them.
// No window: the session feeds it the controls' motion, and tests can drive it alone.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/controls.h"
#include "visibility/camera.h"
#include "visibility/walker.h"

namespace avenues::app {

class WalkState {
 public:
  static constexpr double kMinFov = 5, kMaxFov = 150;  ///< [deg] the zoom's limits

  /// The pose `opt` asks for (--eye, --look, --fov, --fly; else the plan's viewpoint), in
  /// walk mode at that height above the floor when it is a person's (app/walk_state.cpp).
  /// Throws when the eye is not in free space, naming what holds it.
  WalkState(const LoadedPlan& plan, const WalkOptions& opt);

  /// Applies one frame's motion; returns whether the eye or the view changed.
  bool step(const Motion& m, double dt);
  void level() { pitch_ = 0; }
  void toggle_mode() { walker_.set_mode(walker_.mode() == MoveMode::Walk ? MoveMode::Fly : MoveMode::Walk); }

  Vec3 eye() const { return walker_.eye(); }
  CellId cell() const { return walker_.cell(); }
  MoveMode mode() const { return walker_.mode(); }
  double yaw() const { return yaw_; }      ///< [deg] heading, anticlockwise from +x
  double pitch() const { return pitch_; }  ///< [deg] up
  double fov() const { return fov_; }      ///< [deg] horizontal
  /// The camera of a w × h picture of the view.
  Camera camera(int w, int h) const { return Camera::yaw_pitch(walker_.eye(), yaw_, pitch_, fov_, w, h); }

  /// "room 'K', storey 'ground'": where the eye stands, for the status line.
  std::string place() const;
  /// The pose as `avenues view` options that reproduce a w × h view of it.
  std::string pose_text(int w, int h) const;
  /// The pose (eye, yaw, pitch, fov, mode, cell, room, storey) as JSON.
  nlohmann::json pose_json() const;

 private:
  WalkState(const LoadedPlan& plan, const WalkOptions& opt, const ViewSetup& v);
  const CellComplex& c_;
  Walker walker_;
  double yaw_ = 0, pitch_ = 0, fov_ = 60;  ///< [deg]
};

}  // namespace avenues::app
