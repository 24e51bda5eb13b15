// Avenues — lights as the renderer sees them: the light at the eye, or the plan's point
// lights and its ambient light, and how one point light brightens one surface.
//
// Wylie 1967 and Bouknight 1969 light a scene from the eye ("a single flashbulb
// photograph"), which casts no visible shadow; that stays the default (shading.h). A plan's
// [[light]] of kind "point" stands somewhere else, and then the picture is lit by those
// lights instead: each adds Lambert's cosine term where it reaches (shadows.h decides
// where), on top of the ambient light — Bouknight's BACK, or the plan's [[light]] of kind
// "ambient":
//
//   I = A + Σ_k lit_k · (1 − A) · R · s_k · c_k · cos φ_k [· law(r_k)]
//
// A the ambient light, R the reflectance, s_k and c_k the light's intensity and colour,
// φ_k the angle between the surface's normal (on the side the eye sees) and the line to the
// light, r_k the distance to it, law Wylie's distance law (only when asked: falloff), lit_k
// 1 where the light reaches the sample and 0 in shadow. Each channel is clamped to 1. A
// light on the far side of a surface from the eye does not light what the eye sees of it.
//
// Per shading model, each light's term is a LightTerm:
//   Constant  Flat (Bouknight): cos φ and the law at the polygon's centroid;
//   Plane     Smooth, planar: per sample, from the point of the plane the sample sees;
//   Gouraud   Smooth, curved meshes: per vertex from its normal, interpolated (Wylie).
// In colour only when asked: a light or the ambient not white, and a picture in colour;
// otherwise every light is grey (its luminance) and one intensity serves all channels.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "render/raster_map.h"
#include "render/shading.h"

namespace avenues {

/// What lights a picture.
enum class Lights : uint8_t {
  Plan,  ///< the plan's point lights when it has any (with shadows), else the light at the eye
  Eye,   ///< the light at the eye only, whatever the plan says (Wylie, Bouknight)
};

/// Whether objects cast shadows from the plan's point lights (walls always do: light
/// passes only through openings). Bouknight's shadow polygons cost a cut per occluding
/// triangle and surface, which a furnished home with a dozen lamps makes seconds of work.
enum class ObjectShadows : uint8_t {
  Auto,  ///< when the object triangles times the point lights are at most kAutoObjectShadows
  On,    ///< always
  Off,   ///< never
};
/// Object triangles × point lights up to which Auto casts the objects' shadows.
inline constexpr long kAutoObjectShadows = 20000;
const char* to_string(ObjectShadows s);
bool parse_object_shadows(const std::string& text, ObjectShadows& out);
const char* to_string(Lights l);
bool parse_lights(const std::string& text, Lights& out);

/// A point light of the plan, placed.
struct PointLight {
  std::string name;
  Vec3 position;                        ///< [m] world
  float intensity = 1;                  ///< relative, > 0
  std::array<float, 3> colour{1, 1, 1}; ///< linear RGB as given; grey() when not coloured
  CellId cell = kNoCell;                ///< the cell holding it; kNoCell: inside a solid (it lights nothing)
};

struct Lighting {
  bool at_eye = true;                    ///< Wylie and Bouknight: one light at the eye, no shadows
  std::vector<PointLight> points;        ///< empty when at_eye
  std::array<float, 3> ambient{0.1f, 0.1f, 0.1f};  ///< linear RGB, each in [0, 1): A
  float diffuse = 0.9f;                  ///< (1 − A): Bouknight's RANGE, the share left for the lights
  bool coloured = false;                 ///< per channel (some light or the ambient is not white, in colour)
  bool falloff = false;                  ///< Wylie's distance law from each light
  double falloff_start = 0;              ///< [m] the law's r0, when falloff
  int falloff_power = 2;                 ///< 2 or 4
  int ambient_lights = 0;                ///< the plan's ambient lights summed into `ambient`
  int unplaced = 0;                      ///< point lights in no cell (inside a wall): they light nothing
};

/// The lights a render uses: the plan's (complex.lights, each located in its cell) or the
/// light at the eye. `smooth`: some polygon is smoothly shaded (the distance law applies to
/// point lights only then, as it does to the eye's light). `colour`: the picture is in colour.
Lighting lighting_of(const CellComplex& complex, const Shading& shading, Lights lights, bool smooth, bool colour);

/// How one point light brightens one polygon on the raster (see the header comment).
struct LightTerm {
  enum class Kind : uint8_t { Constant, Plane, Gouraud };
  Kind kind = Kind::Constant;
  std::array<float, 3> colour{1, 1, 1};  ///< the light's intensity times its colour ([0] alone when not coloured)
  float diffuse = 0;           ///< Constant: (1 − A)·R·cos φ·law at the centroid; Plane: (1 − A)·R
  Vec3 light;                  ///< Plane: the light in camera space [m]
  Vec3 normal;                 ///< Plane: unit normal in camera space, on the side the eye sees
  float falloff_start_sq = 0;  ///< Plane: [m²] r0² of the distance law; 0: none
  int falloff_power = 2;       ///< Plane: 2 or 4
  RasterPlane diffuse_over_depth;  ///< Gouraud: (1 − A)·R·cos φ·law times 1/Z, affine on the raster
  /// Where it lights: everywhere on the polygon (`whole`) or in the union of the lit
  /// pieces; less the union of the shadow pieces either way. Pieces are indices into the
  /// scene's secondary-scan polygons: lit ones [first_piece, first_piece + lit_pieces), then
  /// shadow ones (shadow_pieces of them).
  bool whole = true;
  int32_t first_piece = 0, lit_pieces = 0, shadow_pieces = 0;
  bool needs_scan() const { return !whole || shadow_pieces > 0; }
};

/// Lambert's term of a planar polygon with plane n·P + d = 0 in camera space (the eye at the
/// origin, d != 0), centroid `centroid`, for a light at `light` (camera space). False when
/// the light is on the far side of the plane from the eye (the eye sees the dark side).
/// `per_sample`: a Plane term (Smooth); otherwise a Constant one (Flat).
bool planar_light_term(const Material& m, Vec3 n, double d, Vec3 centroid, Vec3 light, const PointLight& source,
                       const Lighting& lighting, bool per_sample, LightTerm& out);

/// Gouraud's term of a triangle (camera-space corners and unit vertex normals, the normals
/// turned to the side the eye sees) for a light at `light` (camera space). False when no
/// corner is lit or the triangle's plane passes through the eye.
bool gouraud_light_term(const Material& m, const std::array<Vec3, 3>& points, const std::array<Vec3, 3>& normals,
                        Vec3 light, const PointLight& source, const Lighting& lighting, const RasterMap& raster,
                        LightTerm& out);

/// The light's colour in a term: intensity × colour, or its luminance when not coloured.
std::array<float, 3> term_colour(const PointLight& source, const Lighting& lighting);

/// Intensities of samples [x0, x1) of raster row `row` of a polygon lit by `terms`: the
/// ambient `ambient` plus each term where its mask says it is lit (masks[t][i] != 0 for sample
/// x0 + i; masks[t] == nullptr: lit everywhere), clamped to 1. Writes `channels` values per
/// sample (1: white light, 3: coloured) to `out`.
void lit_samples(const std::array<float, 3>& ambient, const LightTerm* terms, int count, const uint8_t* const* masks,
                 const RasterPlane& depth, const RasterMap& raster, int row, int x0, int x1, int channels, float* out);

}  // namespace avenues
