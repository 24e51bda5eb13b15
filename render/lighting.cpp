// Avenues — the plan's lights placed, and Lambert's cosine term per polygon, per vertex and
// per sample (see lighting.h).
#include "render/lighting.h"

#include <algorithm>
#include <cmath>

namespace avenues {

const char* to_string(Lights l) { return l == Lights::Plan ? "plan" : "eye"; }

const char* to_string(ObjectShadows s) {
  return s == ObjectShadows::On ? "on" : s == ObjectShadows::Off ? "off" : "auto";
}

bool parse_lights(const std::string& text, Lights& out) {
  for (Lights l : {Lights::Plan, Lights::Eye})
    if (text == to_string(l)) {
      out = l;
      return true;
    }
  return false;
}

bool parse_object_shadows(const std::string& text, ObjectShadows& out) {
  for (ObjectShadows s : {ObjectShadows::Auto, ObjectShadows::On, ObjectShadows::Off})
    if (text == to_string(s)) {
      out = s;
      return true;
    }
  return false;
}

namespace {

float luminance_of(const std::array<float, 3>& c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

bool is_grey(const std::array<float, 3>& c) { return c[0] == c[1] && c[1] == c[2]; }

std::array<float, 3> linear_colour(const std::array<double, 3>& c) {
  return {float(std::clamp(c[0], 0.0, 1.0)), float(std::clamp(c[1], 0.0, 1.0)), float(std::clamp(c[2], 0.0, 1.0))};
}

/// Wylie's distance law as a factor in [0, 1]: (r0 / r)^power beyond r0, 1 nearer.
double law(double r, const Lighting& l) {
  if (!l.falloff || r <= l.falloff_start) return 1;
  const double q = (l.falloff_start / r) * (l.falloff_start / r);
  return l.falloff_power == 4 ? q * q : q;
}

}  // namespace

Lighting lighting_of(const CellComplex& complex, const Shading& shading, Lights lights, bool smooth, bool colour) {
  Lighting out;
  const float back = float(std::clamp(shading.back, 0.0, 1.0));
  out.ambient = {back, back, back};
  std::array<float, 3> ambient{0, 0, 0};
  for (const Light& l : complex.lights) {
    if (l.kind != LightKind::Ambient) continue;
    ++out.ambient_lights;
    const std::array<float, 3> c = linear_colour(l.colour);
    for (size_t k = 0; k < 3; ++k) ambient[k] += float(l.intensity) * c[k];
  }
  if (out.ambient_lights > 0)
    for (size_t k = 0; k < 3; ++k) out.ambient[k] = std::clamp(ambient[k], 0.0f, 0.999f);
  if (lights == Lights::Plan)
    for (const Light& l : complex.lights) {
      if (l.kind != LightKind::Point) continue;
      PointLight p;
      p.name = l.name;
      p.position = l.position;
      p.intensity = float(l.intensity);
      p.colour = linear_colour(l.colour);
      const Location at = complex.locate(l.position);
      p.cell = at.what == Location::What::Cell ? at.cell : kNoCell;
      if (p.cell == kNoCell) ++out.unplaced;
      out.points.push_back(std::move(p));
    }
  out.at_eye = out.points.empty();
  // Coloured light only when asked: some light (or the ambient) not white, in a colour picture.
  out.coloured = colour && !out.at_eye && (!is_grey(out.ambient) || std::any_of(out.points.begin(), out.points.end(),
                                                                                 [](const PointLight& p) { return !is_grey(p.colour); }));
  if (!out.coloured) {
    const float a = luminance_of(out.ambient);
    out.ambient = {a, a, a};
    for (PointLight& p : out.points) {
      const float y = luminance_of(p.colour);
      p.colour = {y, y, y};
    }
  }
  out.diffuse = 1 - std::max({out.ambient[0], out.ambient[1], out.ambient[2]});
  out.falloff = smooth && !out.at_eye && shading.falloff_start > 0;
  out.falloff_start = out.falloff ? shading.falloff_start : 0;
  out.falloff_power = shading.falloff_power == 4 ? 4 : 2;
  return out;
}

std::array<float, 3> term_colour(const PointLight& source, const Lighting& lighting) {
  (void)lighting;  // the colour was already reduced to grey when the light is not coloured
  return {source.intensity * source.colour[0], source.intensity * source.colour[1],
          source.intensity * source.colour[2]};
}

bool planar_light_term(const Material& m, Vec3 n, double d, Vec3 centroid, Vec3 light, const PointLight& source,
                       const Lighting& lighting, bool per_sample, LightTerm& out) {
  const double nl = length(n);
  if (!(nl > 0) || d == 0) return false;
  // The eye (the origin) is on the side where n·P + d has the sign of d.
  const Vec3 seen = ((d > 0 ? 1.0 : -1.0) / nl) * n;
  const double height = dot(seen, light) + std::fabs(d) / nl;  // the light's distance from the plane, eye side
  if (!(height > 0)) return false;
  const double base = lighting.diffuse * std::clamp(m.reflectance, 0.0, 1.0);
  out = LightTerm{};
  out.colour = term_colour(source, lighting);
  if (per_sample) {
    out.kind = LightTerm::Kind::Plane;
    out.diffuse = float(base);
    out.light = light;
    out.normal = seen;
    out.falloff_start_sq = lighting.falloff ? float(lighting.falloff_start * lighting.falloff_start) : 0.0f;
    out.falloff_power = lighting.falloff_power;
    return true;
  }
  // Bouknight's flat shade: the cosine (and the law) at the centroid.
  const double r = length(light - centroid);
  out.kind = LightTerm::Kind::Constant;
  out.diffuse = float(base * std::min(1.0, height / r) * law(r, lighting));
  return r > 0;
}

bool gouraud_light_term(const Material& m, const std::array<Vec3, 3>& points, const std::array<Vec3, 3>& normals,
                        Vec3 light, const PointLight& source, const Lighting& lighting, const RasterMap& raster,
                        LightTerm& out) {
  const double base = lighting.diffuse * std::clamp(m.reflectance, 0.0, 1.0);
  std::array<double, 3> value{};
  bool any = false;
  for (size_t k = 0; k < 3; ++k) {
    const Vec3 l = light - points[k];
    const double r = length(l);
    const double cos_phi = r > 0 ? std::max(0.0, dot(normals[k], l) / r) : 0;
    value[k] = base * cos_phi * law(r, lighting);
    any |= value[k] > 0;
  }
  if (!any) return false;
  out = LightTerm{};
  out.kind = LightTerm::Kind::Gouraud;
  out.colour = term_colour(source, lighting);
  return over_depth(points, value, raster, out.diffuse_over_depth);
}

void lit_samples(const std::array<float, 3>& ambient, const LightTerm* terms, int count, const uint8_t* const* masks,
                 const RasterPlane& depth, const RasterMap& raster, int row, int x0, int x1, int channels, float* out) {
  const int n = x1 - x0;
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < channels; ++c) out[i * channels + c] = ambient[size_t(c)];
  const double v = row + 0.5;
  const double y = raster.y0 - raster.step * v;
  const double depth_row = depth.b * v + depth.c;
  for (int t = 0; t < count; ++t) {
    const LightTerm& term = terms[t];
    const uint8_t* mask = masks[t];
    auto add = [&](int i, float d) {
      if (mask && !mask[i]) return;
      for (int c = 0; c < channels; ++c) out[i * channels + c] += d * term.colour[size_t(c)];
    };
    switch (term.kind) {
      case LightTerm::Kind::Constant:
        for (int i = 0; i < n; ++i) add(i, term.diffuse);
        break;
      case LightTerm::Kind::Plane:
        // The sample's ray d = (x, y, 1) meets the plane at P = d·Z, Z = 1 / (1/Z).
        for (int i = 0; i < n; ++i) {
          if (mask && !mask[i]) continue;
          const double u = x0 + i + 0.5;
          const double z = 1 / (depth.a * u + depth_row);
          const Vec3 p{(raster.x0 + raster.step * u) * z, y * z, z};
          const Vec3 l = term.light - p;
          const double r2 = dot(l, l);
          if (!(r2 > 0)) continue;
          const double cos_phi = dot(term.normal, l) / std::sqrt(r2);
          if (!(cos_phi > 0)) continue;
          double f = 1;
          if (term.falloff_start_sq > 0 && r2 > term.falloff_start_sq) {
            f = term.falloff_start_sq / r2;
            if (term.falloff_power == 4) f *= f;
          }
          add(i, float(term.diffuse * cos_phi * f));
        }
        break;
      case LightTerm::Kind::Gouraud: {
        const RasterPlane& g = term.diffuse_over_depth;
        const double g_row = g.b * v + g.c;
        for (int i = 0; i < n; ++i) {
          const double u = x0 + i + 0.5;
          add(i, float(std::clamp((g.a * u + g_row) / (depth.a * u + depth_row), 0.0, 1.0)));
        }
        break;
      }
    }
  }
  for (int i = 0; i < n * channels; ++i) out[i] = std::min(out[i], 1.0f);
}

}  // namespace avenues
