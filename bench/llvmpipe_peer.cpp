// Avenues — Mesa's llvmpipe through OSMesa as the z-buffer peer (see llvmpipe_peer.h).
//
// libOSMesa exports the GL entry points itself (it carries its own dispatch), so the
// benchmark links it alone: linking GLVND's libGL as well would route gl* calls to a
// dispatcher that knows nothing of the OSMesa context.
#include "bench/llvmpipe_peer.h"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <stdexcept>

namespace avenues {

namespace {

struct Vertex {
  float x, y, z;
  uint8_t rgba[4];
};
static_assert(sizeof(Vertex) == 16);

const Material& material_of(const CellComplex& c, MaterialId id) {
  static const Material kDefault;
  return id >= 0 && size_t(id) < c.materials.size() ? c.materials[size_t(id)] : kDefault;
}

/// A flat grey for a triangle: the material's reflectance times its luminance over a
/// little ambient light, dimmed by orientation (floors and ceilings darker than walls,
/// walls facing x darker than those facing y), then sRGB-ish encoded.
uint8_t grey_of(const Material& m, Vec3 normal) {
  const double lum = 0.2126 * m.colour[0] + 0.7152 * m.colour[1] + 0.0722 * m.colour[2];
  const double n = length(normal);
  const Vec3 u = n > 0 ? (1 / n) * normal : Vec3{0, 0, 1};
  const double facing = std::fabs(u.z) > 0.7 ? 0.55 : (std::fabs(u.x) > std::fabs(u.y) ? 0.8 : 1.0);
  const double linear = std::clamp(0.1 + 0.9 * m.reflectance * lum * facing, 0.0, 1.0);
  return uint8_t(std::lround(255 * std::pow(linear, 1 / 2.2)));
}

void push_triangle(std::vector<Vertex>& out, Vec3 a, Vec3 b, Vec3 c, uint8_t grey) {
  for (Vec3 p : {a, b, c}) out.push_back({float(p.x), float(p.y), float(p.z), {grey, grey, grey, 255}});
}

}  // namespace

LlvmpipePeer::LlvmpipePeer(int width, int height) : width_(width), height_(height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("LlvmpipePeer: empty frame");
  // Before the first context: which Gallium driver OSMesa loads, and on how many threads
  // llvmpipe rasterises (as many as Avenues' half-tone is given in the benchmark).
  setenv("GALLIUM_DRIVER", "llvmpipe", 0);
  setenv("LP_NUM_THREADS", "2", 0);
  OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!ctx) throw std::runtime_error("OSMesaCreateContextExt failed");
  context_ = ctx;
  frame_.assign(size_t(width) * size_t(height) * 4, 0);
  if (!OSMesaMakeCurrent(ctx, frame_.data(), GL_UNSIGNED_BYTE, width, height)) {
    OSMesaDestroyContext(ctx);
    throw std::runtime_error("OSMesaMakeCurrent failed");
  }
  const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  renderer_ = r ? r : "?";
  glViewport(0, 0, width, height);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glDisable(GL_LIGHTING);
  glDisable(GL_DITHER);
  glDisable(GL_BLEND);
  glShadeModel(GL_FLAT);
  glClearColor(0, 0, 0, 1);
  glClearDepth(1);
  glGenBuffers(2, buffers_);
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
}

LlvmpipePeer::~LlvmpipePeer() {
  if (!context_) return;
  make_current();
  glDeleteBuffers(2, buffers_);
  OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void LlvmpipePeer::make_current() {
  auto* ctx = static_cast<OSMesaContext>(context_);
  if (OSMesaGetCurrentContext() != ctx) OSMesaMakeCurrent(ctx, frame_.data(), GL_UNSIGNED_BYTE, width_, height_);
}

void LlvmpipePeer::upload(const CellComplex& complex, const std::vector<PlacedObject>& objects) {
  make_current();
  std::vector<Vertex> vertices;
  std::vector<uint32_t> ids;  // per triangle: 1 + source index
  sources_.clear();
  index_of_.clear();
  bounds_ = Box3{};
  auto source = [&](const Source& s) {
    auto [it, fresh] = index_of_.try_emplace(s, int32_t(sources_.size()));
    if (fresh) sources_.push_back(s);
    return uint32_t(it->second) + 1;
  };
  for (size_t ci = 0; ci < complex.cells.size(); ++ci) {
    const Cell& cell = complex.cells[ci];
    for (size_t fi = 0; fi < cell.faces.size(); ++fi) {
      const Face& face = cell.faces[fi];
      for (const OpaquePoly& piece : face.opaque) {
        if (piece.poly.size() < 3) continue;
        const uint8_t grey = grey_of(material_of(complex, piece.material), face.plane.n);
        const uint32_t id = source({0, int(ci), int(fi)});
        for (size_t k = 1; k + 1 < piece.poly.size(); ++k) {
          push_triangle(vertices, piece.poly[0], piece.poly[k], piece.poly[k + 1], grey);
          ids.push_back(id);
        }
      }
    }
  }
  for (size_t oi = 0; oi < objects.size(); ++oi) {
    const PlacedObject& o = objects[oi];
    if (o.cell == kNoCell) continue;  // Avenues never draws it either
    const Mesh& m = o.mesh;
    for (size_t t = 0; t < m.triangles.size(); ++t) {
      const int polygon = t < m.polygon_of.size() ? m.polygon_of[t] : int(t);
      const Vec3 a = m.vertices[size_t(m.triangles[t][0])], b = m.vertices[size_t(m.triangles[t][1])],
                 c = m.vertices[size_t(m.triangles[t][2])];
      push_triangle(vertices, a, b, c, grey_of(o.paint.of_polygon(polygon), cross(b - a, c - a)));
      ids.push_back(source({1, int(oi), polygon}));
    }
  }
  for (const Vertex& v : vertices) bounds_.add({v.x, v.y, v.z});
  triangles_ = long(ids.size());

  std::vector<uint8_t> id_colours(vertices.size() * 4);
  for (size_t t = 0; t < ids.size(); ++t)
    for (size_t k = 0; k < 3; ++k) {
      uint8_t* c = &id_colours[(3 * t + k) * 4];
      c[0] = uint8_t(ids[t] & 0xff);
      c[1] = uint8_t((ids[t] >> 8) & 0xff);
      c[2] = uint8_t((ids[t] >> 16) & 0xff);
      c[3] = 255;
    }
  if (sources_.size() >= (1u << 24) - 1) throw std::runtime_error("LlvmpipePeer: too many sources for 24-bit ids");
  glBindBuffer(GL_ARRAY_BUFFER, buffers_[0]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(Vertex)), vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, buffers_[1]);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(id_colours.size()), id_colours.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

void LlvmpipePeer::set_view(const Camera& cam) {
  // Far: beyond the farthest corner of everything uploaded, along the view direction.
  double far = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3 p{(k & 1) ? bounds_.hi.x : bounds_.lo.x, (k & 2) ? bounds_.hi.y : bounds_.lo.y,
                 (k & 4) ? bounds_.hi.z : bounds_.lo.z};
    far = std::max(far, dot(p - cam.eye, cam.forward));
  }
  const double n = cam.near, f = std::max(far * 1.01 + 1, 2 * n);
  const double hw = cam.half_width(), hh = cam.half_height();
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  // The window on the picture plane Z = 1, scaled to the near plane. GL's window rows go
  // bottom to top, so top = shift_y + hh lands on Avenues' row 0 (see read_rgba).
  if (cam.is_parallel())  // a parallel projection: the same window, from the picture plane through the eye on
    glOrtho(cam.shift_x - hw, cam.shift_x + hw, cam.shift_y - hh, cam.shift_y + hh, 0, f);
  else
    glFrustum((cam.shift_x - hw) * n, (cam.shift_x + hw) * n, (cam.shift_y - hh) * n, (cam.shift_y + hh) * n, n, f);
  // Eye space: x = right, y = up, z = −forward (GL looks down −z).
  const Vec3 r = cam.right, u = cam.up, fw = cam.forward, e = cam.eye;
  const double m[16] = {r.x, u.x, -fw.x, 0, r.y, u.y, -fw.y, 0, r.z, u.z, -fw.z, 0,
                        -dot(r, e), -dot(u, e), dot(fw, e), 1};
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(m);
}

void LlvmpipePeer::draw_with(unsigned colour_buffer, int stride) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glBindBuffer(GL_ARRAY_BUFFER, buffers_[0]);
  glVertexPointer(3, GL_FLOAT, sizeof(Vertex), nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, colour_buffer);
  glColorPointer(4, GL_UNSIGNED_BYTE, stride,
                 colour_buffer == buffers_[0] ? reinterpret_cast<const void*>(offsetof(Vertex, rgba)) : nullptr);
  glDrawArrays(GL_TRIANGLES, 0, GLsizei(3 * triangles_));
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glFinish();
}

void LlvmpipePeer::draw(const Camera& camera) {
  make_current();
  set_view(camera);
  draw_with(buffers_[0], sizeof(Vertex));
}

void LlvmpipePeer::draw_ids(const Camera& camera) {
  make_current();
  set_view(camera);
  draw_with(buffers_[1], 4);
}

std::vector<uint8_t> LlvmpipePeer::read_rgba() {
  make_current();
  const size_t row = size_t(width_) * 4;
  std::vector<uint8_t> gl(row * size_t(height_)), out(gl.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, gl.data());
  for (int r = 0; r < height_; ++r)  // GL row r (from the bottom) is Avenues' row height − 1 − r
    std::copy_n(gl.begin() + std::ptrdiff_t(size_t(r) * row), row,
                out.begin() + std::ptrdiff_t(size_t(height_ - 1 - r) * row));
  return out;
}

std::vector<int32_t> LlvmpipePeer::read_ids() {
  const std::vector<uint8_t> rgba = read_rgba();
  std::vector<int32_t> out(size_t(width_) * size_t(height_));
  for (size_t i = 0; i < out.size(); ++i) {
    const uint32_t id = uint32_t(rgba[4 * i]) | uint32_t(rgba[4 * i + 1]) << 8 | uint32_t(rgba[4 * i + 2]) << 16;
    out[i] = int32_t(id) - 1;
  }
  return out;
}

int32_t LlvmpipePeer::source_index(const Source& s) const {
  auto it = index_of_.find(s);
  return it == index_of_.end() ? -1 : it->second;
}

}  // namespace avenues
