// Avenues — Bouknight's cosine law and Wylie's distance law, per polygon, per vertex and per
// sample (see shading.h).
#include "render/shading.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace avenues {

const char* to_string(ShadingModel m) {
  switch (m) {
    case ShadingModel::Flat: return "flat";
    case ShadingModel::Smooth: return "smooth";
    case ShadingModel::Auto: return "auto";
  }
  return "?";
}

std::array<float, 3> material_colour(const Material& m) {
  return {float(std::clamp(m.colour[0], 0.0, 1.0)), float(std::clamp(m.colour[1], 0.0, 1.0)),
          float(std::clamp(m.colour[2], 0.0, 1.0))};
}

bool parse_shading(const std::string& s, ShadingModel& out) {
  if (s == "flat") out = ShadingModel::Flat;
  else if (s == "smooth") out = ShadingModel::Smooth;
  else if (s == "auto") out = ShadingModel::Auto;
  else return false;
  return true;
}

namespace {

double back_of(const Shading& s) { return std::clamp(s.back, 0.0, 1.0); }

/// Wylie's distance law as a factor in [0, 1]: (r0 / r)^power beyond r0, 1 nearer.
double falloff(double distance, const Shading& s) {
  if (!(s.falloff_start > 0) || distance <= s.falloff_start) return 1;
  const double q = (s.falloff_start / distance) * (s.falloff_start / distance);
  return s.falloff_power == 4 ? q * q : q;
}

}  // namespace

double point_intensity(double reflectance, double cos_phi, double distance, const Shading& shading,
                       bool with_distance) {
  const double back = back_of(shading);
  const double lit = std::clamp(reflectance, 0.0, 1.0) * std::clamp(cos_phi, 0.0, 1.0) *
                     (with_distance ? falloff(distance, shading) : 1.0);
  return back + (1 - back) * lit;
}

SurfaceShade flat_shade(const Material& m, Vec3 normal, Vec3 centroid, const Shading& shading) {
  SurfaceShade s;
  s.kind = SurfaceShade::Kind::Constant;
  s.colour = material_colour(m);
  const double nl = length(normal), cl = length(centroid);
  // Bouknight App. 3: cos φ = |n·l| / (|n| |l|), l from the polygon to the light at the eye.
  const double cos_phi = nl > 0 && cl > 0 ? std::fabs(dot(normal, centroid)) / (nl * cl) : 1;
  s.intensity = float(point_intensity(m.reflectance, cos_phi, cl, shading, false));
  return s;
}

SurfaceShade eye_light_shade(const Material& m, double plane_distance, const Shading& shading) {
  SurfaceShade s;
  s.kind = SurfaceShade::Kind::EyeLight;
  s.colour = material_colour(m);
  const double back = back_of(shading);
  s.ambient = float(back);
  s.diffuse = float((1 - back) * std::clamp(m.reflectance, 0.0, 1.0));
  s.plane_distance = plane_distance;
  s.falloff_start_sq = shading.falloff_start > 0 ? shading.falloff_start * shading.falloff_start : 0;
  s.falloff_power = shading.falloff_power == 4 ? 4 : 2;
  return s;
}

bool over_depth(const std::array<Vec3, 3>& p, const std::array<double, 3>& value, const RasterMap& raster,
                RasterPlane& out) {
  // A function linear over the triangle's plane, which misses the eye, is I(P) = g·P for
  // one vector g: solve g·P_k = I_k by Cramer's rule.
  const Vec3 c12 = cross(p[1], p[2]), c20 = cross(p[2], p[0]), c01 = cross(p[0], p[1]);
  const double det = dot(p[0], c12);
  if (!(std::fabs(det) > 1e-14 * length(p[0]) * length(p[1]) * length(p[2]))) return false;
  const Vec3 g = (1 / det) * (value[0] * c12 + value[1] * c20 + value[2] * c01);
  // On the raster P = d / (1/Z) with d = (x, y, 1) on the picture plane, so I·(1/Z) = g·d,
  // affine in the raster position: x = x0 + step·u, y = y0 − step·v.
  out = {g.x * raster.step, -g.y * raster.step, g.x * raster.x0 + g.y * raster.y0 + g.z};
  return true;
}

bool gouraud_shade(const Material& m, const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& n,
                   const Shading& shading, const RasterMap& raster, SurfaceShade& out) {
  std::array<double, 3> value{};
  for (size_t k = 0; k < 3; ++k) {
    const double r = length(p[k]);
    // Wylie: brightness at each vertex from its normal and its distance to the eye.
    const double cos_phi = r > 0 ? std::fabs(dot(n[k], p[k])) / r : 1;
    value[k] = point_intensity(m.reflectance, cos_phi, r, shading, true);
  }
  RasterPlane f;
  if (!over_depth(p, value, raster, f)) return false;
  out = SurfaceShade{};
  out.kind = SurfaceShade::Kind::Gouraud;
  out.colour = material_colour(m);
  out.intensity_over_depth = f;
  return true;
}

namespace {

/// 1/√a for a >= 1 to a relative 5·10⁻⁶ — an estimate from the float's bits refined by two
/// Newton steps. Unlike std::sqrt (which may set errno) it lets the row loop vectorise.
float inverse_sqrt(float a) {
  float r = std::bit_cast<float>(0x5f375a86u - (std::bit_cast<uint32_t>(a) >> 1));
  r *= 1.5f - 0.5f * a * r * r;
  r *= 1.5f - 0.5f * a * r * r;
  return r;
}

/// EyeLight along one row (v = row + ½), for a distance law of `Power` (0: none). The
/// sample's ray d = (x, y, 1) meets the plane at P = d·Z, Z = 1/(1/Z), so
///   cos φ = |D| / |P| = |D|·(1/Z) / |d|,   (r0 / |P|)² = r0²·(1/Z)² / |d|².
/// In float: plenty for a value that ends as 8 bits, and twice as fast as double.
template <int Power>
void eye_light_row(const SurfaceShade& s, const RasterPlane& depth, const RasterMap& raster, double v, int x0,
                   int x1, float* out) {
  const float y = float(raster.y0 - raster.step * v);
  const float yy1 = y * y + 1;
  const float step = float(raster.step), x_first = float(raster.x0 + raster.step * (x0 + 0.5));
  const float iz_first = float(depth.a * (x0 + 0.5) + depth.b * v + depth.c), iz_step = float(depth.a);
  const float distance = float(s.plane_distance), r0_sq = float(s.falloff_start_sq);
  for (int i = 0; i < x1 - x0; ++i) {
    const float x = x_first + step * float(i);
    const float iz = iz_first + iz_step * float(i);
    const float inv_d = inverse_sqrt(x * x + yy1), inv_d2 = inv_d * inv_d;  // |d| >= 1
    const float cos_phi = std::min(1.0f, std::max(0.0f, distance * iz * inv_d));
    float law = 1;
    if constexpr (Power > 0) law = std::min(1.0f, r0_sq * iz * iz * inv_d2);
    if constexpr (Power == 4) law *= law;
    out[i] = s.ambient + s.diffuse * cos_phi * law;
  }
}

}  // namespace

void shade_samples(const SurfaceShade& s, const RasterPlane& depth, const RasterMap& raster, int row, int x0,
                   int x1, float* out) {
  const double v = row + 0.5;
  switch (s.kind) {
    case SurfaceShade::Kind::Constant:
      std::fill(out, out + (x1 - x0), s.intensity);
      return;
    case SurfaceShade::Kind::EyeLight:
      if (s.falloff_start_sq <= 0) return eye_light_row<0>(s, depth, raster, v, x0, x1, out);
      if (s.falloff_power == 4) return eye_light_row<4>(s, depth, raster, v, x0, x1, out);
      return eye_light_row<2>(s, depth, raster, v, x0, x1, out);
    case SurfaceShade::Kind::Lit:  // lit_samples (lighting.h) lights these, with the secondary scan's masks
      std::fill(out, out + (x1 - x0), 0.0f);
      return;
    case SurfaceShade::Kind::Gouraud: {
      const RasterPlane& f = s.intensity_over_depth;
      const double f_row = f.b * v + f.c, depth_row = depth.b * v + depth.c;
      for (int i = x0; i < x1; ++i) {
        const double u = i + 0.5;
        out[i - x0] = float(std::clamp((f.a * u + f_row) / (depth.a * u + depth_row), 0.0, 1.0));
      }
      return;
    }
  }
}

}  // namespace avenues
