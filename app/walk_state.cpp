// Avenues — the walkthrough's walking state (see walk_state.h).
#include "app/walk_state.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"
#include "core/number_format.h"
#include "plans/formats/doom_map.h"

namespace avenues::app {

namespace {

ViewOptions view_options(const WalkOptions& opt) {
  ViewOptions v;
  v.plan = opt.plan;
  v.eye = opt.eye, v.look = opt.look, v.fov = opt.fov, v.size = opt.size, v.kernel = opt.kernel, v.search = opt.search;
  return v;
}

/// Walk mode keeps the eye at the height above its floor it starts at (a plan's view, a
/// Doom player's 41 units), when that is a person's; else at 1.6 m. A Doom map's player
/// steps up to 24 map units, its stairs' risers 8 to 24.
WalkerOptions walker_options(const CellComplex& c, Vec3 eye, FileFormat format) {
  WalkerOptions o;
  if (format == FileFormat::DoomWad) o.step_height = 24 * kDoomUnit;
  const double above = eye.z - Walker(c, eye, o).floor_below();
  if (above >= 1.0 && above <= 2.2) o.eye_height = above;
  if (!(o.eye_height > o.step_height + 0.1)) o.step_height = o.eye_height / 2;
  return o;
}

}  // namespace

WalkState::WalkState(const LoadedPlan& plan, const WalkOptions& opt)
    : WalkState(plan, opt, set_up_view(plan, view_options(opt))) {}

WalkState::WalkState(const LoadedPlan& plan, const WalkOptions& opt, const ViewSetup& v)
    : c_(plan.complex),
      walker_(c_, v.viewpoint.eye, walker_options(c_, v.viewpoint.eye, plan.format)) {
  const Vec3 f = v.camera.forward;
  yaw_ = deg_from_rad(std::atan2(f.y, f.x));
  pitch_ = deg_from_rad(std::asin(std::clamp(f.z, -1.0, 1.0)));
  fov_ = v.viewpoint.fov_deg;
  walker_.set_mode(opt.fly ? MoveMode::Fly : MoveMode::Walk);
}

bool WalkState::step(const Motion& m, double dt) {
  const Vec3 eye0 = walker_.eye();
  const double yaw0 = yaw_, pitch0 = pitch_, fov0 = fov_;
  yaw_ = std::remainder(yaw_ + m.turn, 360.0);
  pitch_ = std::clamp(pitch_ + m.pitch, -89.0, 89.0);
  if (m.zoom != 1) {
    // The picture's scale is 1/tan(fov/2): zoom multiplies it.
    const double scale = 1 / std::tan(rad_from_deg(fov_) / 2) * m.zoom;
    fov_ = std::clamp(deg_from_rad(2 * std::atan(1 / scale)), kMinFov, kMaxFov);
  }
  const double y = rad_from_deg(yaw_), p = rad_from_deg(pitch_);
  const Vec3 heading{std::cos(y), std::sin(y), 0}, right{std::sin(y), -std::cos(y), 0};
  // Walking goes along the heading; flying goes where the eye looks.
  const Vec3 ahead =
      walker_.mode() == MoveMode::Fly ? Vec3{std::cos(p) * std::cos(y), std::cos(p) * std::sin(y), std::sin(p)} : heading;
  const Vec3 d = m.forward * ahead + m.strafe * right + Vec3{m.world_x, m.world_y, m.world_z + m.up};
  walker_.move(d, dt);
  return !(walker_.eye() == eye0) || yaw_ != yaw0 || pitch_ != pitch0 || fov_ != fov0;
}

std::string WalkState::place() const {
  const Cell& cell = c_.cells[size_t(walker_.cell())];
  const std::string room =
      cell.room >= 0 ? "room '" + c_.rooms[size_t(cell.room)].name + "'" : std::string(to_string(cell.kind));
  const std::string storey = cell.storey >= 0 && size_t(cell.storey) < c_.storeys.size()
                                 ? "storey '" + c_.storeys[size_t(cell.storey)].name + "'"
                                 : std::string("no storey");
  return room + ", " + storey;
}

std::string WalkState::pose_text(int w, int h) const {
  const Vec3 e = walker_.eye();
  return "--eye " + format_exact(e.x) + "," + format_exact(e.y) + "," + format_exact(e.z) + " --yaw " + format_exact(yaw_) + " --pitch " +
         format_exact(pitch_) + " --fov " + format_exact(fov_) + " --size " + std::to_string(w) + "x" + std::to_string(h);
}

nlohmann::json WalkState::pose_json() const {
  const Vec3 e = walker_.eye();
  const Cell& cell = c_.cells[size_t(walker_.cell())];
  return {{"eye", {e.x, e.y, e.z}},
          {"yaw", yaw_},
          {"pitch", pitch_},
          {"fov", fov_},
          {"mode", to_string(walker_.mode())},
          {"cell", walker_.cell()},
          {"room", cell.room >= 0 ? c_.rooms[size_t(cell.room)].name : std::string(to_string(cell.kind))},
          {"storey", cell.storey >= 0 && size_t(cell.storey) < c_.storeys.size() ? c_.storeys[size_t(cell.storey)].name : ""}};
}

}  // namespace avenues::app
