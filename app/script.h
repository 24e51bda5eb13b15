// Avenues — a key-event script: input for the walkthrough window, replayed frame by frame.
//
// `avenues walk --script FILE` replays FILE as if a person pressed the keys, so that tests
// (and demonstrations) drive the real window. One event per line, "FRAME EVENT ARGS", the
// frame counted from 0 (events of a frame happen, in file order, before it is drawn); '#'
// starts a comment:
//
//   0    down W            key W goes down (held until "up")
//   90   up W
//   91   tap 1             pressed and released: latches sense switch 1 (x+)
//   120  look 200 -40      the mouse moves 200 px right, 40 px up while looking
//   150  resize 800 450    the window is resized
//   180  screenshot a.png  the frame as shown is read back and written (PNG)
//   181  pose              the eye, heading, pitch and field of view are printed
//   200  pad LEFT_Y -1     a gamepad's stick or trigger moves to a value in [-1, 1], or a
//   230  pad A 1           button goes down (1) or up (0): the scripted pad stands in for
//                          a real one, as GLFW would report it, until the script ends
//   240  quit
//
// Key names are GLFW's without the prefix (W, UP, PAGE_UP, F2, 1, KP_ADD, ...); so are
// the gamepad's axes (LEFT_X, LEFT_Y, RIGHT_X, RIGHT_Y, LEFT_TRIGGER, RIGHT_TRIGGER) and
// buttons (A, B, X, Y, LEFT_BUMPER, ..., BACK, START, GUIDE, DPAD_UP, ...).
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "app/controls.h"

namespace avenues::app {

struct ScriptEvent {
  enum class What : uint8_t { Down, Up, Tap, Look, Resize, Screenshot, Pose, Quit, PadAxis, PadButton } what = What::Tap;
  long frame = 0;      ///< >= 0
  int key = -1;        ///< GLFW key code (Down, Up, Tap); GLFW gamepad axis or button (PadAxis, PadButton)
  double x = 0, y = 0; ///< Look: [px]; Resize: width, height; PadAxis: value; PadButton: 0 or 1
  std::string path;    ///< Screenshot
  int line = 0;        ///< in the file, for messages
};

/// Reads a script. Throws PlanError naming the file, line and the bad word; events come
/// back sorted by frame (stable: a frame's events keep their order).
std::vector<ScriptEvent> read_script(const std::string& path);

/// The script's text for `frames` frames of random input from `seed`: keys held and let go,
/// switches flipped, mouse looks, mode and style toggles, resizes (no exports, no quit).
std::string random_script(uint32_t seed, long frames);

/// Replays a script frame by frame without a window: key, mouse and gamepad events go to
/// the controls (the scripted gamepad is kept here, as GLFW would report it); what only
/// the window can do is handed back, in file order.
class ScriptPlayer {
 public:
  explicit ScriptPlayer(std::vector<ScriptEvent> events);

  /// What a frame's events ask of the window.
  struct Requests {
    std::vector<std::pair<int, int>> resizes;  ///< [px] width, height
    std::vector<std::string> screenshots;      ///< paths
    int poses = 0;                             ///< "pose" lines to print
    bool quit = false;
  };
  /// Plays every event up to and including `frame` (events of a frame come before it is drawn).
  Requests play(long frame, Controls& controls);
  /// The scripted gamepad (present once a "pad" event was played; triggers rest at -1).
  const GamepadState& pad() const { return pad_; }
  /// True when the script holds any event at all.
  bool empty() const { return events_.empty(); }

 private:
  std::vector<ScriptEvent> events_;
  size_t next_ = 0;
  GamepadState pad_;
};

}  // namespace avenues::app
