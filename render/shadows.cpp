// Avenues — lit pieces and shadow polygons per surface, per point light (see shadows.h).
#include "render/shadows.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/thread_arena.h"

namespace avenues {

namespace {

/// Relative size below which a piece is a sliver of rounding, not a region.
constexpr double kSliver = 1e-9;
/// Twice an occluder's area, relative to its longest edge squared, below which it is a
/// segment (the sine of its widest angle, about).
constexpr double kFlat = 1e-9;

struct Sphere {
  Vec3 c;
  double r = 0;
};

Sphere sphere_of(const std::vector<Vec3>& pts) {
  Vec3 lo = pts[0], hi = pts[0];
  for (Vec3 p : pts) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  Sphere s{0.5 * (lo + hi), 0};
  for (Vec3 p : pts) s.r = std::max(s.r, length(p - s.c));
  return s;
}

/// Can something inside `occ` shade something inside `rec`, lit from `light`? Conservative:
/// false only when the receiver lies wholly nearer the light than the occluder, or outside
/// the cone from the light around the occluder.
bool may_shade(Vec3 light, const Sphere& occ, const Sphere& rec) {
  const Vec3 a = occ.c - light, b = rec.c - light;
  const double da = length(a), db = length(b);
  if (da <= occ.r || db <= rec.r) return true;
  if (db + rec.r < da - occ.r) return false;
  const double angle = std::acos(std::clamp(dot(a, b) / (da * db), -1.0, 1.0));
  return angle <= std::asin(occ.r / da) + std::asin(rec.r / db) + 1e-9;
}

Vec3 newell(const std::vector<Vec3>& p) {
  Vec3 n{0, 0, 0};
  for (size_t i = 0; i < p.size(); ++i) n = n + cross(p[i], p[(i + 1) % p.size()]);
  return n;
}

/// The shadow volume of a convex occluder lit from a point: the region beyond the
/// occluder's plane (away from the light) and inside the planes through the light and each
/// of its edges, each plane as a function ≥ 0 inside. Built once per occluder and light, so
/// that each receiver costs a few dot products when it lies outside (the usual case), and
/// the cut itself only when it may not.
class ShadowVolume {
 public:
  ShadowVolume(const std::vector<Vec3>& occluder, Vec3 light) : light_(light) {
    if (occluder.size() < 3) return;
    Vec3 n = newell(occluder);
    // An occluder of no area (its corners in a line, as models have them) hides nothing;
    // its side planes would all be one plane, and the "volume" half of space.
    double longest = 0;
    for (size_t i = 0; i < occluder.size(); ++i)
      longest = std::max(longest, length(occluder[(i + 1) % occluder.size()] - occluder[i]));
    if (!(length(n) > kFlat * longest * longest)) return;
    const double h = dot(n, light - occluder[0]);
    if (h == 0) return;  // the light in the occluder's plane: it casts nothing
    if (h < 0) n = -1.0 * n;
    base_ = occluder[0];
    back_ = n;
    Vec3 c{0, 0, 0};
    for (Vec3 v : occluder) c = c + (1.0 / double(occluder.size())) * v;
    for (size_t i = 0; i < occluder.size(); ++i) {
      Vec3 m = cross(occluder[i] - light, occluder[(i + 1) % occluder.size()] - light);
      if (dot(m, c - light) < 0) m = -1.0 * m;
      sides_.push_back(m);
    }
    casts_ = true;
  }

  /// True when the polygon lies wholly outside one of the volume's planes, so that the
  /// cut would leave nothing: no shadow on it.
  bool misses(const std::vector<Vec3>& poly) const {
    if (!casts_) return true;
    auto outside = [&](auto f) {
      for (Vec3 x : poly)
        if (f(x) >= 0) return false;
      return true;
    };
    if (outside([&](Vec3 x) { return -dot(back_, x - base_); })) return true;
    for (const Vec3& m : sides_)
      if (outside([&](Vec3 x) { return dot(m, x - light_); })) return true;
    return false;
  }

  /// The convex part of `surface` inside the volume; empty if none of some area.
  std::vector<Vec3> cut(const std::vector<Vec3>& surface) const {
    if (!casts_ || surface.size() < 3) return {};
    std::vector<Vec3> out = cut_polygon(surface, [&](Vec3 x) { return -dot(back_, x - base_); });
    for (size_t i = 0; i < sides_.size() && out.size() >= 3; ++i)
      out = cut_polygon(out, [&](Vec3 x) { return dot(sides_[i], x - light_); });
    if (out.size() < 3 || !(polygon_area(out) > kSliver * polygon_area(surface))) return {};
    return out;
  }

 private:
  Vec3 light_, base_, back_;
  std::vector<Vec3> sides_;
  bool casts_ = false;
};

/// One triangle of an object that faces the light.
struct Occluder {
  int object = -1, polygon = -1;
  std::vector<Vec3> tri;
  ShadowVolume volume;
};

/// A receiver of light: the convex parts of one face or one object polygon.
struct Receiver {
  CellId cell = kNoCell;
  int object = -1, polygon = -1;  ///< an object's polygon: it does not shade itself
  std::vector<std::vector<Vec3>> parts;
};

class LightCaster {
 public:
  LightCaster(const CellComplex& c, const std::vector<PlacedObject>& objects, Vec3 light, LightShadows& out)
      : c_(c), objects_(objects), light_(light), out_(out), scale_(1 + length(light)) {}

  void prepare() {
    // Cones per cell: the planes of each path's window; an empty window is every direction.
    cones_.assign(c_.cells.size(), {});
    all_directions_.assign(c_.cells.size(), 0);
    for (const LightPath& p : out_.reach.paths) {
      if (p.window.empty()) all_directions_[size_t(p.cell)] = 1;
      else cones_[size_t(p.cell)].push_back(cone_planes(light_, p.window));
    }
    // Occluders: the triangles facing the light of every object in a cell it reaches.
    occluders_by_object_.assign(objects_.size(), {});
    runs_by_object_.assign(objects_.size(), {});
    spheres_.assign(objects_.size(), {});
    for (size_t o = 0; o < objects_.size(); ++o) {
      const PlacedObject& obj = objects_[o];
      if (obj.cell == kNoCell || !out_.reach.reaches(obj.cell) || obj.mesh.vertices.empty()) continue;
      // The fitting a light hangs in (its bounds hold the light: a lamp's shade around its
      // bulb) casts no shadow from it; taken as opaque, it would put the whole room in
      // its shadow.
      if (obj.bounds.contains(light_)) continue;
      spheres_[o] = sphere_of(obj.mesh.vertices);
      for (size_t t = 0; t < obj.mesh.triangles.size(); ++t) {
        std::vector<Vec3> tri = triangle(obj.mesh, t);
        const double h = dot(newell(tri), light_ - tri[0]);
        if (obj.mesh.closed ? !(h > 0) : h == 0) continue;  // seen from behind, or edge-on
        ShadowVolume volume(tri, light_);
        occluders_by_object_[o].push_back(Occluder{int(o), obj.mesh.polygon_of[t], std::move(tri), std::move(volume)});
        ++out_.occluders;
      }
      // Runs of consecutive occluders (neighbours in the mesh, mostly) under one sphere, so
      // that a receiver far from most of an object's triangles skips them by the run.
      const std::vector<Occluder>& occ = occluders_by_object_[o];
      for (size_t first = 0; first < occ.size(); first += kRun) {
        std::vector<Vec3> pts;
        for (size_t k = first; k < std::min(occ.size(), first + kRun); ++k) pts.insert(pts.end(), occ[k].tri.begin(), occ[k].tri.end());
        runs_by_object_[o].push_back(sphere_of(pts));
      }
    }
  }

  /// What the light does to a surface; false: nothing (it does not reach it).
  bool light(const Receiver& s, SurfaceLight& out) {
    out = SurfaceLight{};
    const auto& cones = cones_[size_t(s.cell)];
    out.whole = all_directions_[size_t(s.cell)] != 0;
    for (size_t k = 0; k < cones.size() && !out.whole; ++k) out.whole = inside_cone(s.parts, cones[k]);
    if (!out.whole) {
      for (const auto& cone : cones)
        for (const auto& part : s.parts) {
          std::vector<Vec3> piece = part;
          for (const Vec3& n : cone) {
            piece = cut_polygon(piece, [&](Vec3 x) { return dot(n, x - light_); });
            if (piece.size() < 3) break;
          }
          if (piece.size() >= 3 && polygon_area(piece) > kSliver * polygon_area(part)) out.lit.push_back(std::move(piece));
        }
      if (out.lit.empty()) return false;
    }
    // Bouknight's shadow polygons: each occluder's shadow volume cut by the surface.
    std::vector<Vec3> all;
    for (const auto& part : s.parts) all.insert(all.end(), part.begin(), part.end());
    const Sphere rec = sphere_of(all);
    for (size_t o = 0; o < occluders_by_object_.size(); ++o) {
      if (occluders_by_object_[o].empty() || !may_shade(light_, spheres_[o], rec)) continue;
      const std::vector<Occluder>& occ = occluders_by_object_[o];
      for (size_t k = 0; k < occ.size(); ++k) {
        if (k % kRun == 0 && !may_shade(light_, runs_by_object_[o][k / kRun], rec)) {
          k += kRun - 1;
          continue;
        }
        const Occluder& q = occ[k];
        if (q.object == s.object && q.polygon == s.polygon) continue;
        for (const auto& part : s.parts) {
          ++out_.pairs_tested;
          if (q.volume.misses(part)) continue;
          std::vector<Vec3> sh = q.volume.cut(part);
          if (sh.empty()) continue;
          out.shadow.push_back(std::move(sh));
          ++out_.shadow_polygons;
        }
      }
    }
    return true;
  }

 private:
  static std::vector<Vec3> triangle(const Mesh& m, size_t t) {
    return {m.vertices[size_t(m.triangles[t][0])], m.vertices[size_t(m.triangles[t][1])],
            m.vertices[size_t(m.triangles[t][2])]};
  }

  bool inside_cone(const std::vector<std::vector<Vec3>>& parts, const std::vector<Vec3>& cone) const {
    for (const auto& part : parts)
      for (Vec3 x : part)
        for (const Vec3& n : cone)
          if (dot(n, x - light_) < -kSliver * scale_) return false;
    return true;
  }

  const CellComplex& c_;
  const std::vector<PlacedObject>& objects_;
  Vec3 light_;
  LightShadows& out_;
  double scale_;
  std::vector<std::vector<std::vector<Vec3>>> cones_;  ///< per cell: per path, its cone's planes
  std::vector<uint8_t> all_directions_;                ///< per cell: lit from every direction
  static constexpr size_t kRun = 16;  ///< occluders per run
  std::vector<std::vector<Occluder>> occluders_by_object_;
  std::vector<std::vector<Sphere>> runs_by_object_;  ///< per object: the sphere of each run of kRun occluders
  std::vector<Sphere> spheres_;
};

}  // namespace

std::vector<Vec3> shadow_on(const std::vector<Vec3>& surface, const std::vector<Vec3>& occluder, Vec3 light) {
  return ShadowVolume(occluder, light).cut(surface);
}

const SurfaceLight* SceneShadows::on_face(size_t light, CellId cell, int face) const {
  if (light >= lights.size() || cell < 0 || size_t(cell) >= face_base.size()) return nullptr;
  const int32_t s = lights[light].face_surface[size_t(face_base[size_t(cell)] + face)];
  return s < 0 ? nullptr : &lights[light].surfaces[size_t(s)];
}

const SurfaceLight* SceneShadows::on_object(size_t light, int object, int polygon) const {
  if (light >= lights.size() || object < 0 || size_t(object) + 1 >= polygon_base.size()) return nullptr;
  const int32_t g = polygon_base[size_t(object)] + polygon;
  if (polygon < 0 || g >= polygon_base[size_t(object) + 1]) return nullptr;
  const int32_t s = lights[light].polygon_surface[size_t(g)];
  return s < 0 ? nullptr : &lights[light].surfaces[size_t(s)];
}

/// What casts shadows when objects do not.
const std::vector<PlacedObject> kNoObjects;

SceneShadows cast_shadows(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                          const Lighting& lighting, Kernel kernel, bool object_shadows, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  SceneShadows out;
  int32_t faces = 0, polygons = 0;
  for (const Cell& cell : complex.cells) {
    out.face_base.push_back(faces);
    faces += int32_t(cell.faces.size());
  }
  for (const PlacedObject& o : objects) {
    out.polygon_base.push_back(polygons);
    int32_t n = 0;
    for (int g : o.mesh.polygon_of) n = std::max(n, g + 1);
    polygons += n;
  }
  out.polygon_base.push_back(polygons);
  if (lighting.at_eye) return out;
  // Each light on its own: lights are independent, so they are cast side by side.
  out.lights.resize(lighting.points.size());
  auto cast = [&](size_t index) {
    const PointLight& light = lighting.points[index];
    LightShadows& ls = out.lights[index];
    ls.face_surface.assign(size_t(faces), -1);
    ls.polygon_surface.assign(size_t(polygons), -1);
    if (light.cell == kNoCell) return;
    ls.reach = find_lit(complex, light.position, light.cell, kernel);
    LightCaster caster(complex, object_shadows ? objects : kNoObjects, light.position, ls);
    caster.prepare();
    const double tol = 1e-9 * (1 + length(light.position));
    Receiver s;
    SurfaceLight lit;
    // The faces of every cell it reaches, lit from their inner side.
    for (CellId id : ls.reach.cells) {
      const Cell& cell = complex.cells[size_t(id)];
      for (size_t k = 0; k < cell.faces.size(); ++k) {
        const Face& f = cell.faces[k];
        if (f.opaque.empty() || !(f.plane.eval(light.position) < -tol)) continue;
        s.cell = id;
        s.parts = {f.poly};
        if (!caster.light(s, lit)) continue;
        ls.face_surface[size_t(out.face_base[size_t(id)]) + k] = int32_t(ls.surfaces.size());
        ls.surfaces.push_back(std::move(lit));
      }
    }
    // The polygons of every object in a cell it reaches: the triangles facing the light
    // (every triangle of an open mesh, lit on whichever side the eye sees).
    for (size_t o = 0; o < objects.size(); ++o) {
      const PlacedObject& obj = objects[o];
      if (obj.cell == kNoCell || !ls.reach.reaches(obj.cell)) continue;
      const Mesh& m = obj.mesh;
      const int32_t count = out.polygon_base[o + 1] - out.polygon_base[o];
      std::vector<std::vector<std::vector<Vec3>>> parts(static_cast<size_t>(count));
      for (size_t t = 0; t < m.triangles.size(); ++t) {
        std::vector<Vec3> tri{m.vertices[size_t(m.triangles[t][0])], m.vertices[size_t(m.triangles[t][1])],
                              m.vertices[size_t(m.triangles[t][2])]};
        const double h = dot(newell(tri), light.position - tri[0]);
        if (m.closed ? !(h > 0) : h == 0) continue;
        parts[size_t(m.polygon_of[t])].push_back(std::move(tri));
      }
      for (int32_t g = 0; g < count; ++g) {
        if (parts[size_t(g)].empty()) continue;
        s.cell = obj.cell;
        s.object = int(o);
        s.polygon = g;
        s.parts = std::move(parts[size_t(g)]);
        if (!caster.light(s, lit)) continue;
        ls.polygon_surface[size_t(out.polygon_base[o] + g)] = int32_t(ls.surfaces.size());
        ls.surfaces.push_back(std::move(lit));
      }
      s.object = s.polygon = -1;
    }
  };
  if (lighting.points.size() > 1)
    arena_for(threads).execute([&] { tbb::parallel_for(size_t(0), lighting.points.size(), cast); });
  else if (!lighting.points.empty()) cast(0);
  out.micros = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace avenues
