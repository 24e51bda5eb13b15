// Avenues — the other peer a renderer without cells would be: Embree (Intel's ray tracing
// kernels) casting one primary ray per pixel into a BVH of every opaque triangle of the
// whole building, and shading the hit flat grey.
//
//   EmbreePeer peer(1920, 1080, 2);         // a device, 2 threads (TBB) for the rows
//   peer.upload(complex, objects);          // once: every face's opaque pieces as fans, the objects; builds the BVH
//   peer.draw(camera);                      // one frame: a ray through every pixel centre
//   peer.read_ids();                        // what each pixel's ray hit, as a source index (-1: nothing)
//
// Rays go through Avenues' own pixel centres (Camera::ray_through_raster at i + ½, j + ½), so
// each pixel's hit can be compared with Avenues' item buffer; sources are numbered the way
// LlvmpipePeer numbers them ((0, cell, face) or (1, object, polygon)), in upload order.
#pragma once

#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

#include "cells/cell_complex.h"
#include "render/scene_objects.h"
#include "visibility/camera.h"

namespace avenues {

class EmbreePeer {
 public:
  using Source = std::tuple<int, int, int>;

  EmbreePeer(int width, int height, int threads);
  ~EmbreePeer();
  EmbreePeer(const EmbreePeer&) = delete;
  EmbreePeer& operator=(const EmbreePeer&) = delete;

  /// Every opaque triangle (all cells, far box included) and the objects lying in a cell;
  /// commits the scene (builds the BVH). Throws std::runtime_error if Embree fails.
  void upload(const CellComplex& complex, const std::vector<PlacedObject>& objects);
  long triangles() const { return long(source_of_triangle_.size()); }

  /// One frame: a ray per pixel, the hit's grey into the frame (8-bit, rows from the top).
  void draw(const Camera& camera);
  const std::vector<uint8_t>& frame() const { return grey_; }
  /// The last frame's hits as source indices (-1 where the ray met nothing).
  const std::vector<int32_t>& read_ids() const { return ids_; }
  const std::vector<Source>& sources() const { return sources_; }
  int32_t source_index(const Source& s) const;

 private:
  int width_, height_, threads_;
  void* device_ = nullptr;  ///< RTCDevice
  void* scene_ = nullptr;   ///< RTCScene
  std::vector<Source> sources_;
  std::map<Source, int32_t> index_of_;
  std::vector<int32_t> source_of_triangle_;
  std::vector<uint8_t> grey_of_triangle_;
  std::vector<uint8_t> grey_;
  std::vector<int32_t> ids_;
};

}  // namespace avenues
