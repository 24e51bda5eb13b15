// Avenues — the walkthrough's controls: keyboard, mouse, gamepad and Jones's sense switches.
//
// Jones 1971 moved the eye with the PDP-7's console: "the eight sense switches ... x+, x−,
// y+, y−, z+, z−, scale+, scale−", latching switches that, while on, kept changing the view.
// Here they are the number keys 1–8: each press latches its switch on or off, and while on
// it moves the eye at sense_speed along its world axis (x, y, z), or changes the scale of
// the picture — its magnification, 1/tan(fov/2) — by scale_rate per second (scale+ narrows
// the field of view, scale− widens it). Every other control is held (walk, turn, look,
// climb, zoom) or a command taken once per press (toggles, exports). The bindings are one
// table, which the help overlay lists.
//
// Nothing here opens a window: key codes are GLFW's, and the walkthrough (cmd_walk.cpp)
// feeds events in from GLFW's callbacks or from a replayed script alike.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace avenues::app {

enum class Action : uint8_t {
  // Held.
  Forward, Back, StrafeLeft, StrafeRight, TurnLeft, TurnRight, LookUp, LookDown, Up, Down, ZoomIn, ZoomOut, Run,
  // Taken once per press.
  Switch1, Switch2, Switch3, Switch4, Switch5, Switch6, Switch7, Switch8, SwitchesOff,
  ToggleFly, ToggleLines, CycleStereo, ToggleProgressive, ToggleHelp, ToggleHud, CaptureMouse, LevelView,
  ExportPicture, ExportDrawing, ExportStereo, RecordKeyframe, Quit,
};

/// True for an action taken once per press (not held).
bool is_command(Action a);

struct Binding {
  int key;           ///< GLFW key code
  Action action;
  const char* label; ///< the key as the help shows it
  const char* what;  ///< what it does
};
/// Every key binding, in the order the help lists them.
const std::vector<Binding>& bindings();
/// The help overlay's lines: keys, mouse, gamepad and sense switches.
std::vector<std::string> help_lines();

/// GLFW key code for a script's key name ("W", "UP", "PAGE_UP", "F2", "1", "KP_ADD", ...);
/// -1 if unknown.
int key_code(const std::string& name);
/// The names key_code() knows, for messages.
std::string key_names();

/// GLFW_GAMEPAD_AXIS_* and GLFW_GAMEPAD_BUTTON_* by their names without the prefix
/// ("LEFT_Y", "A", "DPAD_UP"); -1 for other names.
int gamepad_axis_code(const std::string& name);
int gamepad_button_code(const std::string& name);
/// The names those know, for messages.
std::string gamepad_names();

/// The switches' names, in order: x+, x−, y+, y−, z+, z−, scale+, scale−.
const std::array<const char*, 8>& switch_names();

/// A gamepad's state as GLFW reports it (GLFWgamepadstate), copied.
struct GamepadState {
  bool present = false;
  std::array<float, 6> axes{};       ///< left x, left y, right x, right y, left trigger, right trigger: [-1, 1]
  std::array<uint8_t, 15> buttons{}; ///< GLFW_GAMEPAD_BUTTON_*: 1 pressed
};

/// What the controls ask of the eye for one frame.
struct Motion {
  double forward = 0, strafe = 0;  ///< [m] along the heading, and to its right
  double turn = 0, pitch = 0;      ///< [deg] heading anticlockwise, pitch up
  double up = 0;                   ///< [m] vertical (climb in walk mode)
  double world_x = 0, world_y = 0, world_z = 0;  ///< [m] the sense switches' moves, along world axes
  double zoom = 1;                 ///< factor on the picture's scale (> 1: narrower field of view)
};

struct ControlRates {
  double walk_speed = 1.4;   ///< [m/s]
  double run_factor = 3;     ///< with Shift held
  double turn_rate = 90;     ///< [deg/s]
  double look_rate = 60;     ///< [deg/s] keyboard pitch
  double climb_speed = 1.2;  ///< [m/s] PgUp/PgDn
  double zoom_rate = 1.5;    ///< factor per second with +/−
  double sense_speed = 1.0;  ///< [m/s] a position switch
  double scale_rate = 1.25;  ///< factor per second: a scale switch
  double mouse_deg_per_px = 0.15;
  double stick_dead_zone = 0.15;
};

class Controls {
 public:
  explicit Controls(const ControlRates& rates = {}) : rates_(rates) {}

  /// A key went down or up (GLFW code). A command's press is queued for take_commands().
  void key(int code, bool down);
  /// The mouse moved by (dx, dy) [px] while looking (a button held, or the cursor captured).
  void look(double dx, double dy);
  /// The gamepad's state this frame; a button's press is a command like a key's.
  void gamepad(const GamepadState& g);
  /// Commands pressed since the last call, in order.
  std::vector<Action> take_commands();
  /// The frame's motion over dt seconds (held keys, sticks, switches, mouse look since the
  /// last call, which it consumes).
  Motion motion(double dt);
  /// Flips switch i (0..7).
  void flip_switch(int i) { switches_[size_t(i)] = !switches_[size_t(i)]; }
  void switches_off() { switches_.fill(false); }
  const std::array<bool, 8>& switches() const { return switches_; }
  /// "x+ scale−": the switches that are on; "" when none.
  std::string switches_on() const;
  /// True when anything would move the eye without a new event (held keys, switches, sticks).
  bool active() const;
  /// Releases every held key (the window lost focus).
  void release_all();

 private:
  bool held(Action a) const;
  ControlRates rates_;
  std::vector<int> down_;  ///< key codes held
  std::array<bool, 8> switches_{};
  std::vector<Action> commands_;
  double look_dx_ = 0, look_dy_ = 0;
  GamepadState pad_, pad_before_;
};

}  // namespace avenues::app
