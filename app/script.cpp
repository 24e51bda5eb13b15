// Avenues — a key-event script (see script.h).
#include "app/script.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <GLFW/glfw3.h>

#include "app/controls.h"
#include "plans/plan.h"

namespace avenues::app {

std::vector<ScriptEvent> read_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read the script " + path);
  std::vector<ScriptEvent> events;
  std::string text;
  for (int n = 1; std::getline(in, text); ++n) {
    text = text.substr(0, text.find('#'));
    std::istringstream words(text);
    if (!(words >> std::ws).good()) continue;
    ScriptEvent e;
    e.line = n;
    std::string what;
    auto fail = [&](const std::string& element, const std::string& message) {
      throw PlanError({path, n, 0, element}, message);
    };
    if (!(words >> e.frame) || e.frame < 0) fail("frame", "a script line starts with a frame number (0 or more)");
    if (!(words >> what))
      fail("event", "the frame number wants an event: down, up, tap, look, resize, screenshot, pose, pad or quit");
    if (what == "down" || what == "up" || what == "tap") {
      e.what = what == "down" ? ScriptEvent::What::Down : what == "up" ? ScriptEvent::What::Up : ScriptEvent::What::Tap;
      std::string key;
      if (!(words >> key)) fail(what, "'" + what + "' wants a key name");
      e.key = key_code(key);
      if (e.key < 0) fail(key, "unknown key '" + key + "' (keys: " + key_names() + ")");
    } else if (what == "look") {
      e.what = ScriptEvent::What::Look;
      if (!(words >> e.x >> e.y) || !std::isfinite(e.x) || !std::isfinite(e.y))
        fail("look", "'look' wants the mouse's move in pixels: DX DY");
    } else if (what == "resize") {
      e.what = ScriptEvent::What::Resize;
      if (!(words >> e.x >> e.y) || !(e.x >= 1 && e.x <= 16384 && e.y >= 1 && e.y <= 16384) || e.x != std::floor(e.x) ||
          e.y != std::floor(e.y))
        fail("resize", "'resize' wants the window's new size in pixels: WIDTH HEIGHT");
    } else if (what == "screenshot") {
      e.what = ScriptEvent::What::Screenshot;
      if (!(words >> e.path)) fail("screenshot", "'screenshot' wants a file name (.png)");
    } else if (what == "pad") {
      std::string name;
      if (!(words >> name)) fail("pad", "'pad' wants an axis or a button and its value: LEFT_Y -1, A 1");
      e.key = gamepad_axis_code(name);
      e.what = ScriptEvent::What::PadAxis;
      if (e.key < 0) {
        e.key = gamepad_button_code(name);
        e.what = ScriptEvent::What::PadButton;
      }
      if (e.key < 0) fail(name, "unknown gamepad axis or button '" + name + "' (" + gamepad_names() + ")");
      if (!(words >> e.x) || !(e.x >= -1 && e.x <= 1) ||
          (e.what == ScriptEvent::What::PadButton && e.x != 0 && e.x != 1))
        fail(name, e.what == ScriptEvent::What::PadAxis ? "an axis wants a value from -1 to 1"
                                                         : "a button wants 1 (down) or 0 (up)");
    } else if (what == "pose") {
      e.what = ScriptEvent::What::Pose;
    } else if (what == "quit") {
      e.what = ScriptEvent::What::Quit;
    } else {
      fail(what, "unknown event '" + what + "' (down, up, tap, look, resize, screenshot, pose, pad, quit)");
    }
    if (!(words >> std::ws).eof()) fail(what, "too many words for '" + what + "'");
    events.push_back(e);
  }
  std::stable_sort(events.begin(), events.end(), [](const ScriptEvent& a, const ScriptEvent& b) { return a.frame < b.frame; });
  return events;
}

std::string random_script(uint32_t seed, long frames) {
  std::mt19937 rng(seed);
  const char* held[] = {"W", "S", "A", "D", "LEFT", "RIGHT", "R", "V", "PAGE_UP", "PAGE_DOWN", "EQUAL", "MINUS", "LEFT_SHIFT"};
  const char* taps[] = {"1", "2", "3", "4", "5", "6", "7", "8", "0", "F", "L", "B", "P", "HOME", "TAB", "H"};
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<size_t> pick_held(0, std::size(held) - 1), pick_tap(0, std::size(taps) - 1);
  std::vector<bool> is_down(std::size(held), false);
  std::ostringstream out;
  out << "# random input, seed " << seed << ", " << frames << " frames\n";
  for (long f = 0; f < frames; ++f) {
    if (u(rng) < 0.15) {
      const size_t k = pick_held(rng);
      out << f << (is_down[k] ? " up " : " down ") << held[k] << "\n";
      is_down[k] = !is_down[k];
    }
    if (u(rng) < 0.03) out << f << " tap " << taps[pick_tap(rng)] << "\n";
    if (u(rng) < 0.05) out << f << " look " << std::lround(400 * (u(rng) - 0.5)) << " " << std::lround(200 * (u(rng) - 0.5)) << "\n";
    if (u(rng) < 0.004) out << f << " resize " << 160 + std::lround(1000 * u(rng)) << " " << 120 + std::lround(560 * u(rng)) << "\n";
  }
  return out.str();
}

ScriptPlayer::ScriptPlayer(std::vector<ScriptEvent> events) : events_(std::move(events)) {
  // Triggers rest at -1, as GLFW reports them.
  pad_.axes[GLFW_GAMEPAD_AXIS_LEFT_TRIGGER] = pad_.axes[GLFW_GAMEPAD_AXIS_RIGHT_TRIGGER] = -1;
}

ScriptPlayer::Requests ScriptPlayer::play(long frame, Controls& controls) {
  Requests r;
  for (; next_ < events_.size() && events_[next_].frame <= frame; ++next_) {
    const ScriptEvent& e = events_[next_];
    switch (e.what) {
      case ScriptEvent::What::Down: controls.key(e.key, true); break;
      case ScriptEvent::What::Up: controls.key(e.key, false); break;
      case ScriptEvent::What::Tap: controls.key(e.key, true), controls.key(e.key, false); break;
      case ScriptEvent::What::Look: controls.look(e.x, e.y); break;
      case ScriptEvent::What::Resize: r.resizes.emplace_back(int(e.x), int(e.y)); break;
      case ScriptEvent::What::Screenshot: r.screenshots.push_back(e.path); break;
      case ScriptEvent::What::Pose: ++r.poses; break;
      case ScriptEvent::What::Quit: r.quit = true; break;
      case ScriptEvent::What::PadAxis:
        pad_.present = true;
        pad_.axes[size_t(e.key)] = float(e.x);
        break;
      case ScriptEvent::What::PadButton:
        pad_.present = true;
        pad_.buttons[size_t(e.key)] = uint8_t(e.x);
        break;
    }
  }
  return r;
}

}  // namespace avenues::app
