// Avenues — the Embree peer (see embree_peer.h).
#include "bench/embree_peer.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace avenues {

namespace {

const Material& material_of(const CellComplex& c, MaterialId id) {
  static const Material fallback;
  return id >= 0 && id < MaterialId(c.materials.size()) ? c.materials[size_t(id)] : fallback;
}

/// The same flat grey the llvmpipe peer gives a triangle: reflectance × luminance, dimmed
/// by orientation so that floors, walls and ceilings differ.
uint8_t grey_of(const Material& m, Vec3 n) {
  const double l = length(n);
  const double up = l > 0 ? std::fabs(n.z / l) : 0;
  const double lum = 0.2126 * m.colour[0] + 0.7152 * m.colour[1] + 0.0722 * m.colour[2];
  return uint8_t(std::lround(255 * std::clamp(m.reflectance * lum * (0.6 + 0.4 * up), 0.0, 1.0)));
}

}  // namespace

EmbreePeer::EmbreePeer(int width, int height, int threads) : width_(width), height_(height), threads_(threads) {
  const std::string config = "threads=" + std::to_string(threads);
  device_ = rtcNewDevice(config.c_str());
  if (!device_) throw std::runtime_error("EmbreePeer: rtcNewDevice failed");
  grey_.assign(size_t(width) * size_t(height), 0);
  ids_.assign(size_t(width) * size_t(height), -1);
}

EmbreePeer::~EmbreePeer() {
  if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
  if (device_) rtcReleaseDevice(static_cast<RTCDevice>(device_));
}

int32_t EmbreePeer::source_index(const Source& s) const {
  auto it = index_of_.find(s);
  return it == index_of_.end() ? -1 : it->second;
}

void EmbreePeer::upload(const CellComplex& complex, const std::vector<PlacedObject>& objects) {
  RTCDevice device = static_cast<RTCDevice>(device_);
  if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
  RTCScene scene = rtcNewScene(device);
  scene_ = scene;
  sources_.clear();
  index_of_.clear();
  source_of_triangle_.clear();
  grey_of_triangle_.clear();
  std::vector<float> v;
  auto source = [&](const Source& s) {
    auto [it, fresh] = index_of_.try_emplace(s, int32_t(sources_.size()));
    if (fresh) sources_.push_back(s);
    return it->second;
  };
  auto triangle = [&](Vec3 a, Vec3 b, Vec3 c, int32_t src, uint8_t grey) {
    for (Vec3 p : {a, b, c}) v.insert(v.end(), {float(p.x), float(p.y), float(p.z)});
    source_of_triangle_.push_back(src);
    grey_of_triangle_.push_back(grey);
  };
  for (size_t ci = 0; ci < complex.cells.size(); ++ci) {
    const Cell& cell = complex.cells[ci];
    for (size_t fi = 0; fi < cell.faces.size(); ++fi)
      for (const OpaquePoly& piece : cell.faces[fi].opaque) {
        if (piece.poly.size() < 3) continue;
        const int32_t id = source({0, int(ci), int(fi)});
        const uint8_t g = grey_of(material_of(complex, piece.material), cell.faces[fi].plane.n);
        for (size_t k = 1; k + 1 < piece.poly.size(); ++k) triangle(piece.poly[0], piece.poly[k], piece.poly[k + 1], id, g);
      }
  }
  for (size_t oi = 0; oi < objects.size(); ++oi) {
    const PlacedObject& o = objects[oi];
    if (o.cell == kNoCell) continue;
    const Mesh& m = o.mesh;
    for (size_t t = 0; t < m.triangles.size(); ++t) {
      const int polygon = t < m.polygon_of.size() ? m.polygon_of[t] : int(t);
      const Vec3 a = m.vertices[size_t(m.triangles[t][0])], b = m.vertices[size_t(m.triangles[t][1])],
                 c = m.vertices[size_t(m.triangles[t][2])];
      triangle(a, b, c, source({1, int(oi), polygon}), grey_of(o.paint.of_polygon(polygon), cross(b - a, c - a)));
    }
  }
  const size_t n = source_of_triangle_.size();
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                         3 * sizeof(float), 3 * n));
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                            3 * sizeof(unsigned), n));
  if (!vb || !ib) throw std::runtime_error("EmbreePeer: cannot allocate the geometry buffers");
  std::copy(v.begin(), v.end(), vb);
  for (size_t i = 0; i < 3 * n; ++i) ib[i] = unsigned(i);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  rtcCommitScene(scene);
  if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw std::runtime_error("EmbreePeer: building the scene failed");
}

void EmbreePeer::draw(const Camera& cam) {
  // Primary rays are coherent: cast them in 4 × 4 packets (rtcIntersect16), Embree's
  // fastest path for camera rays, rows of tiles spread over the threads.
  RTCScene scene = static_cast<RTCScene>(scene_);
  const int tiles_y = (height_ + 3) / 4;
  tbb::task_arena arena(threads_);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_y, 2), [&](const tbb::blocked_range<int>& rows) {
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
      alignas(64) RTCRayHit16 rh;
      alignas(64) int valid[16];
      for (int ty = rows.begin(); ty < rows.end(); ++ty)
        for (int tx = 0; tx < width_; tx += 4) {
          for (int k = 0; k < 16; ++k) {
            const int x = tx + k % 4, y = 4 * ty + k / 4;
            valid[k] = x < width_ && y < height_ ? -1 : 0;
            const Vec3 d = cam.ray_through_raster({x + 0.5, y + 0.5});
            rh.ray.org_x[k] = float(cam.eye.x);
            rh.ray.org_y[k] = float(cam.eye.y);
            rh.ray.org_z[k] = float(cam.eye.z);
            rh.ray.dir_x[k] = float(d.x);
            rh.ray.dir_y[k] = float(d.y);
            rh.ray.dir_z[k] = float(d.z);
            rh.ray.tnear[k] = 0;
            rh.ray.tfar[k] = std::numeric_limits<float>::infinity();
            rh.ray.mask[k] = unsigned(-1);
            rh.ray.flags[k] = 0;
            rh.ray.time[k] = 0;
            rh.ray.id[k] = unsigned(k);
            rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
            rh.hit.instID[0][k] = RTC_INVALID_GEOMETRY_ID;
          }
          rtcIntersect16(valid, scene, &ctx, &rh);
          for (int k = 0; k < 16; ++k) {
            if (!valid[k]) continue;
            const size_t i = size_t(4 * ty + k / 4) * size_t(width_) + size_t(tx + k % 4);
            if (rh.hit.geomID[k] == RTC_INVALID_GEOMETRY_ID) {
              grey_[i] = 0;
              ids_[i] = -1;
            } else {
              grey_[i] = grey_of_triangle_[rh.hit.primID[k]];
              ids_[i] = source_of_triangle_[rh.hit.primID[k]];
            }
          }
        }
    });
  });
}

}  // namespace avenues
