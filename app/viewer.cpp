// Avenues — the walkthrough window (see viewer.h).
#include "app/viewer.h"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

namespace avenues::app {

namespace {

std::string& glfw_error() {
  static std::string e;
  return e;
}

void on_error(int, const char* description) { glfw_error() = description ? description : "unknown GLFW error"; }

Viewer* viewer_of(GLFWwindow* w) { return static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }

}  // namespace

struct Viewer::FramebufferApi {
  PFNGLGENFRAMEBUFFERSPROC gen = nullptr;
  PFNGLDELETEFRAMEBUFFERSPROC del = nullptr;
  PFNGLBINDFRAMEBUFFERPROC bind = nullptr;
  PFNGLFRAMEBUFFERTEXTURE2DPROC attach = nullptr;
  PFNGLCHECKFRAMEBUFFERSTATUSPROC status = nullptr;
  PFNGLBLITFRAMEBUFFERPROC blit = nullptr;
  GLuint read_fbo = 0;
  GLuint attached = 0;  ///< the texture attached to read_fbo

  /// The entry points of the current context, or null when it has none.
  static std::unique_ptr<FramebufferApi> load() {
    const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    const bool core30 = version && std::atoi(version) >= 3;
    if (!core30 && !glfwExtensionSupported("GL_ARB_framebuffer_object")) return nullptr;
    auto api = std::make_unique<FramebufferApi>();
    api->gen = reinterpret_cast<PFNGLGENFRAMEBUFFERSPROC>(glfwGetProcAddress("glGenFramebuffers"));
    api->del = reinterpret_cast<PFNGLDELETEFRAMEBUFFERSPROC>(glfwGetProcAddress("glDeleteFramebuffers"));
    api->bind = reinterpret_cast<PFNGLBINDFRAMEBUFFERPROC>(glfwGetProcAddress("glBindFramebuffer"));
    api->attach = reinterpret_cast<PFNGLFRAMEBUFFERTEXTURE2DPROC>(glfwGetProcAddress("glFramebufferTexture2D"));
    api->status = reinterpret_cast<PFNGLCHECKFRAMEBUFFERSTATUSPROC>(glfwGetProcAddress("glCheckFramebufferStatus"));
    api->blit = reinterpret_cast<PFNGLBLITFRAMEBUFFERPROC>(glfwGetProcAddress("glBlitFramebuffer"));
    if (!api->gen || !api->del || !api->bind || !api->attach || !api->status || !api->blit) return nullptr;
    api->gen(1, &api->read_fbo);
    return api;
  }
};

Viewer::Viewer() = default;

std::unique_ptr<Viewer> Viewer::open(int width, int height, const std::string& title, bool vsync, std::string& why) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) {
    why = "no display (DISPLAY is not set)";
    return nullptr;
  }
  glfwSetErrorCallback(on_error);
  // An X server whose last client has just left (the window of the plan walked before, in
  // `avenues bench walk A B`) resets, and refuses connections meanwhile: try for a second.
  bool started = glfwInit();
  for (int tries = 0; !started && tries < 20; ++tries) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    started = glfwInit();
  }
  if (!started) {
    why = "cannot start GLFW: " + glfw_error();
    return nullptr;
  }
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  glfwWindowHint(GLFW_DOUBLEBUFFER, GLFW_TRUE);
  GLFWwindow* w = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!w) {
    why = "cannot open a window: " + glfw_error();
    glfwTerminate();
    return nullptr;
  }
  std::unique_ptr<Viewer> v(new Viewer);
  v->window_ = w;
  glfwSetWindowUserPointer(w, v.get());
  glfwMakeContextCurrent(w);
  glfwSwapInterval(vsync ? 1 : 0);
  glfwSetKeyCallback(w, on_key);
  glfwSetWindowFocusCallback(w, on_focus);
  glfwSetCursorPosCallback(w, on_cursor);
  v->fbo_ = FramebufferApi::load();
  return v;
}

void Viewer::on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action == GLFW_REPEAT || key == GLFW_KEY_UNKNOWN) return;
  viewer_of(w)->pending_.keys.push_back({key, action == GLFW_PRESS});
}

void Viewer::on_focus(GLFWwindow* w, int focused) {
  if (!focused) viewer_of(w)->pending_.focus_lost = true;
}

void Viewer::on_cursor(GLFWwindow* w, double x, double y) {
  Viewer& v = *viewer_of(w);
  // Look while the cursor is captured or a mouse button is held.
  bool looking = v.captured_;
  for (int b = GLFW_MOUSE_BUTTON_1; b <= GLFW_MOUSE_BUTTON_LAST && !looking; ++b)
    looking = glfwGetMouseButton(w, b) == GLFW_PRESS;
  if (looking && v.have_last_) {
    v.pending_.look_dx += x - v.last_x_;
    v.pending_.look_dy += y - v.last_y_;
  }
  v.last_x_ = x, v.last_y_ = y;
  v.have_last_ = true;
}

Viewer::~Viewer() {
  if (!window_) return;
  glfwMakeContextCurrent(window_);
  if (fbo_) fbo_->del(1, &fbo_->read_fbo);
  if (frame_tex_.id) glDeleteTextures(1, &frame_tex_.id);
  for (Texture& t : panel_tex_)
    if (t.id) glDeleteTextures(1, &t.id);
  glfwDestroyWindow(window_);
  glfwTerminate();
}

WindowInput Viewer::poll(double wait_s) {
  if (wait_s > 0) glfwWaitEventsTimeout(wait_s);
  else glfwPollEvents();
  WindowInput in = std::move(pending_);
  pending_ = WindowInput{};
  // The first gamepad GLFW knows (its mapping database names the buttons).
  for (int jid = GLFW_JOYSTICK_1; jid <= GLFW_JOYSTICK_LAST; ++jid) {
    GLFWgamepadstate s;
    if (!glfwJoystickIsGamepad(jid) || !glfwGetGamepadState(jid, &s)) continue;
    in.gamepad.present = true;
    for (size_t a = 0; a < in.gamepad.axes.size(); ++a) in.gamepad.axes[a] = s.axes[a];
    for (size_t b = 0; b < in.gamepad.buttons.size(); ++b) in.gamepad.buttons[b] = s.buttons[b];
    break;
  }
  return in;
}

bool Viewer::should_close() const { return glfwWindowShouldClose(window_); }
void Viewer::close() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

void Viewer::framebuffer_size(int& w, int& h) const { glfwGetFramebufferSize(window_, &w, &h); }

void Viewer::resize(int w, int h) { glfwSetWindowSize(window_, w, h); }

void Viewer::capture_mouse(bool on) {
  captured_ = on;
  glfwSetInputMode(window_, GLFW_CURSOR, on ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
  have_last_ = false;
}

void Viewer::upload(Texture& t, int w, int h, unsigned format, const uint8_t* pixels) {
  if (!t.id) glGenTextures(1, &t.id);
  glBindTexture(GL_TEXTURE_2D, t.id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (t.width != w || t.height != h) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexImage2D(GL_TEXTURE_2D, 0, format == GL_BGRA ? GL_RGBA8 : GL_RGB8, w, h, 0, format, GL_UNSIGNED_BYTE, pixels);
    t.width = w, t.height = h;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, format, GL_UNSIGNED_BYTE, pixels);
  }
}

void Viewer::quad(const Texture& t, int x, int y, int scale) {
  // Texel (i, j) on pixel (x + i, y + j): corners on pixel edges, so every pixel centre
  // samples its texel's centre.
  glBindTexture(GL_TEXTURE_2D, t.id);
  glBegin(GL_QUADS);
  glTexCoord2f(0, 0), glVertex2i(x, y);
  glTexCoord2f(1, 0), glVertex2i(x + scale * t.width, y);
  glTexCoord2f(1, 1), glVertex2i(x + scale * t.width, y + scale * t.height);
  glTexCoord2f(0, 1), glVertex2i(x, y + scale * t.height);
  glEnd();
}

void Viewer::draw(const Image& frame, bool frame_changed, const std::vector<const OverlayPanel*>& panels, int scale) {
  scale = std::max(1, scale);
  glfwMakeContextCurrent(window_);
  int fw = 0, fh = 0;
  framebuffer_size(fw, fh);
  glViewport(0, 0, fw, fh);
  if (scale * frame.width < fw || scale * frame.height < fh) {  // black where the picture does not reach
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, fw, fh, 0, -1, 1);  // rows from the top, like the picture
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glDisable(GL_BLEND);
  if (frame.width > 0 && frame.height > 0) {
    if (frame_changed || frame_tex_.width != frame.width || frame_tex_.height != frame.height) {
      // As BGRA, the layout drivers take without converting. For the blit, rows from the
      // bottom as OpenGL counts them, so that the copy needs no flip.
      const size_t n = size_t(frame.width) * size_t(frame.height), w = size_t(frame.width);
      bgra_.resize(n * 4);
      for (int y = 0; y < frame.height; ++y) {
        const uint8_t* src = frame.row(y);
        uint8_t* dst = bgra_.data() + size_t(fbo_ ? frame.height - 1 - y : y) * w * 4;
        if (frame.channels == 1)
          for (size_t i = 0; i < w; ++i) dst[4 * i] = dst[4 * i + 1] = dst[4 * i + 2] = src[i], dst[4 * i + 3] = 255;
        else
          for (size_t i = 0; i < w; ++i)
            dst[4 * i] = src[3 * i + 2], dst[4 * i + 1] = src[3 * i + 1], dst[4 * i + 2] = src[3 * i], dst[4 * i + 3] = 255;
      }
      upload(frame_tex_, frame.width, frame.height, GL_BGRA, bgra_.data());
    }
    if (fbo_) {
      // Texel (i, j) to pixel (i, fh - frame.height + j), or to a scale × scale block there:
      // the picture's top row at the top.
      fbo_->bind(GL_READ_FRAMEBUFFER, fbo_->read_fbo);
      if (fbo_->attached != frame_tex_.id) {
        fbo_->attach(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, frame_tex_.id, 0);
        fbo_->attached = frame_tex_.id;
      }
      fbo_->bind(GL_DRAW_FRAMEBUFFER, 0);
      fbo_->blit(0, 0, frame.width, frame.height, 0, fh - scale * frame.height, scale * frame.width, fh,
                 GL_COLOR_BUFFER_BIT, GL_NEAREST);
      fbo_->bind(GL_READ_FRAMEBUFFER, 0);
    } else {
      quad(frame_tex_, 0, 0, scale);
    }
  }
  if (panel_tex_.size() < panels.size()) panel_tex_.resize(panels.size());
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);  // premultiplied alpha
  for (size_t i = 0; i < panels.size(); ++i) {
    const OverlayPanel& p = *panels[i];
    if (p.width <= 0 || p.height <= 0) continue;
    Texture& t = panel_tex_[i];
    if (t.version != p.version || t.width != p.width || t.height != p.height) {
      upload(t, p.width, p.height, GL_BGRA, p.bgra.data());
      t.version = p.version;
    }
    quad(t, p.x, p.y);
  }
  glDisable(GL_BLEND);
  glDisable(GL_TEXTURE_2D);
}

Image Viewer::read_back() const {
  int fw = 0, fh = 0;
  framebuffer_size(fw, fh);
  Image out;
  out.resize(fw, fh, 3);
  std::vector<uint8_t> rows(size_t(fw) * size_t(fh) * 3);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, fw, fh, GL_RGB, GL_UNSIGNED_BYTE, rows.data());
  // OpenGL's rows run from the bottom.
  for (int y = 0; y < fh; ++y) std::memcpy(out.row(y), rows.data() + size_t(fh - 1 - y) * size_t(fw) * 3, size_t(fw) * 3);
  return out;
}

void Viewer::swap() { glfwSwapBuffers(window_); }

}  // namespace avenues::app
