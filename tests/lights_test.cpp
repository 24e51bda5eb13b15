// Tests of lights and shadows (render/lighting.h, render/shadows.h, visibility/light_reach.h,
// the secondary scan in render/scanline.h): tiny hand-made plans, each named for what it
// shows, checked in pixels against analytic shadows.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <cmath>
#include <string>
#include <vector>

#include "cells/build_cells.h"
#include "plans/plan.h"
#include "render/effects.h"
#include "render/halftone.h"
#include "render/raster_srgb.h"
#include "render/shadow_outline.h"
#include "render/view_lines.h"
#include "ray_oracle.h"
#include "test_plans.h"
#include "visibility/light_reach.h"
#include "visibility/viewpoint.h"

using namespace avenues;
using avenues::testing::room_named;
using avenues::testing::wall;

namespace {

Room room(const std::string& name, Vec2 at) {
  Room r;
  r.name = name;
  r.label = at;
  return r;
}

Light point_light(const std::string& name, Vec3 at) {
  Light l;
  l.name = name;
  l.position = at;
  return l;
}

/// A 6 m square room, 3 m high, a 1 m box on its floor at (3, 3), and a lamp at (2, 2, 2.5).
Plan box_under_a_light() {
  Plan p;
  p.name = "box under a light";
  p.far_margin = 2;
  p.storeys.push_back({"ground", 0, 3.0, 0.3, {}});
  p.walls.push_back(wall("room", {{0, 0}, {6, 0}, {6, 6}, {0, 6}, {0, 0}}, 0.2));
  p.rooms = {room("room", {1, 1})};
  Object box;
  box.name = "box";
  box.box = {1, 1, 1};
  box.position = {3, 3, 0};
  p.objects = {box};
  p.lights = {point_light("lamp", {2, 2, 2.5})};
  return p;
}

constexpr Vec3 kLamp{2, 2, 2.5};

constexpr Vec3 kDoorLamp{1.0, 1.9, 2.3};

/// Two 4 m rooms side by side, 2.5 m high; the wall between them (x = 3.9 to 4.1) has a
/// door 0.8 m wide (y = 1.5 to 2.3) and 2 m high when `door`. A lamp in the west room.
Plan two_rooms(bool door) {
  Plan p;
  p.name = door ? "light through a door" : "two rooms, no door";
  p.far_margin = 2;
  p.storeys.push_back({"ground", 0, 2.5, 0.3, {}});
  p.walls.push_back(wall("outer", {{0, 0}, {8, 0}, {8, 4}, {0, 4}, {0, 0}}, 0.2));
  Wall mid = wall("mid", {{4, 0}, {4, 4}}, 0.2);
  if (door) {
    Opening o;
    o.name = "door";
    o.at = 1.5;
    o.width = 0.8;
    o.sill = 0;
    o.head = 2.0;
    mid.openings.push_back(o);
  }
  p.walls.push_back(mid);
  p.rooms = {room("west", {2, 2}), room("east", {6, 2})};
  p.lights = {point_light("lamp", kDoorLamp)};
  return p;
}

/// Where a ray from `eye` through the centre (or corner) of a pixel meets `plane`.
bool hit(const Camera& cam, Vec2 px, const Plane& plane, Vec3& at) {
  const Vec3 d = cam.ray_through_raster(px);
  const double den = dot(plane.n, d);
  if (den == 0) return false;
  const double t = -plane.eval(cam.eye) / den;
  if (!(t > 0)) return false;
  at = cam.eye + t * d;
  return true;
}

bool inside(const std::vector<Vec2>& ccw, Vec2 q) {
  for (size_t i = 0; i < ccw.size(); ++i)
    if (cross(ccw[(i + 1) % ccw.size()] - ccw[i], q - ccw[i]) < 0) return false;
  return true;
}

/// The box's shadow on the floor from the lamp, analytically: the hull of its footprint and
/// its top corners projected from the lamp onto z = 0.
std::vector<Vec2> analytic_box_shadow() {
  std::vector<Vec2> pts;
  for (double x : {2.5, 3.5})
    for (double y : {2.5, 3.5}) {
      pts.push_back({x, y});
      const double k = kLamp.z / (kLamp.z - 1.0);  // top at z = 1
      pts.push_back({kLamp.x + k * (x - kLamp.x), kLamp.y + k * (y - kLamp.y)});
    }
  return convex_hull(pts);
}

/// A grey picture of the view lit by the plan's lights, with its item buffer.
struct Shot {
  Camera cam;
  ScreenScene scene;
  Image picture;
  std::vector<int32_t> items;
};

Shot shoot(const CellComplex& c, const Camera& cam, int threads = 0) {
  const VisibleSet vs = find_visible(c, cam, c.locate(cam.eye).cell);
  const std::vector<PlacedObject> objects = place_objects(c);
  HalftoneOptions o;
  o.colour = false;
  o.threads = threads;
  const SceneEffects e = prepare_effects(c, objects, o);
  SceneOptions so = scene_options(o);
  so.lighting = &e.plan.lighting;
  so.shadows = &e.shadows;
  Shot s{cam, screen_scene_of_view(c, objects, cam, vs, so), {}, {}};
  render_scene(s.scene, o, s.picture, nullptr, &s.items);
  return s;
}

/// The grey code of a surface of the default material in ambient light only (BACK = 0.1).
uint8_t unlit_code() { return srgb_encoder()(float(0.8 * 0.1)); }

/// Compares a shot's pixels on the faces `wanted` says with `lit(P)`; pixels whose centre
/// and corners disagree analytically (the outline runs through them) are left out.
struct Tally {
  long lit = 0, dark = 0, wrong = 0, boundary = 0;
};
template <class Wanted, class Lit>
Tally compare(const CellComplex& c, const Shot& s, Wanted wanted, Lit lit) {
  Tally t;
  const uint8_t dark = unlit_code();
  for (int y = 0; y < s.cam.height; ++y)
    for (int x = 0; x < s.cam.width; ++x) {
      const int32_t p = s.items[size_t(y) * size_t(s.cam.width) + size_t(x)];
      if (p < 0) continue;
      const PolygonSource& src = s.scene.sources[size_t(p)];
      if (src.kind != PolygonSource::Kind::Face || !wanted(src)) continue;
      const Plane& plane = c.cells[size_t(src.cell)].faces[size_t(src.face)].plane;
      Vec3 at;
      if (!hit(s.cam, {x + 0.5, y + 0.5}, plane, at)) continue;
      const bool expect = lit(at, plane);
      bool straddles = false;
      for (double dx : {0.0, 1.0})
        for (double dy : {0.0, 1.0}) {
          Vec3 corner;
          straddles |= !hit(s.cam, {x + dx, y + dy}, plane, corner) || lit(corner, plane) != expect;
        }
      if (straddles) {
        ++t.boundary;
        continue;
      }
      const bool measured = s.picture.row(y)[x] > dark + 2;  // above the ambient level (rounding aside)
      (expect ? t.lit : t.dark) += 1;
      if (measured != expect) ++t.wrong;
    }
  return t;
}

}  // namespace

// --- lights in plans --------------------------------------------------------------------

TEST(Lights, PlansCarryPointAndAmbientLights) {
  const Plan p = parse_plan(
      "name = 'lit'\n"
      "[[storey]]\nname = 'g'\nheight = 3\n"
      "[[wall]]\npath = [[0, 0], [4, 0], [4, 4], [0, 4], [0, 0]]\n"
      "[[room]]\nname = 'r'\nat = [2, 2]\n"
      "[[light]]\nname = 'lamp'\nposition = [2, 2, 2]\ncolour = [1, 0.5, 0.25]\n"
      "[[light]]\nname = 'sky'\nkind = 'ambient'\nintensity = 0.2\n",
      "lit.toml");
  ASSERT_EQ(p.lights.size(), 2u);
  EXPECT_EQ(p.lights[0].kind, LightKind::Point);
  EXPECT_EQ(p.lights[1].kind, LightKind::Ambient);
  EXPECT_DOUBLE_EQ(p.lights[1].intensity, 0.2);
  const CellComplex c = build_cells(p);
  const Lighting l = lighting_of(c, Shading{}, Lights::Plan, false, true);
  EXPECT_FALSE(l.at_eye);
  ASSERT_EQ(l.points.size(), 1u);
  EXPECT_NE(l.points[0].cell, kNoCell);
  EXPECT_TRUE(l.coloured);
  EXPECT_FLOAT_EQ(l.ambient[0], 0.2f);
  EXPECT_FLOAT_EQ(l.diffuse, 0.8f);
  // Grey pictures and the light at the eye carry no colour; Eye ignores the point lights.
  EXPECT_FALSE(lighting_of(c, Shading{}, Lights::Plan, false, false).coloured);
  EXPECT_TRUE(lighting_of(c, Shading{}, Lights::Eye, false, true).at_eye);
}

TEST(Lights, BadLightsNameFileAndElement) {
  auto fails = [](const std::string& light, const std::string& says) {
    try {
      parse_plan("name = 'x'\n[[storey]]\nname = 'g'\n[[wall]]\npath = [[0, 0], [4, 0]]\n[[light]]\nname = 'l'\n" + light,
                 "x.toml");
      ADD_FAILURE() << "accepted " << light;
    } catch (const PlanError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("x.toml"), std::string::npos) << what;
      EXPECT_NE(what.find("light 'l'"), std::string::npos) << what;
      EXPECT_NE(what.find(says), std::string::npos) << what;
    }
  };
  fails("kind = 'spot'\nposition = [0, 0, 1]\n", "unknown light kind 'spot'");
  fails("kind = 'ambient'\nposition = [0, 0, 1]\n", "has no 'position'");
  fails("kind = 'ambient'\nintensity = 2\n", "at most 1");
  fails("intensity = 1\n", "position");
}

TEST(Lights, LambertsCosineFromALightAwayFromTheEye) {
  // A plane z = 0 seen from the eye above; a light 1 m above the point (0, 0): at the foot
  // cos φ = 1, at 1 m off it cos φ = 1/√2, and a light below the plane lights nothing seen.
  Material m;
  m.reflectance = 1;
  Lighting lighting;
  lighting.at_eye = false;
  lighting.ambient = {0, 0, 0};
  lighting.diffuse = 1;
  PointLight lamp;
  const Vec3 n{0, 0, 1};
  const double d = 2;  // camera space: the eye at the origin, the plane z = −2 ... n·P + 2 = 0
  LightTerm t;
  ASSERT_TRUE(planar_light_term(m, n, d, {0, 0, -2}, {0, 0, -1}, lamp, lighting, false, t));
  EXPECT_NEAR(t.diffuse, 1.0, 1e-6);
  ASSERT_TRUE(planar_light_term(m, n, d, {1, 0, -2}, {0, 0, -1}, lamp, lighting, false, t));
  EXPECT_NEAR(t.diffuse, 1 / std::sqrt(2.0), 1e-6);
  EXPECT_FALSE(planar_light_term(m, n, d, {0, 0, -2}, {0, 0, -3}, lamp, lighting, false, t));
  // Distance falloff only when asked: Wylie's law (r0 / r)² beyond r0.
  lighting.falloff = true;
  lighting.falloff_start = 0.5;
  ASSERT_TRUE(planar_light_term(m, n, d, {0, 0, -2}, {0, 0, -1}, lamp, lighting, false, t));
  EXPECT_NEAR(t.diffuse, 0.25, 1e-6);
}

// --- what a light reaches ------------------------------------------------------------------

TEST(LightReach, NoLightReachesACellWithNoPortalPathToTheLight) {
  const CellComplex c = build_cells(two_rooms(false));
  const LightReach r = find_lit(c, kDoorLamp, c.locate(kDoorLamp).cell);
  const RoomId west = room_named(c, "west"), east = room_named(c, "east");
  ASSERT_GE(west, 0);
  ASSERT_GE(east, 0);
  bool lit_west = false;
  for (CellId id : r.cells) {
    EXPECT_NE(c.cells[size_t(id)].room, east) << "light leaked through the wall into cell " << id;
    lit_west |= c.cells[size_t(id)].room == west;
  }
  EXPECT_TRUE(lit_west);
  // And in the picture: every pixel of the east room is at the ambient level.
  const Shot s = shoot(c, Camera::look_at({7.5, 0.6, 2.0}, {4.5, 2.5, 0.5}, 80, 96, 72));
  const Tally t = compare(
      c, s, [&](const PolygonSource& src) { return c.cells[size_t(src.cell)].room == east; },
      [](Vec3, const Plane&) { return false; });
  EXPECT_GT(t.dark, 1000);
  EXPECT_EQ(t.wrong, 0);
  EXPECT_EQ(t.lit, 0);
}

TEST(LightReach, ThroughADoorTheConeIsTheDoorway) {
  const CellComplex c = build_cells(two_rooms(true));
  const LightReach r = find_lit(c, kDoorLamp, c.locate(kDoorLamp).cell);
  const RoomId east = room_named(c, "east");
  bool through = false;
  for (const LightPath& p : r.paths) {
    if (c.cells[size_t(p.cell)].room != east) continue;
    through = true;
    ASSERT_GE(p.window.size(), 3u);
    // The window lies in the door's plane on the east face of the wall, inside the door.
    for (Vec3 w : p.window) {
      EXPECT_GE(w.y, 1.5 - 1e-9);
      EXPECT_LE(w.y, 2.3 + 1e-9);
      EXPECT_LE(w.z, 2.0 + 1e-9);
    }
  }
  EXPECT_TRUE(through);
  EXPECT_EQ(r.paths[0].cell, c.locate(kDoorLamp).cell);
  EXPECT_TRUE(r.paths[0].window.empty());
}

// --- shadows in pixels -------------------------------------------------------------------

/// The floor of a box_under_a_light() plan (its lamps all at kLamp), seen from above a
/// corner: lit but in the box's analytic shadow, pixel by pixel.
void expect_the_box_shadow_on_the_floor(const Plan& p) {
  const CellComplex c = build_cells(p);
  const std::vector<Vec2> shadow = analytic_box_shadow();
  const Shot s = shoot(c, Camera::look_at({5.6, 5.6, 2.7}, {3.0, 3.0, 0.0}, 70, 200, 150));
  const Tally t = compare(
      c, s, [&](const PolygonSource& src) { return c.cells[size_t(src.cell)].faces[size_t(src.face)].plane.n.z < -0.99; },
      [&](Vec3 at, const Plane&) { return !inside(shadow, {at.x, at.y}); });
  EXPECT_GT(t.dark, 500) << "the shadow is in view";
  EXPECT_GT(t.lit, 2000);
  EXPECT_EQ(t.wrong, 0) << t.lit << " lit, " << t.dark << " in shadow, " << t.boundary << " on the outline";
}

TEST(Shadows, ABoxUnderALampShadowsItsProjectionOnTheFloor) { expect_the_box_shadow_on_the_floor(box_under_a_light()); }

TEST(Shadows, SeventyLampsInOnePlaceCastOneShadow) {
  // The half-tone keeps each light's state as a bit, 64 lights a word: the 70 lamps' terms
  // take two words. Every lamp's shadow is the box's one shadow, which none lights.
  Plan p = box_under_a_light();
  p.lights.clear();
  for (int k = 0; k < 70; ++k) p.lights.push_back(point_light("lamp " + std::to_string(k), kLamp));
  expect_the_box_shadow_on_the_floor(p);
}

TEST(Shadows, LightThroughADoorIsTheDoorwaysProjection) {
  const CellComplex c = build_cells(two_rooms(true));
  const RoomId east = room_named(c, "east");
  // Lit in the east room: in front of the face, and the segment from the lamp passes the
  // doorway on both faces of the wall (x = 3.9 and 4.1), y in [1.5, 2.3], z in [0, 2].
  auto lit = [](Vec3 p, const Plane& face) {
    if (!(face.eval(kDoorLamp) < 0)) return false;
    for (double x : {3.9, 4.1}) {
      const double t = (x - kDoorLamp.x) / (p.x - kDoorLamp.x);
      const Vec3 q = kDoorLamp + t * (p - kDoorLamp);
      if (q.y < 1.5 || q.y > 2.3 || q.z < 0 || q.z > 2.0) return false;
    }
    return true;
  };
  const Shot s = shoot(c, Camera::look_at({7.5, 0.4, 2.2}, {5.5, 2.5, 0.2}, 80, 200, 150));
  const Tally t = compare(
      c, s, [&](const PolygonSource& src) { return c.cells[size_t(src.cell)].room == east; }, lit);
  EXPECT_GT(t.lit, 300) << "the patch of light is in view";
  EXPECT_GT(t.dark, 2000);
  EXPECT_EQ(t.wrong, 0) << t.lit << " lit, " << t.dark << " dark, " << t.boundary << " on the outline";
}

TEST(Shadows, ACurvedMeshUnderALampIsLitOnTheSideFacingIt) {
  // Smooth: Gouraud from the vertex normals, turned to the side the eye sees. A torus lying
  // under the lamp, seen from above: most of what the eye sees of it faces the lamp and is lit.
  Plan p = box_under_a_light();
  Object torus;
  torus.name = "torus";
  torus.mesh = avenues::testing::plan_path("scenes/torus.off");
  torus.position = {2, 2, 0.6};
  torus.scale = {0.3, 0.3, 0.3};
  p.objects = {torus};
  const CellComplex c = build_cells(p);
  const Camera cam = Camera::look_at({3.2, 3.2, 2.6}, {2, 2, 0.6}, 50, 160, 120);
  const VisibleSet vs = find_visible(c, cam, c.locate(cam.eye).cell);
  const std::vector<PlacedObject> objects = place_objects(c);
  HalftoneOptions o;
  o.colour = false;
  o.shading.model = ShadingModel::Smooth;
  const SceneEffects e = prepare_effects(c, objects, o);
  SceneOptions so = scene_options(o);
  so.shading = e.plan.shading;
  so.lighting = &e.plan.lighting;
  so.shadows = &e.shadows;
  const ScreenScene scene = screen_scene_of_view(c, objects, cam, vs, so);
  long gouraud = 0;
  for (const LightTerm& t : scene.light_terms) gouraud += t.kind == LightTerm::Kind::Gouraud;
  EXPECT_GT(gouraud, 100);
  Image im;
  std::vector<int32_t> items;
  render_scene(scene, o, im, nullptr, &items);
  long seen = 0, lit = 0;
  for (size_t i = 0; i < items.size(); ++i) {
    if (items[i] < 0 || scene.sources[size_t(items[i])].kind != PolygonSource::Kind::Object) continue;
    ++seen;
    lit += im.data[i] > unlit_code() + 2;
  }
  EXPECT_GT(seen, 1000);
  EXPECT_GT(lit, seen / 2) << lit << " of " << seen;
}

TEST(Shadows, TheSamePictureOnAnyNumberOfThreads) {
  const CellComplex c = build_cells(box_under_a_light());
  const Camera cam = Camera::look_at({5.6, 5.6, 2.7}, {3.0, 3.0, 0.0}, 70, 160, 120);
  EXPECT_EQ(shoot(c, cam, 1).picture.data, shoot(c, cam, 2).picture.data);
}

TEST(Shadows, AShadowPolygonIsTheSurfaceCutToTheShadowVolume) {
  // A unit square 1 m under a light, 1 m above a floor: its shadow is the square doubled.
  const std::vector<Vec3> floor{{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
  const std::vector<Vec3> square{{-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0.5, 0.5, 1}, {-0.5, 0.5, 1}};
  const std::vector<Vec3> sh = shadow_on(floor, square, {0, 0, 2});
  ASSERT_EQ(sh.size(), 4u);
  for (Vec3 v : sh) {
    EXPECT_NEAR(std::fabs(v.x), 1.0, 1e-12);
    EXPECT_NEAR(std::fabs(v.y), 1.0, 1e-12);
    EXPECT_NEAR(v.z, 0.0, 1e-12);
  }
  EXPECT_TRUE(shadow_on(floor, square, {0, 0, 0.5}).empty()) << "the light below the occluder";
  EXPECT_TRUE(shadow_on(floor, square, {0, 0, 1}).empty()) << "the light in the occluder's plane";
}

TEST(Shadows, AnOccluderOfNoAreaCastsNoShadow) {
  // Models hold triangles whose corners lie in a line (Sweet Home's Studio has hundreds).
  // Their three side planes are one plane, so a shadow volume built from them was half of
  // space: the whole floor on one side of the line fell in shadow.
  const std::vector<Vec3> floor{{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
  const std::vector<Vec3> line{{-0.5, 0, 1}, {0, 0, 1}, {0.5, 0, 1}};
  const std::vector<Vec3> nearly{{-0.5, 0, 1}, {0, 1e-13, 1}, {0.5, 0, 1}};
  for (Vec3 light : {Vec3{0.3, 0.2, 2}, Vec3{-1, 3, 1.5}, Vec3{2, -2, 4}}) {
    EXPECT_TRUE(shadow_on(floor, line, light).empty()) << light.x << " " << light.y << " " << light.z;
    EXPECT_TRUE(shadow_on(floor, nearly, light).empty()) << light.x << " " << light.y << " " << light.z;
  }
  // A thin triangle that has an area still casts its thin shadow.
  const std::vector<Vec3> thin{{-0.5, 0, 1}, {0, 1e-3, 1}, {0.5, 0, 1}};
  const std::vector<Vec3> sh = shadow_on(floor, thin, {0, 0, 2});
  ASSERT_GE(sh.size(), 3u);
  EXPECT_NEAR(polygon_area(sh), 4 * 0.5e-3, 1e-9);
}

// --- shadow outlines in drawings -----------------------------------------------------------

TEST(ShadowOutlines, TheBoxsShadowOutlineIsItsAnalyticOutline) {
  const CellComplex c = build_cells(box_under_a_light());
  const std::vector<PlacedObject> objects = place_objects(c);
  const Lighting lighting = lighting_of(c, Shading{}, Lights::Plan, false, false);
  const SceneShadows shadows = cast_shadows(c, objects, lighting);
  const std::vector<Vec2> want = analytic_box_shadow();
  double perimeter = 0;
  for (size_t i = 0; i < want.size(); ++i) perimeter += length(want[(i + 1) % want.size()] - want[i]);
  double drawn = 0;
  int floors = 0;
  for (size_t id = 0; id < c.cells.size(); ++id)
    for (size_t k = 0; k < c.cells[id].faces.size(); ++k) {
      const Face& f = c.cells[id].faces[k];
      const SurfaceLight* s = shadows.on_face(0, CellId(id), int(k));
      if (!s || f.plane.n.z > -0.99) continue;  // floors: outward normal down
      ++floors;
      for (const auto& e : shadow_outline(f.poly, *s)) {
        drawn += length(e[1] - e[0]);
        // Every piece lies on the analytic outline.
        for (Vec3 p : {e[0], e[1], 0.5 * (e[0] + e[1])}) {
          double nearest = HUGE_VAL;
          for (size_t i = 0; i < want.size(); ++i) {
            const Vec2 a = want[i], b = want[(i + 1) % want.size()];
            const double t = std::clamp(dot(Vec2{p.x, p.y} - a, b - a) / dot(b - a, b - a), 0.0, 1.0);
            nearest = std::min(nearest, length(Vec2{p.x, p.y} - (a + t * (b - a))));
          }
          EXPECT_LT(nearest, 1e-9);
          EXPECT_NEAR(p.z, 0.0, 1e-9);
        }
      }
    }
  EXPECT_GE(floors, 1);
  EXPECT_NEAR(drawn, perimeter, 1e-6) << "the whole outline, once";
  // In a drawing: an optional layer, there only when asked.
  LineOptions lo;
  const Camera cam = Camera::look_at({5.6, 5.6, 2.7}, {3.0, 3.0, 0.0}, 70, 200, 150);
  const VisibleSet vs = find_visible(c, cam, c.locate(cam.eye).cell);
  auto shadow_strokes = [&](const Drawing& d) {
    return std::count_if(d.strokes.begin(), d.strokes.end(), [](const Stroke& s) { return s.layer == Layer::Shadows; });
  };
  EXPECT_EQ(shadow_strokes(draw_view(c, prepare_line_scene(c), cam, vs, lo)), 0);
  lo.shadows = true;
  EXPECT_GT(shadow_strokes(draw_view(c, prepare_line_scene(c, lo), cam, vs, lo)), 2);
}

// A lamp's light on a face is the union of the pieces its avenues through the portals cut
// from it (shadows.h), each rounded to the raster on its own. Where two pieces meet, a
// sample centred on their seam fell in neither when each was exactly its own polygon: the
// bundled plans' own views showed 2 to 4 single dark samples inside lit floors and walls
// (curved-walls' floor lit through the rotunda's door, Jones's house). Every sample of a
// face is here checked against rays from the lamps (the ray oracle: no cells, no
// portals): the samples a face shows lit by the same lamps, away from where that changes,
// are all of one value.
TEST(Shadows, NoSampleInsideALampsLightOnAFaceIsLeftDark) {
  for (const char* name : {"curved-walls.toml", "jones-house.toml", "office-corridor.toml", "two-storey-house.toml"}) {
    SCOPED_TRACE(name);
    const CellComplex c = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/" + name));
    const Viewpoint vp = default_viewpoint(c);
    const Camera cam = Camera::look_at(vp.eye, vp.look, vp.fov_deg, 1920, 1080);
    const Shot s = shoot(c, cam);
    const Lighting lighting = lighting_of(c, Shading{}, Lights::Plan, false, true);
    ASSERT_FALSE(lighting.points.empty());
    ASSERT_LE(lighting.points.size(), 32u);
    const avenues::testing::OracleIndex index(c);
    // Per pixel: the lamps whose light reaches the point its centre sees (bits), or ~0 when
    // it shows no face of a cell lit in pieces.
    constexpr uint32_t kNotChecked = ~uint32_t(0);
    std::vector<uint32_t> reached(s.items.size(), kNotChecked);
    long checked = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const size_t i = size_t(y) * size_t(cam.width) + size_t(x);
        const int32_t p = s.items[i];
        if (p < 0 || s.scene.sources[size_t(p)].kind != PolygonSource::Kind::Face) continue;
        const SurfaceShade& shade = s.scene.shades[size_t(p)];
        bool pieced = false;
        for (int t = 0; t < shade.terms; ++t) pieced |= s.scene.light_terms[size_t(shade.first_term + t)].needs_scan();
        if (!pieced) continue;
        const PolygonSource& src = s.scene.sources[size_t(p)];
        const Plane& plane = c.cells[size_t(src.cell)].faces[size_t(src.face)].plane;
        Vec3 at;
        if (!hit(s.cam, {x + 0.5, y + 0.5}, plane, at)) continue;
        uint32_t bits = 0;
        for (size_t k = 0; k < lighting.points.size(); ++k) {
          const Vec3 lamp = lighting.points[k].position;
          if (plane.eval(lamp) >= 0) continue;  // behind the face (faces' normals point out of their cells)
          if (index.first_hit(lamp, at - lamp) > 1 - 1e-6) bits |= uint32_t(1) << k;
        }
        reached[i] = bits;
        ++checked;
      }
    // Each (polygon, lamps reached) is one value, away from where the lamps reached change
    // (a pixel whose neighbour on the same polygon is reached by other lamps).
    std::map<std::pair<int32_t, uint32_t>, std::map<uint8_t, long>> values;
    for (int y = 1; y + 1 < cam.height; ++y)
      for (int x = 1; x + 1 < cam.width; ++x) {
        const size_t i = size_t(y) * size_t(cam.width) + size_t(x);
        if (reached[i] == kNotChecked) continue;
        bool edge = false;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const size_t j = size_t(y + dy) * size_t(cam.width) + size_t(x + dx);
            edge |= s.items[j] == s.items[i] && reached[j] != reached[i];
          }
        if (!edge) ++values[{s.items[i], reached[i]}][s.picture.row(y)[x]];
      }
    EXPECT_GT(checked, 20000) << "faces lit in pieces are in view";
    for (const auto& [key, counts] : values) {
      std::ostringstream seen;
      for (const auto& [v, n] : counts) seen << ' ' << n << " of " << int(v) << ';';
      EXPECT_EQ(counts.size(), 1u) << "polygon " << key.first << ", lamps " << key.second << ":" << seen.str();
    }
  }
}

// A walkthrough renders every frame into one FrameStorage (halftone.h): whatever the frame
// before it left there (more polygons, another size, lights' pieces or none), each frame is
// the picture a fresh render makes, byte for byte, on one thread or two.
TEST(FrameStorage, EachFrameIsThePictureAFreshRenderMakes) {
  const CellComplex lit = build_cells(box_under_a_light());
  const CellComplex furnished = build_cells(read_plan(std::string(AVENUES_SOURCE_DIR) + "/plans/furnished-room.toml"));
  const Viewpoint vp = default_viewpoint(furnished);
  struct Frame {
    const CellComplex* complex;
    Camera cam;
  };
  const std::vector<Frame> frames{
      {&lit, Camera::look_at({5.6, 5.6, 2.7}, {3.0, 3.0, 0.0}, 70, 160, 120)},
      {&furnished, Camera::look_at(vp.eye, vp.look, vp.fov_deg, 320, 180)},
      {&lit, Camera::look_at({0.5, 5.5, 1.6}, {3.0, 3.0, 0.5}, 60, 200, 100)},
      {&furnished, Camera::look_at(vp.eye, vp.look, vp.fov_deg, 96, 54)},
      {&lit, Camera::look_at({5.6, 5.6, 2.7}, {3.0, 3.0, 0.0}, 70, 160, 120)},
  };
  for (int threads : {1, 2}) {
    SCOPED_TRACE(threads);
    HalftoneOptions o;
    o.threads = threads;
    o.samples = 4;
    FrameStorage storage;
    for (size_t k = 0; k < frames.size(); ++k) {
      SCOPED_TRACE(k);
      const CellComplex& c = *frames[k].complex;
      const Camera& cam = frames[k].cam;
      const std::vector<PlacedObject> objects = place_objects(c);
      const SceneEffects effects = prepare_effects(c, objects, o);
      const VisibleSet vs = find_visible(c, cam, c.locate(cam.eye).cell);
      Image fresh, reused;
      RenderStats fresh_stats, reused_stats;
      render_view(c, objects, effects, cam, vs, o, fresh, &fresh_stats);
      render_view(c, objects, effects, cam, vs, o, reused, storage, &reused_stats);
      ASSERT_EQ(fresh.width, cam.width);
      EXPECT_EQ(reused.width, fresh.width);
      EXPECT_EQ(reused.height, fresh.height);
      EXPECT_TRUE(reused.data == fresh.data);
      EXPECT_EQ(reused_stats.polygons, fresh_stats.polygons);
      EXPECT_EQ(reused_stats.spans, fresh_stats.spans);
      EXPECT_EQ(reused_stats.pixels, fresh_stats.pixels);
      EXPECT_EQ(reused_stats.light_pieces, fresh_stats.light_pieces);
      EXPECT_GT(fresh_stats.polygons, 0);
    }
  }
}
