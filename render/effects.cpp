// Avenues — deciding the effects of a scene and saying why (see effects.h).
#include "render/effects.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <sstream>

#include "render/interpenetration.h"

namespace avenues {

namespace {

using Clock = std::chrono::steady_clock;
double micros_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string plural(long n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

/// Names in quotes, the first few: 'a', 'b' and 2 more.
std::string names(const std::vector<std::string>& all) {
  std::string out;
  const size_t shown = std::min<size_t>(all.size(), 3);
  for (size_t i = 0; i < shown; ++i) out += (i == 0 ? "'" : ", '") + all[i] + "'";
  if (all.size() > shown) out += " and " + std::to_string(all.size() - shown) + " more";
  return out;
}

/// A mesh is curved when some triangle's corners carry normals other than its own, each
/// within 45° of it (the builder's test for Gouraud under Auto, scene_screen.cpp, triangle
/// by triangle): a smooth surface cut into polygons. A box's corners keep their faces'
/// normals (smooth_corner_normals averages only across edges under 45°), so it is flat.
bool curved(const Mesh& m) {
  for (size_t i = 0; i < m.triangles.size() && 3 * i + 2 < m.corner_normals.size(); ++i) {
    const auto& t = m.triangles[i];
    const Vec3 a = m.vertices[size_t(t[0])], b = m.vertices[size_t(t[1])], c = m.vertices[size_t(t[2])];
    const Vec3 n = cross(b - a, c - a);
    const double l = length(n);
    if (!(l > 0)) continue;
    double min_cos = 1;
    for (size_t k = 0; k < 3; ++k) min_cos = std::min(min_cos, dot(m.corner_normals[3 * i + k], (1 / l) * n));
    if (!(min_cos > 1 - 1e-9) && min_cos >= kCurvedCos) return true;
  }
  return false;
}

std::string colour_text(const std::array<float, 3>& c) {
  std::string out = "(";  // not "(" + string: GCC 12's -Wrestrict misfires on it (a known false positive)
  out += num(c[0]) + ", " + num(c[1]) + ", " + num(c[2]) + ")";
  return out;
}

bool grey(const std::array<double, 3>& c) { return c[0] == c[1] && c[1] == c[2]; }

}  // namespace

EffectPlan plan_effects(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                        const HalftoneOptions& options) {
  const auto t0 = Clock::now();
  EffectPlan p;
  p.shading = options.shading;

  // Depth: only among a cell's objects and its own faces.
  std::set<CellId> cells_with_objects;
  std::vector<std::string> curved_names;
  long drawn = 0;
  for (const PlacedObject& o : objects) {
    if (o.cell == kNoCell) continue;
    ++drawn;
    for (const ObjectCell& in : o.cells) cells_with_objects.insert(in.cell);
    if (curved(o.mesh)) curved_names.push_back(o.name);
  }
  p.depth.on = drawn > 0;
  p.depth.why = drawn > 0 ? plural(drawn, "object", "objects") + " in " +
                                plural(long(cells_with_objects.size()), "cell", "cells") +
                                ": depth is sorted in those cells only"
                          : "no object stands in any cell, and the faces of a convex cell never hide each other";

  // Smooth shading: asked, or (Auto) for curved meshes only.
  switch (options.shading.model) {
    case ShadingModel::Flat: p.smooth = {false, "flat shading asked (Bouknight)"}; break;
    case ShadingModel::Smooth: p.smooth = {true, "smooth shading asked (Wylie), on every polygon"}; break;
    case ShadingModel::Auto:
      p.smooth.on = !curved_names.empty();
      p.smooth.why = p.smooth.on ? plural(long(curved_names.size()), "curved mesh", "curved meshes") + " (" +
                                       names(curved_names) + "): Gouraud on their curved polygons, flat elsewhere"
                                 : "no curved mesh: every polygon is planar, and flat shading lights a plane exactly";
      break;
  }

  // The lights.
  p.lighting = lighting_of(complex, options.shading, options.lights, p.smooth.on, options.colour);
  if (p.lighting.at_eye && p.lighting.ambient_lights > 0) p.shading.back = p.lighting.ambient[0];

  // Implicit lines: only where polygons interpenetrate.
  if (drawn == 0) {
    p.implicit_lines = {false, "no objects: the faces of convex cells never cross"};
  } else {
    const Interpenetration ip = find_interpenetration(complex, objects);
    p.interpenetration_pairs = ip.pairs_tested;
    p.implicit_lines.on = ip.found;
    p.implicit_lines.why = ip.found ? ip.what
                                    : "no two polygons interpenetrate (" +
                                          plural(ip.pairs_tested, "pair", "pairs") + " of triangles tested at load)";
  }

  // Shadows: only for point lights away from the eye.
  std::vector<std::string> point_names;
  for (const Light& l : complex.lights)
    if (l.kind == LightKind::Point) point_names.push_back(l.name);
  if (point_names.empty()) {
    p.shadows = {false, "the plan has no light away from the eye"};
  } else if (options.lights == Lights::Eye) {
    p.shadows = {false, "lit from the eye only, as asked (the plan's " +
                            plural(long(point_names.size()), "point light is", "point lights are") + " not used)"};
  } else {
    p.shadows.on = true;
    p.shadows.why = plural(long(point_names.size()), "point light", "point lights") + " away from the eye (" +
                    names(point_names) + ")";
  }
  // Objects' shadows: Bouknight's shadow polygons, one cut per occluding triangle and surface.
  long triangles = 0;
  for (const PlacedObject& o : objects)
    if (o.cell != kNoCell) triangles += long(o.mesh.triangles.size());
  const long work = triangles * long(point_names.size());
  const std::string count = plural(triangles, "object triangle", "object triangles") + " under " +
                            plural(long(point_names.size()), "point light", "point lights");
  if (!p.shadows.on) {
    p.object_shadows = {false, "no shadows"};
  } else if (triangles == 0) {
    p.object_shadows = {false, "no object stands in any cell"};
  } else if (options.object_shadows == ObjectShadows::Off) {
    p.object_shadows = {false, "asked off (" + count + ")"};
  } else if (options.object_shadows == ObjectShadows::On) {
    p.object_shadows = {true, "asked (" + count + ")"};
  } else if (work <= kAutoObjectShadows) {
    p.object_shadows = {true, count + ", at most " + std::to_string(kAutoObjectShadows) + " triangle-lights"};
  } else {
    p.object_shadows = {false, count + ": " + std::to_string(work) + " triangle-lights, over the " +
                                   std::to_string(kAutoObjectShadows) + " that auto casts (seconds of cutting); "
                                   "--object-shadows on casts them"};
  }

  // Distance falloff: Wylie's law, with smooth shading and a distance to start from.
  if (!p.smooth.on) {
    p.falloff = {false, "flat shading has no distance law"};
  } else if (!(options.shading.falloff_start > 0)) {
    p.falloff = {false, "no falloff distance given"};
  } else {
    p.falloff.on = true;
    p.falloff.why = std::string(p.lighting.at_eye ? "Wylie's law from the eye" : "Wylie's law from each light") +
                    " beyond " + num(options.shading.falloff_start) + " m (inverse " +
                    (options.shading.falloff_power == 4 ? "fourth power" : "square") + ")";
  }

  // Coloured light: only when some light or the ambient is not white, in colour.
  if (!options.colour) {
    p.coloured = {false, "the picture is grey"};
  } else if (p.lighting.at_eye) {
    p.coloured = {false, "the light at the eye is white"};
  } else if (!p.lighting.coloured) {
    p.coloured = {false, "every light is white"};
  } else {
    p.coloured.on = true;
    for (const Light& l : complex.lights)
      if (!grey(l.colour)) {
        p.coloured.why = std::string(l.kind == LightKind::Ambient ? "ambient light '" : "light '") + l.name +
                         "' is coloured " +
                         colour_text({float(l.colour[0]), float(l.colour[1]), float(l.colour[2])});
        break;
      }
  }
  p.plan_us = micros_since(t0);
  return p;
}

std::string explain_effects(const EffectPlan& plan) {
  const std::pair<const char*, const Effect*> rows[] = {
      {"depth", &plan.depth},          {"implicit lines", &plan.implicit_lines},
      {"shadows", &plan.shadows},      {"object shadows", &plan.object_shadows}, {"smooth shading", &plan.smooth},
      {"distance falloff", &plan.falloff}, {"coloured light", &plan.coloured}};
  std::string out;
  for (const auto& [name, effect] : rows)
    out += std::string(name) + ": " + (effect->on ? "on" : "off") + " \u2014 " + effect->why + "\n";
  return out;
}

SceneEffects prepare_effects(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                             const HalftoneOptions& options, Kernel kernel) {
  const auto t0 = Clock::now();
  SceneEffects e;
  e.plan = plan_effects(complex, objects, options);
  if (e.plan.shadows.on) {
    e.shadows = cast_shadows(complex, objects, e.plan.lighting, kernel, e.plan.object_shadows.on, options.threads);
    std::string reach;
    for (size_t k = 0; k < e.shadows.lights.size(); ++k) {
      const PointLight& light = e.plan.lighting.points[k];
      const LightShadows& ls = e.shadows.lights[k];
      reach += (k == 0 ? ": '" : "; '") + light.name + "' ";
      reach += light.cell == kNoCell ? std::string("stands in no cell and lights nothing")
                                     : "reaches " + plural(long(ls.reach.cells.size()), "cell", "cells") +
                                           (e.plan.object_shadows.on ? ", objects cast " + plural(ls.shadow_polygons, "shadow polygon", "shadow polygons") : "");
    }
    e.plan.shadows.why += reach;
  }
  e.prepare_us = micros_since(t0);
  return e;
}

}  // namespace avenues
