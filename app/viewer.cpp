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
  if (texture_) glDeleteTextures(1, &texture_);
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

namespace {

/// A BGRA pixel as the 32-bit word OpenGL's GL_UNSIGNED_INT_8_8_8_8_REV reads: alpha in the
/// top byte, blue in the bottom one, whatever the machine's byte order.
constexpr uint32_t bgra(uint32_t r, uint32_t g, uint32_t b) { return 0xff000000u | r << 16 | g << 8 | b; }

/// RGB pixels to BGRA words, one at a time.
void bgra_of_rgb(const uint8_t* src, int width, uint32_t* dst) {
  for (int i = 0; i < width; ++i, src += 3) dst[i] = bgra(src[0], src[1], src[2]);
}

#if defined(__GNUC__) && defined(__x86_64__)
/// The same, 16 pixels at a time: each 12 bytes read as 16 and shuffled into 4 words by
/// SSSE3's byte shuffle (on every x86-64 machine of the last 15 years; `bgra_of_rgb` on
/// the others). Reads at most 4 bytes past pixel width − 1's last byte only while they lie
/// within the row, so the last pixels go one at a time.
__attribute__((target("ssse3"))) void bgra_of_rgb_ssse3(const uint8_t* src, int width, uint32_t* dst) {
  typedef uint8_t Bytes __attribute__((vector_size(16)));
  const Bytes order = {2, 1, 0, 0, 5, 4, 3, 0, 8, 7, 6, 0, 11, 10, 9, 0};
  const Bytes alpha = {0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0, 255};
  int i = 0;
  for (; i + 18 <= width; i += 16)
    for (int k = 0; k < 4; ++k) {
      Bytes v;
      std::memcpy(&v, src + 3 * (i + 4 * k), sizeof v);
      v = __builtin_shuffle(v, order) | alpha;
      std::memcpy(dst + i + 4 * k, &v, sizeof v);
    }
  bgra_of_rgb(src + 3 * i, width - i, dst + i);
}
#endif

/// Row `src` of an RGB or grey picture, each pixel `scale` times, into `dst`.
void widen_row(const uint8_t* src, int width, int channels, int scale, uint32_t* dst) {
  if (channels == 1) {
    for (int i = 0; i < width; ++i, dst += scale) std::fill_n(dst, scale, bgra(src[i], src[i], src[i]));
  } else if (scale == 1) {
#if defined(__GNUC__) && defined(__x86_64__)
    static const bool ssse3 = __builtin_cpu_supports("ssse3");
    if (ssse3) return bgra_of_rgb_ssse3(src, width, dst);
#endif
    bgra_of_rgb(src, width, dst);
  } else {
    for (int i = 0; i < width; ++i, src += 3, dst += scale) std::fill_n(dst, scale, bgra(src[0], src[1], src[2]));
  }
}

/// Premultiplied `over` on `under`, one channel: over + under · (1 − alpha), rounded.
inline uint32_t blend(uint32_t over, uint32_t under, uint32_t alpha) {
  return std::min<uint32_t>(255, over + (under * (255 - alpha) + 127) / 255);
}

}  // namespace

void Viewer::compose(const Image& frame, const std::vector<const OverlayPanel*>& panels, int scale, int fw, int fh) {
  picture_.resize(size_t(fw) * size_t(fh));
  const uint32_t black = bgra(0, 0, 0);
  const int shown_w = std::min(fw, scale * frame.width);  // [px] the window's pixels the frame covers across
  const int from_frame = shown_w / scale;                   // frame pixels shown whole
  for (int y = 0; y < fh; ++y) {
    uint32_t* dst = picture_.data() + size_t(y) * size_t(fw);
    const int src_y = y / scale;
    if (src_y >= frame.height || shown_w <= 0) {
      std::fill_n(dst, fw, black);
    } else if (y % scale != 0) {
      std::memcpy(dst, dst - fw, size_t(fw) * sizeof(uint32_t));  // the block's row above
    } else {
      const uint8_t* src = frame.row(src_y);
      widen_row(src, from_frame, frame.channels, scale, dst);
      if (from_frame * scale < shown_w)  // the last frame pixel, cut by the window's edge
        widen_row(src + size_t(from_frame) * size_t(frame.channels), 1, frame.channels, shown_w - from_frame * scale,
                  dst + from_frame * scale);
      std::fill(dst + shown_w, dst + fw, black);
    }
  }
  for (const OverlayPanel* p : panels) {
    const int x0 = std::max(0, p->x), x1 = std::min(fw, p->x + p->width);
    const int y0 = std::max(0, p->y), y1 = std::min(fh, p->y + p->height);
    if (p->bgra.size() < size_t(p->width) * size_t(p->height) * 4) continue;
    for (int y = y0; y < y1; ++y) {
      const uint8_t* src = p->bgra.data() + (size_t(y - p->y) * size_t(p->width) + size_t(x0 - p->x)) * 4;
      uint32_t* dst = picture_.data() + size_t(y) * size_t(fw);
      for (int x = x0; x < x1; ++x, src += 4) {
        const uint32_t a = src[3];
        if (a == 0 && (src[0] | src[1] | src[2]) == 0) continue;
        const uint32_t under = dst[x];
        dst[x] = 0xff000000u | blend(src[2], under >> 16 & 0xff, a) << 16 | blend(src[1], under >> 8 & 0xff, a) << 8 |
                 blend(src[0], under & 0xff, a);
      }
    }
  }
}

void Viewer::upload(int w, int h) {
  if (!texture_) glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  if (texture_w_ != w || texture_h_ != h) {
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    // GL_RGBA without a size lets the driver keep the texels in the layout they are given
    // (Mesa then stores BGRA, and the upload and the blit to a BGRA window are copies);
    // GL_RGBA8 would have it convert them to RGBA on every upload.
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, w, h, 0, GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, picture_.data());
    texture_w_ = w, texture_h_ = h;
    if (fbo_) fbo_->attached = 0;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, picture_.data());
  }
}

void Viewer::present(int fw, int fh) {
  if (fbo_) {
    fbo_->bind(GL_READ_FRAMEBUFFER, fbo_->read_fbo);
    if (fbo_->attached != texture_) {
      fbo_->attach(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
      fbo_->attached = texture_;
    }
    fbo_->bind(GL_DRAW_FRAMEBUFFER, 0);
    // Texture row 0 (the picture's top) to the window's top row, OpenGL's row fh − 1: in
    // memory, where both count rows from the top, a copy.
    fbo_->blit(0, 0, fw, fh, 0, fh, fw, 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    fbo_->bind(GL_READ_FRAMEBUFFER, 0);
    return;
  }
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, fw, fh, 0, -1, 1);  // rows from the top, like the picture
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glDisable(GL_BLEND);
  // Texel (i, j) on pixel (i, j): corners on pixel edges, so every pixel centre samples its
  // texel's centre.
  glBegin(GL_QUADS);
  glTexCoord2f(0, 0), glVertex2i(0, 0);
  glTexCoord2f(1, 0), glVertex2i(fw, 0);
  glTexCoord2f(1, 1), glVertex2i(fw, fh);
  glTexCoord2f(0, 1), glVertex2i(0, fh);
  glEnd();
  glDisable(GL_TEXTURE_2D);
}

void Viewer::draw(const Image& frame, bool frame_changed, const std::vector<const OverlayPanel*>& panels, int scale) {
  scale = std::max(1, scale);
  glfwMakeContextCurrent(window_);
  int fw = 0, fh = 0;
  framebuffer_size(fw, fh);
  if (fw <= 0 || fh <= 0) return;  // minimised
  glViewport(0, 0, fw, fh);
  Shown now{fw, fh, scale, frame.width, frame.height, {}};
  for (const OverlayPanel* p : panels)
    if (p->width > 0 && p->height > 0) now.panels.push_back({p, p->version, p->x, p->y, p->width, p->height});
  if (frame_changed || !(now == shown_) || !texture_) {
    compose(frame, panels, scale, fw, fh);  // a panel of no size adds nothing
    upload(fw, fh);
    shown_ = std::move(now);
  }
  present(fw, fh);
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
