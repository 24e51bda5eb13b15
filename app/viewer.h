// Avenues — the walkthrough window: a GLFW window that shows pictures Avenues rendered.
//
// The picture is made by Avenues itself (the half-tone renderer, or the hidden-line drawing
// rasterised); the window only shows it: the picture is uploaded as a texture and drawn
// pixel for pixel (nearest texel, one texel per pixel) in the window's top-left corner, so
// what the window shows is the picture exactly. Where the driver has framebuffer objects
// (OpenGL 3.0, or ARB_framebuffer_object) the texture is copied with glBlitFramebuffer —
// for a software driver such as Mesa's llvmpipe under Xvfb a plain copy, not a textured
// quad run through its shader JIT; otherwise it is drawn as a textured quad with OpenGL
// 1.1's fixed-function pipeline. Overlay panels (the status line, the help) are
// premultiplied BGRA pictures blended on top, uploaded only when they change.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "app/controls.h"
#include "render/raster.h"

struct GLFWwindow;

namespace avenues::app {

/// A picture to blend over the frame.
struct OverlayPanel {
  int x = 0, y = 0;           ///< [px] its top-left corner in the window
  int width = 0, height = 0;  ///< [px] 0: nothing to show
  std::vector<uint8_t> bgra;  ///< premultiplied BGRA, rows from the top, width·4 bytes each
  uint64_t version = 0;       ///< a new value whenever the pixels change
  std::string source;         ///< what the pixels were made from (text), to redraw only on a change
};

/// Events the window received since the last poll.
struct WindowInput {
  std::vector<std::pair<int, bool>> keys;  ///< (GLFW key code, down) in order
  double look_dx = 0, look_dy = 0;         ///< [px] mouse moves while looking
  bool focus_lost = false;
  GamepadState gamepad;
};

class Viewer {
 public:
  /// Opens a window of width × height pixels. Returns null, with the reason in `why`,
  /// when there is no display or no window can be made.
  static std::unique_ptr<Viewer> open(int width, int height, const std::string& title, bool vsync, std::string& why);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  /// Processes window events (waiting at most `wait_s` seconds for one when > 0).
  WindowInput poll(double wait_s = 0);
  bool should_close() const;
  void close();
  /// The framebuffer's size [px] (the size to render at).
  void framebuffer_size(int& w, int& h) const;
  /// Asks for a new window size [px]; the framebuffer follows at a later poll.
  void resize(int w, int h);
  /// Captures the cursor (mouse look without a button) or frees it.
  void capture_mouse(bool on);
  bool mouse_captured() const { return captured_; }

  /// Draws the frame (pixel for pixel at the top-left, or each of its pixels as a `scale` ×
  /// `scale` block; black where it does not reach) and the panels.
  void draw(const Image& frame, bool frame_changed, const std::vector<const OverlayPanel*>& panels, int scale = 1);
  /// What was just drawn, read back from the framebuffer (before swap): RGB, rows from the top.
  Image read_back() const;
  void swap();

 private:
  Viewer();
  struct Texture {
    unsigned id = 0;
    int width = 0, height = 0;
    uint64_t version = ~uint64_t(0);
  };
  void upload(Texture& t, int w, int h, unsigned format, const uint8_t* pixels);
  static void quad(const Texture& t, int x, int y, int scale = 1);
  // GLFW's callbacks (the window's user pointer is the viewer).
  static void on_key(GLFWwindow* w, int key, int scancode, int action, int mods);
  static void on_focus(GLFWwindow* w, int focused);
  static void on_cursor(GLFWwindow* w, double x, double y);

  /// OpenGL 3.0's framebuffer objects, when the driver has them (looked up at open()).
  struct FramebufferApi;
  std::unique_ptr<FramebufferApi> fbo_;

  GLFWwindow* window_ = nullptr;
  Texture frame_tex_;
  std::vector<uint8_t> bgra_;  ///< the frame as BGRA, the layout the driver takes without conversion
  std::vector<Texture> panel_tex_;
  bool captured_ = false;
  double last_x_ = 0, last_y_ = 0;
  bool have_last_ = false;
  WindowInput pending_;
};

}  // namespace avenues::app
