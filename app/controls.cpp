// Avenues — the walkthrough's controls (see controls.h).
#include "app/controls.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace avenues::app {

bool is_command(Action a) { return a >= Action::Switch1; }

const std::vector<Binding>& bindings() {
  static const std::vector<Binding> table = {
      {GLFW_KEY_W, Action::Forward, "W S, Up Down", "walk forward, back"},
      {GLFW_KEY_UP, Action::Forward, "", ""},
      {GLFW_KEY_S, Action::Back, "", ""},
      {GLFW_KEY_DOWN, Action::Back, "", ""},
      {GLFW_KEY_A, Action::StrafeLeft, "A D", "step left, right"},
      {GLFW_KEY_D, Action::StrafeRight, "", ""},
      {GLFW_KEY_LEFT, Action::TurnLeft, "Left Right, Q E", "turn left, right"},
      {GLFW_KEY_Q, Action::TurnLeft, "", ""},
      {GLFW_KEY_RIGHT, Action::TurnRight, "", ""},
      {GLFW_KEY_E, Action::TurnRight, "", ""},
      {GLFW_KEY_R, Action::LookUp, "R V, Home", "look up, down; look level"},
      {GLFW_KEY_V, Action::LookDown, "", ""},
      {GLFW_KEY_HOME, Action::LevelView, "", ""},
      {GLFW_KEY_PAGE_UP, Action::Up, "PgUp PgDn", "up, down (walking: climb, descend a stairwell)"},
      {GLFW_KEY_PAGE_DOWN, Action::Down, "", ""},
      {GLFW_KEY_EQUAL, Action::ZoomIn, "+ -", "zoom in, out (narrower, wider field of view)"},
      {GLFW_KEY_KP_ADD, Action::ZoomIn, "", ""},
      {GLFW_KEY_MINUS, Action::ZoomOut, "", ""},
      {GLFW_KEY_KP_SUBTRACT, Action::ZoomOut, "", ""},
      {GLFW_KEY_LEFT_SHIFT, Action::Run, "Shift", "hold to go three times as fast"},
      {GLFW_KEY_RIGHT_SHIFT, Action::Run, "", ""},
      {GLFW_KEY_1, Action::Switch1, "1 .. 8, 0", "sense switches x+ x- y+ y- z+ z- scale+ scale- (latch); 0: all off"},
      {GLFW_KEY_2, Action::Switch2, "", ""},
      {GLFW_KEY_3, Action::Switch3, "", ""},
      {GLFW_KEY_4, Action::Switch4, "", ""},
      {GLFW_KEY_5, Action::Switch5, "", ""},
      {GLFW_KEY_6, Action::Switch6, "", ""},
      {GLFW_KEY_7, Action::Switch7, "", ""},
      {GLFW_KEY_8, Action::Switch8, "", ""},
      {GLFW_KEY_0, Action::SwitchesOff, "", ""},
      {GLFW_KEY_F, Action::ToggleFly, "F", "walk / fly"},
      {GLFW_KEY_L, Action::ToggleLines, "L", "half-tone / hidden lines"},
      {GLFW_KEY_B, Action::CycleStereo, "B", "mono / stereo side by side / anaglyph"},
      {GLFW_KEY_P, Action::ToggleProgressive, "P", "progressive display (cell by cell) on / off"},
      {GLFW_KEY_M, Action::CaptureMouse, "M", "capture the mouse (look without a button) on / off"},
      {GLFW_KEY_F2, Action::ExportPicture, "F2", "write the picture as shown (PNG)"},
      {GLFW_KEY_F3, Action::ExportDrawing, "F3", "write the hidden-line drawing (SVG)"},
      {GLFW_KEY_F4, Action::ExportStereo, "F4", "write a stereo pair (PNG side by side, SVG left and right)"},
      {GLFW_KEY_K, Action::RecordKeyframe, "K", "record a keyframe (for avenues path --keys)"},
      {GLFW_KEY_TAB, Action::ToggleHud, "Tab", "status line on / off"},
      {GLFW_KEY_H, Action::ToggleHelp, "H, F1", "this help on / off"},
      {GLFW_KEY_F1, Action::ToggleHelp, "", ""},
      {GLFW_KEY_ESCAPE, Action::Quit, "Esc", "free the mouse, else quit"},
  };
  return table;
}

std::vector<std::string> help_lines() {
  std::vector<std::string> lines = {"Avenues walkthrough: the controls", ""};
  for (const Binding& b : bindings()) {
    if (!*b.label) continue;
    std::string l = b.label;
    l.resize(std::max<size_t>(l.size(), 16), ' ');
    lines.push_back(l + "  " + b.what);
  }
  lines.push_back("mouse             look while a button is held (or always, captured with M)");
  lines.push_back("gamepad           left stick walk, right stick look, triggers down/up, shoulders");
  lines.push_back("                  zoom, A walk/fly, B lines, X stereo, Y help, Start keyframe");
  lines.push_back("The switches move the eye 1 m/s along the world's axes or zoom 1.25x a second.");
  return lines;
}

namespace {

const std::vector<std::pair<std::string, int>>& named_keys() {
  static const std::vector<std::pair<std::string, int>> keys = [] {
    std::vector<std::pair<std::string, int>> k;
    for (char c = 'A'; c <= 'Z'; ++c) k.push_back({std::string(1, c), GLFW_KEY_A + (c - 'A')});
    for (char c = '0'; c <= '9'; ++c) k.push_back({std::string(1, c), GLFW_KEY_0 + (c - '0')});
    for (int f = 1; f <= 12; ++f) {
      std::string name = "F";
      name += std::to_string(f);
      k.push_back({name, GLFW_KEY_F1 + f - 1});
    }
    const std::pair<const char*, int> more[] = {
        {"UP", GLFW_KEY_UP}, {"DOWN", GLFW_KEY_DOWN}, {"LEFT", GLFW_KEY_LEFT}, {"RIGHT", GLFW_KEY_RIGHT},
        {"PAGE_UP", GLFW_KEY_PAGE_UP}, {"PAGE_DOWN", GLFW_KEY_PAGE_DOWN}, {"HOME", GLFW_KEY_HOME},
        {"END", GLFW_KEY_END}, {"ESCAPE", GLFW_KEY_ESCAPE}, {"TAB", GLFW_KEY_TAB}, {"SPACE", GLFW_KEY_SPACE},
        {"ENTER", GLFW_KEY_ENTER}, {"LEFT_SHIFT", GLFW_KEY_LEFT_SHIFT}, {"RIGHT_SHIFT", GLFW_KEY_RIGHT_SHIFT},
        {"EQUAL", GLFW_KEY_EQUAL}, {"MINUS", GLFW_KEY_MINUS}, {"KP_ADD", GLFW_KEY_KP_ADD},
        {"KP_SUBTRACT", GLFW_KEY_KP_SUBTRACT}, {"INSERT", GLFW_KEY_INSERT}, {"DELETE", GLFW_KEY_DELETE}};
    for (const auto& [name, code] : more) k.push_back({name, code});
    return k;
  }();
  return keys;
}

constexpr std::array<const char*, 8> kSwitchNames = {"x+", "x-", "y+", "y-", "z+", "z-", "scale+", "scale-"};

/// A stick's deflection past the dead zone, rescaled to [-1, 1].
double stick(float v, double dead) {
  const double a = std::fabs(v);
  if (a <= dead) return 0;
  return std::copysign(std::min(1.0, (a - dead) / (1 - dead)), double(v));
}

}  // namespace

int key_code(const std::string& name) {
  for (const auto& [n, code] : named_keys())
    if (n == name) return code;
  return -1;
}

namespace {
const std::pair<const char*, int> kPadAxes[] = {
    {"LEFT_X", GLFW_GAMEPAD_AXIS_LEFT_X},           {"LEFT_Y", GLFW_GAMEPAD_AXIS_LEFT_Y},
    {"RIGHT_X", GLFW_GAMEPAD_AXIS_RIGHT_X},         {"RIGHT_Y", GLFW_GAMEPAD_AXIS_RIGHT_Y},
    {"LEFT_TRIGGER", GLFW_GAMEPAD_AXIS_LEFT_TRIGGER}, {"RIGHT_TRIGGER", GLFW_GAMEPAD_AXIS_RIGHT_TRIGGER}};
const std::pair<const char*, int> kPadButtons[] = {
    {"A", GLFW_GAMEPAD_BUTTON_A},
    {"B", GLFW_GAMEPAD_BUTTON_B},
    {"X", GLFW_GAMEPAD_BUTTON_X},
    {"Y", GLFW_GAMEPAD_BUTTON_Y},
    {"LEFT_BUMPER", GLFW_GAMEPAD_BUTTON_LEFT_BUMPER},
    {"RIGHT_BUMPER", GLFW_GAMEPAD_BUTTON_RIGHT_BUMPER},
    {"BACK", GLFW_GAMEPAD_BUTTON_BACK},
    {"START", GLFW_GAMEPAD_BUTTON_START},
    {"GUIDE", GLFW_GAMEPAD_BUTTON_GUIDE},
    {"LEFT_THUMB", GLFW_GAMEPAD_BUTTON_LEFT_THUMB},
    {"RIGHT_THUMB", GLFW_GAMEPAD_BUTTON_RIGHT_THUMB},
    {"DPAD_UP", GLFW_GAMEPAD_BUTTON_DPAD_UP},
    {"DPAD_RIGHT", GLFW_GAMEPAD_BUTTON_DPAD_RIGHT},
    {"DPAD_DOWN", GLFW_GAMEPAD_BUTTON_DPAD_DOWN},
    {"DPAD_LEFT", GLFW_GAMEPAD_BUTTON_DPAD_LEFT}};
}  // namespace

int gamepad_axis_code(const std::string& name) {
  for (const auto& [n, code] : kPadAxes)
    if (n == name) return code;
  return -1;
}

int gamepad_button_code(const std::string& name) {
  for (const auto& [n, code] : kPadButtons)
    if (n == name) return code;
  return -1;
}

std::string gamepad_names() {
  std::string out = "axes";
  for (const auto& [n, code] : kPadAxes) out += std::string(code == 0 ? " " : ", ") + n;
  out += "; buttons";
  for (const auto& [n, code] : kPadButtons) out += std::string(code == 0 ? " " : ", ") + n;
  return out;
}

std::string key_names() {
  return "A..Z, 0..9, F1..F12, UP, DOWN, LEFT, RIGHT, PAGE_UP, PAGE_DOWN, HOME, END, ESCAPE, TAB, SPACE, ENTER, "
         "LEFT_SHIFT, RIGHT_SHIFT, EQUAL, MINUS, KP_ADD, KP_SUBTRACT, INSERT, DELETE";
}

const std::array<const char*, 8>& switch_names() { return kSwitchNames; }

void Controls::key(int code, bool down) {
  const auto it = std::find(down_.begin(), down_.end(), code);
  const bool was_down = it != down_.end();
  if (down && !was_down) down_.push_back(code);
  if (!down && was_down) down_.erase(it);
  if (!down || was_down) return;  // commands on the press only (no auto-repeat)
  for (const Binding& b : bindings())
    if (b.key == code && is_command(b.action)) commands_.push_back(b.action);
}

void Controls::look(double dx, double dy) {
  look_dx_ += dx;
  look_dy_ += dy;
}

void Controls::gamepad(const GamepadState& g) {
  pad_before_ = pad_;
  pad_ = g;
  if (!g.present) return;
  const std::pair<int, Action> presses[] = {{GLFW_GAMEPAD_BUTTON_A, Action::ToggleFly},
                                            {GLFW_GAMEPAD_BUTTON_B, Action::ToggleLines},
                                            {GLFW_GAMEPAD_BUTTON_X, Action::CycleStereo},
                                            {GLFW_GAMEPAD_BUTTON_Y, Action::ToggleHelp},
                                            {GLFW_GAMEPAD_BUTTON_BACK, Action::ToggleHud},
                                            {GLFW_GAMEPAD_BUTTON_START, Action::RecordKeyframe},
                                            {GLFW_GAMEPAD_BUTTON_GUIDE, Action::LevelView}};
  for (const auto& [button, action] : presses)
    if (pad_.buttons[size_t(button)] && !pad_before_.buttons[size_t(button)]) commands_.push_back(action);
}

std::vector<Action> Controls::take_commands() { return std::exchange(commands_, {}); }

bool Controls::held(Action a) const {
  for (const Binding& b : bindings())
    if (b.action == a && std::find(down_.begin(), down_.end(), b.key) != down_.end()) return true;
  return false;
}

Motion Controls::motion(double dt) {
  Motion m;
  const double run = held(Action::Run) ? rates_.run_factor : 1;
  auto axis = [&](Action plus, Action minus) { return (held(plus) ? 1.0 : 0.0) - (held(minus) ? 1.0 : 0.0); };
  double forward = axis(Action::Forward, Action::Back), strafe = axis(Action::StrafeRight, Action::StrafeLeft);
  double turn = axis(Action::TurnLeft, Action::TurnRight), pitch = axis(Action::LookUp, Action::LookDown);
  double up = axis(Action::Up, Action::Down), zoom = axis(Action::ZoomIn, Action::ZoomOut);
  if (pad_.present) {
    const double dz = rates_.stick_dead_zone;
    forward -= stick(pad_.axes[GLFW_GAMEPAD_AXIS_LEFT_Y], dz);  // stick forward is negative
    strafe += stick(pad_.axes[GLFW_GAMEPAD_AXIS_LEFT_X], dz);
    turn -= stick(pad_.axes[GLFW_GAMEPAD_AXIS_RIGHT_X], dz);
    pitch -= stick(pad_.axes[GLFW_GAMEPAD_AXIS_RIGHT_Y], dz);
    // Triggers rest at -1 and go to +1.
    up += (pad_.axes[GLFW_GAMEPAD_AXIS_RIGHT_TRIGGER] + 1) / 2 - (pad_.axes[GLFW_GAMEPAD_AXIS_LEFT_TRIGGER] + 1) / 2;
    if (std::fabs(up) < dz) up = 0;
    up += pad_.buttons[GLFW_GAMEPAD_BUTTON_DPAD_UP] - pad_.buttons[GLFW_GAMEPAD_BUTTON_DPAD_DOWN];
    zoom += pad_.buttons[GLFW_GAMEPAD_BUTTON_RIGHT_BUMPER] - pad_.buttons[GLFW_GAMEPAD_BUTTON_LEFT_BUMPER];
  }
  auto clamp1 = [](double v) { return std::clamp(v, -1.0, 1.0); };
  m.forward = clamp1(forward) * rates_.walk_speed * run * dt;
  m.strafe = clamp1(strafe) * rates_.walk_speed * run * dt;
  m.turn = clamp1(turn) * rates_.turn_rate * dt - look_dx_ * rates_.mouse_deg_per_px;
  m.pitch = clamp1(pitch) * rates_.look_rate * dt - look_dy_ * rates_.mouse_deg_per_px;
  m.up = clamp1(up) * rates_.climb_speed * run * dt;
  m.zoom = std::pow(rates_.zoom_rate, clamp1(zoom) * dt);
  look_dx_ = look_dy_ = 0;
  // Jones's sense switches: x+ x- y+ y- z+ z- scale+ scale-.
  const double s = rates_.sense_speed * dt;
  const auto& sw = switches_;
  m.world_x = s * ((sw[0] ? 1 : 0) - (sw[1] ? 1 : 0));
  m.world_y = s * ((sw[2] ? 1 : 0) - (sw[3] ? 1 : 0));
  m.world_z = s * ((sw[4] ? 1 : 0) - (sw[5] ? 1 : 0));
  m.zoom *= std::pow(rates_.scale_rate, ((sw[6] ? 1 : 0) - (sw[7] ? 1 : 0)) * dt);
  return m;
}

std::string Controls::switches_on() const {
  std::string s;
  for (size_t i = 0; i < 8; ++i)
    if (switches_[i]) {
      if (!s.empty()) s += ' ';
      s += kSwitchNames[i];
    }
  return s;
}

bool Controls::active() const {
  for (const Binding& b : bindings())
    if (!is_command(b.action) && b.action != Action::Run && std::find(down_.begin(), down_.end(), b.key) != down_.end())
      return true;
  if (std::any_of(switches_.begin(), switches_.end(), [](bool b) { return b; })) return true;
  if (look_dx_ != 0 || look_dy_ != 0) return true;
  if (pad_.present) {
    for (int a = 0; a < 4; ++a)
      if (stick(pad_.axes[size_t(a)], rates_.stick_dead_zone) != 0) return true;
    if (pad_.axes[4] > -0.9 || pad_.axes[5] > -0.9) return true;
    for (int b : {GLFW_GAMEPAD_BUTTON_DPAD_UP, GLFW_GAMEPAD_BUTTON_DPAD_DOWN, GLFW_GAMEPAD_BUTTON_LEFT_BUMPER,
                  GLFW_GAMEPAD_BUTTON_RIGHT_BUMPER})
      if (pad_.buttons[size_t(b)]) return true;
  }
  return false;
}

void Controls::release_all() { down_.clear(); }

}  // namespace avenues::app
