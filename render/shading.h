// Avenues — how bright a surface is: the half-tone shading of Bouknight and Wylie, with the
// light at the eye.
//
// Bouknight 1969, Appendix 3: "I = R * RANGE * cos φ + BACK", φ the angle between the
// surface's normal and the line to the light, R the surface's reflectance, BACK "the
// amount of ambient light reflected from a surface" and RANGE = 256 − BACK. On our scale
// of [0, 1] in linear light: I = back + (1 − back)·R·cos φ, and the material's colour
// (linear RGB) tints the result.
//
// Wylie 1967: "a point source of illumination at the view point (like a single flashbulb
// photograph)"; "light flux varies as the inverse square of the distance ... We have
// arbitrarily chosen an inverse fourth law"; intensity found at the vertices and "linear
// interpolation ... over the visible interior" of each triangle.
//
// Two models:
//  - Flat: Bouknight's, one intensity per polygon. He simplifies the direction to the light
//    to the view axis; we take the line from the eye to the polygon's centroid, so that
//    in a wide interior view the floor and the side walls are not all left at BACK.
//  - Smooth: Wylie's, with the distance law. A planar polygon (architecture) is lit at
//    every sample from its plane (computed, not interpolated: no seams where masks cut a
//    face, and no Gouraud error over large walls). A curved mesh is lit at its vertices from their normals and interpolated
//    across each triangle (Gouraud), perspective-correct: I/Z is affine on the raster,
//    so the interpolation is the triangle's own in space and does not change when the
//    near plane or a mask clips it (Wylie interpolated on the picture plane, I = ax+by+c).
// The light sits at the eye in both (cos φ uses |n·l|: a face is lit from whichever side
// the eye sees it).
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "core/geometry.h"
#include "plans/plan.h"
#include "render/raster_map.h"

namespace avenues {

/// Flat: Bouknight's, everywhere. Smooth: Wylie's, everywhere. Auto: smooth only where it
/// shows — Gouraud on the curved polygons of meshes, flat on everything planar.
enum class ShadingModel : uint8_t { Flat, Smooth, Auto };
/// Auto: a mesh polygon is curved when its corners' normals differ from its own, each by
/// less than 45° (cosine above this); more than that is a crease (a box's averaged corners).
constexpr double kCurvedCos = 0.70710678118654752;
const char* to_string(ShadingModel m);
/// Parses "flat", "smooth" or "auto"; false if it is none of them.
bool parse_shading(const std::string& s, ShadingModel& out);

struct Shading {
  ShadingModel model = ShadingModel::Flat;
  double back = 0.1;          ///< Bouknight's BACK as a fraction of full scale, [0, 1)
  double falloff_start = 5;   ///< [m] Smooth: Wylie's distance law dims what lies farther than this; <= 0: off
  int falloff_power = 2;      ///< Smooth: 2 (inverse square) or 4 (Wylie's inverse fourth power)
};

/// One polygon's shading on the raster: what the scan needs to light its samples.
struct SurfaceShade {
  enum class Kind : uint8_t {
    Constant,  ///< I = intensity (Flat)
    EyeLight,  ///< I from the plane at each sample (Smooth, planar polygons)
    Gouraud,   ///< I = intensity_over_depth / (1/Z) (Smooth, meshes)
    Lit,       ///< I from the plan's lights: ambient plus light terms (lighting.h), where the secondary scan says lit
  };
  Kind kind = Kind::Constant;
  std::array<float, 3> colour{0.8f, 0.8f, 0.8f};  ///< linear RGB of the material, each [0, 1]
  float intensity = 0;            ///< Constant: I in [0, 1]
  float ambient = 0;              ///< EyeLight: back
  float diffuse = 0;              ///< EyeLight: (1 − back)·R
  double plane_distance = 0;      ///< EyeLight: [m] distance from the eye to the polygon's plane, > 0
  double falloff_start_sq = 0;    ///< EyeLight: [m²] square of Shading::falloff_start; 0: no falloff
  int falloff_power = 2;          ///< EyeLight: 2 or 4
  RasterPlane intensity_over_depth;  ///< Gouraud: I·(1/Z), affine on the raster
  std::array<float, 3> lit_ambient{};  ///< Lit: the ambient light A (linear RGB; [0] alone when not coloured)
  int32_t first_term = 0, terms = 0;   ///< Lit: the scene's light terms [first_term, first_term + terms)
  bool coloured = false;               ///< Lit: light per channel
};

/// A material's colour as linear RGB, each channel clamped to [0, 1].
std::array<float, 3> material_colour(const Material& m);

/// Bouknight's intensity at a point: back + (1 − back)·R·cos φ, times Wylie's distance law
/// min(1, (falloff_start / distance)^power) when `with_distance` (Smooth). In [0, 1].
double point_intensity(double reflectance, double cos_phi, double distance, const Shading& shading, bool with_distance);

/// Flat: the whole polygon at the intensity of its centroid, lit from the eye.
/// `normal` and `centroid` in camera space (the eye at the origin); normal of any length.
SurfaceShade flat_shade(const Material& m, Vec3 normal, Vec3 centroid, const Shading& shading);

/// Smooth, planar: lit per sample from the plane, which lies `plane_distance` [m] from the eye.
SurfaceShade eye_light_shade(const Material& m, double plane_distance, const Shading& shading);

/// Smooth, curved: Gouraud over a triangle with corners `points` and unit vertex normals
/// `normals`, both in camera space. False (and nothing set) if the triangle's plane
/// passes through the eye.
bool gouraud_shade(const Material& m, const std::array<Vec3, 3>& points, const std::array<Vec3, 3>& normals,
                   const Shading& shading, const RasterMap& raster, SurfaceShade& out);

/// The affine function on the raster equal to value[k]·(1/Z) at the triangle's corners
/// `points` (camera space): perspective-correct interpolation of a per-vertex quantity.
/// False if the triangle's plane passes through the eye.
bool over_depth(const std::array<Vec3, 3>& points, const std::array<double, 3>& value, const RasterMap& raster,
                RasterPlane& out);

/// Intensities I in [0, 1] of samples [x0, x1) of raster row `row` (centres at x + ½,
/// row + ½) on a polygon whose 1/Z is `depth`. Writes x1 − x0 values to `out`.
void shade_samples(const SurfaceShade& shade, const RasterPlane& depth, const RasterMap& raster, int row, int x0,
                   int x1, float* out);

}  // namespace avenues
