// Avenues — the walkthrough window: a GLFW window that shows pictures Avenues rendered.
//
// The picture is made by Avenues itself (the half-tone renderer, or the hidden-line drawing
// rasterised); the window only shows it. What the window shows is put together on the CPU
// as one picture the window's size: the frame pixel for pixel in the top-left corner (or
// each of its pixels as a block), black where it does not reach, the overlay panels (the
// status line, the help: premultiplied BGRA) blended on top. It is made again only when
// one of these changed, uploaded as BGRA (the layout drivers keep as it is given), and
// copied to the window one texel per pixel. Where the driver has framebuffer objects
// (OpenGL 3.0, or ARB_framebuffer_object) the copy is glBlitFramebuffer, asked to turn the
// texture's rows (the picture's top first) over: OpenGL counts rows from the bottom, a
// window's memory from the top, so a driver such as Mesa's llvmpipe under Xvfb then copies
// memory (0.4 ms at 1280 × 720) where any other blit, a scaled one or one it must turn
// over itself, runs a textured quad through its shader JIT (1.8–2.4 ms, on the cores the
// renderer uses). Without framebuffer objects the picture is drawn as a textured quad with
// OpenGL 1.1's fixed-function pipeline.
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
  /// What the window's picture was last made of: it is made again when any of it changes.
  struct Shown {
    int window_w = 0, window_h = 0, scale = 0, frame_w = 0, frame_h = 0;
    struct Panel {
      const OverlayPanel* panel = nullptr;
      uint64_t version = 0;
      int x = 0, y = 0, width = 0, height = 0;
      bool operator==(const Panel&) const = default;
    };
    std::vector<Panel> panels;
    bool operator==(const Shown&) const = default;
  };
  /// Puts the window's picture together in `picture_` (see the top of this file).
  void compose(const Image& frame, const std::vector<const OverlayPanel*>& panels, int scale, int fw, int fh);
  void upload(int w, int h);
  void present(int fw, int fh);
  // GLFW's callbacks (the window's user pointer is the viewer).
  static void on_key(GLFWwindow* w, int key, int scancode, int action, int mods);
  static void on_focus(GLFWwindow* w, int focused);
  static void on_cursor(GLFWwindow* w, double x, double y);

  /// OpenGL 3.0's framebuffer objects, when the driver has them (looked up at open()).
  struct FramebufferApi;
  std::unique_ptr<FramebufferApi> fbo_;

  GLFWwindow* window_ = nullptr;
  unsigned texture_ = 0;
  int texture_w_ = 0, texture_h_ = 0;
  std::vector<uint32_t> picture_;  ///< the window's picture: BGRA pixels as 32-bit words, rows from the top
  Shown shown_;
  bool captured_ = false;
  double last_x_ = 0, last_y_ = 0;
  bool have_last_ = false;
  WindowInput pending_;
};

}  // namespace avenues::app
