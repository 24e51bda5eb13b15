// Avenues — the peer a renderer without cells would be: Mesa's llvmpipe (through OSMesa)
// drawing every opaque triangle of the whole building with a z-buffer, no culling.
//
//   LlvmpipePeer peer(1920, 1080);          // an OSMesa context (RGBA, 24-bit depth)
//   peer.upload(complex, objects);          // once: every face's opaque pieces as fans, the objects
//   peer.draw(camera);                      // one frame: clear, draw all, glFinish
//
// The projection is the camera's own: an off-axis glFrustum from its window on the picture
// plane (shift_x ± half_width, shift_y ± half_height, times the near distance) and the
// camera's basis as the modelview, so that GL's pixel (i, r) (rows from the bottom) is
// Avenues' pixel (i, height − 1 − r). A parallel camera gets glOrtho over the same window,
// from its picture plane on (a plan's or section's cut plane passes through its eye). Each triangle is one flat grey from its material
// (reflectance × luminance, dimmed by a fixed per-orientation factor so that floors, walls
// and ceilings differ). For checking, draw_ids() paints each triangle with the index of
// what it came from (a cell's face, or an object's input polygon), as Avenues' item
// buffer names its polygons by PolygonSource.
//
// The GL context is owned by the peer and made current on the calling thread by draw().
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "cells/cell_complex.h"
#include "render/scene_objects.h"
#include "visibility/camera.h"

namespace avenues {

class LlvmpipePeer {
 public:
  /// Where a triangle came from: (0, cell, face) for a face's opaque piece, (1, object,
  /// input polygon) for an object's triangle.
  using Source = std::tuple<int, int, int>;

  /// An OSMesa context of this size. Sets GALLIUM_DRIVER=llvmpipe and LP_NUM_THREADS=2
  /// unless the environment says otherwise. Throws std::runtime_error if OSMesa fails.
  LlvmpipePeer(int width, int height);
  ~LlvmpipePeer();
  LlvmpipePeer(const LlvmpipePeer&) = delete;
  LlvmpipePeer& operator=(const LlvmpipePeer&) = delete;

  /// glGetString(GL_RENDERER), e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& renderer() const { return renderer_; }
  int width() const { return width_; }
  int height() const { return height_; }

  /// Every opaque triangle of the complex (all cells, far box included) and of the placed
  /// objects that lie in a cell, into vertex buffers on the GL side (replacing any earlier).
  void upload(const CellComplex& complex, const std::vector<PlacedObject>& objects);
  long triangles() const { return triangles_; }

  /// One frame: clear colour and depth, draw every triangle (depth test on, culling off),
  /// glFinish.
  void draw(const Camera& camera);
  /// The same frame with each triangle painted with 1 + its source's index (0: nothing).
  void draw_ids(const Camera& camera);

  /// The colour buffer read back with glReadPixels: RGBA, rows from the top (Avenues' order).
  std::vector<uint8_t> read_rgba();
  /// After draw_ids: per pixel, rows from the top, the source index drawn there (-1: none).
  std::vector<int32_t> read_ids();
  /// Source index of a source, -1 if no triangle came from it.
  int32_t source_index(const Source& s) const;
  /// Every source, by index.
  const std::vector<Source>& sources() const { return sources_; }

 private:
  void make_current();
  void set_view(const Camera& camera);
  void draw_with(unsigned colour_buffer, int stride);

  int width_ = 0, height_ = 0;
  void* context_ = nullptr;  ///< OSMesaContext
  std::vector<uint8_t> frame_;
  std::string renderer_;
  unsigned buffers_[2] = {0, 0};  ///< interleaved position + grey; id colours
  long triangles_ = 0;
  Box3 bounds_;  ///< of every uploaded vertex: the far plane lies beyond it
  std::vector<Source> sources_;
  std::map<Source, int32_t> index_of_;
};

}  // namespace avenues
