// Tests of effects on demand (render/effects.h, render/interpenetration.h): which stages a
// scene calls for and why, what `avenues view --explain` says, and that a scene which calls
// for none renders exactly as the bare pipeline did.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "cells/build_cells.h"
#include "plans/plan.h"
#include "render/effects.h"
#include "render/halftone.h"
#include "render/interpenetration.h"
#include "test_plans.h"
#include "visibility/viewpoint.h"

using namespace avenues;
using avenues::testing::plan_path;
using avenues::testing::wall;

namespace {

/// A 6 m square room, 3 m high, with the objects and lights given.
Plan room_with(std::vector<Object> objects, std::vector<Light> lights) {
  Plan p;
  p.name = "room";
  p.far_margin = 2;
  p.storeys.push_back({"ground", 0, 3.0, 0.3, {}});
  p.walls.push_back(wall("room", {{0, 0}, {6, 0}, {6, 6}, {0, 6}, {0, 0}}, 0.2));
  Room r;
  r.name = "room";
  r.label = Vec2{1, 1};
  p.rooms = {r};
  p.objects = std::move(objects);
  p.lights = std::move(lights);
  return p;
}

Object box(const std::string& name, Vec3 at, Vec3 size = {1, 1, 1}) {
  Object o;
  o.name = name;
  o.box = size;
  o.position = at;
  return o;
}

Object torus(Vec3 at) {
  Object o;
  o.name = "torus";
  o.mesh = plan_path("scenes/torus.off");
  o.position = at;
  o.scale = {0.3, 0.3, 0.3};
  return o;
}

Light lamp(std::array<double, 3> colour = {1, 1, 1}) {
  Light l;
  l.name = "lamp";
  l.position = {2, 2, 2.5};
  l.colour = colour;
  return l;
}

/// The explanation's line for one effect.
std::string line(const std::string& text, const std::string& effect) {
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (l.rfind(effect + ": ", 0) == 0) return l;
  return "(no line for " + effect + ")";
}

std::string explain(const Plan& p, HalftoneOptions o = {}) {
  const CellComplex c = build_cells(p);
  return explain_effects(prepare_effects(c, place_objects(c), o).plan);
}

}  // namespace

TEST(Effects, ABareRoomCallsForNothing) {
  const std::string e = explain(room_with({}, {}));
  EXPECT_EQ(line(e, "depth"),
            "depth: off \u2014 no object stands in any cell, and the faces of a convex cell never hide each other");
  EXPECT_EQ(line(e, "implicit lines"), "implicit lines: off \u2014 no objects: the faces of convex cells never cross");
  EXPECT_EQ(line(e, "shadows"), "shadows: off \u2014 the plan has no light away from the eye");
  EXPECT_EQ(line(e, "object shadows"), "object shadows: off \u2014 no shadows");
  EXPECT_EQ(line(e, "smooth shading"), "smooth shading: off \u2014 flat shading asked (Bouknight)");
  EXPECT_EQ(line(e, "distance falloff"), "distance falloff: off \u2014 flat shading has no distance law");
  EXPECT_EQ(line(e, "coloured light"), "coloured light: off \u2014 the light at the eye is white");
  EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 7);
}

TEST(Effects, DepthOnlyWhereObjectsStandAndImplicitLinesOnlyWhereTheyCross) {
  // A box resting on the floor touches it but does not cross it.
  std::string e = explain(room_with({box("crate", {3, 3, 0})}, {}));
  EXPECT_EQ(line(e, "depth"), "depth: on \u2014 1 object in 1 cell: depth is sorted in those cells only");
  EXPECT_EQ(line(e, "implicit lines").rfind("implicit lines: off \u2014 no two polygons interpenetrate (", 0), 0u) << e;
  // Two boxes through each other; a box sunk into the floor.
  e = explain(room_with({box("a", {2, 2, 0}), box("b", {2.5, 2.4, 0.3})}, {}));
  EXPECT_EQ(line(e, "implicit lines"), "implicit lines: on \u2014 object 'a' and object 'b' cross");
  e = explain(room_with({box("sunk", {3, 3, -0.2})}, {}));
  EXPECT_EQ(line(e, "implicit lines"), "implicit lines: on \u2014 object 'sunk' and a face of its cell cross");
}

TEST(Effects, ShadowsOnlyForLightsAwayFromTheEye) {
  std::string e = explain(room_with({box("crate", {3, 3, 0})}, {lamp()}));
  EXPECT_EQ(line(e, "shadows").rfind("shadows: on \u2014 1 point light away from the eye ('lamp'): 'lamp' reaches 1 cell, "
                                     "objects cast ", 0), 0u) << e;
  HalftoneOptions eye;
  eye.lights = Lights::Eye;
  e = explain(room_with({}, {lamp()}), eye);
  EXPECT_EQ(line(e, "shadows"),
            "shadows: off \u2014 lit from the eye only, as asked (the plan's 1 point light is not used)");
}

TEST(Effects, ObjectsCastShadowsWhereTheirCostIsSmallOrWhenAsked) {
  // One crate (12 triangles) under one lamp: auto casts its shadow.
  const Plan one = room_with({box("crate", {3, 3, 0})}, {lamp()});
  std::string e = explain(one);
  EXPECT_EQ(line(e, "object shadows"),
            "object shadows: on \u2014 12 object triangles under 1 point light, at most 20000 triangle-lights")
      << e;
  HalftoneOptions off;
  off.object_shadows = ObjectShadows::Off;
  e = explain(one, off);
  EXPECT_EQ(line(e, "object shadows"), "object shadows: off \u2014 asked off (12 object triangles under 1 point light)");
  EXPECT_EQ(line(e, "shadows").find("objects cast"), std::string::npos) << e;
  HalftoneOptions on;
  on.object_shadows = ObjectShadows::On;
  EXPECT_EQ(line(explain(one, on), "object shadows"),
            "object shadows: on \u2014 asked (12 object triangles under 1 point light)");
  // A furnished home's worth: 1,700 small crates under a lamp are over what auto casts.
  std::vector<Object> crates;
  for (int i = 0; i < 1700; ++i)
    crates.push_back(box("crate " + std::to_string(i), {0.4 + 0.13 * (i % 40), 0.4 + 0.12 * (i / 40), 0}, {0.1, 0.1, 0.1}));
  const CellComplex c = build_cells(room_with(crates, {lamp()}));
  const SceneEffects fx = prepare_effects(c, place_objects(c), HalftoneOptions{});
  EXPECT_FALSE(fx.plan.object_shadows.on);
  EXPECT_EQ(fx.plan.object_shadows.why,
            "20400 object triangles under 1 point light: 20400 triangle-lights, over the 20000 that auto casts "
            "(seconds of cutting); --object-shadows on casts them");
  ASSERT_EQ(fx.shadows.lights.size(), 1u);
  EXPECT_EQ(fx.shadows.lights[0].occluders, 0);
  EXPECT_EQ(fx.shadows.lights[0].shadow_polygons, 0);
  // The room and the crates are still lit by the lamp: the walls' shadows do not need the objects'.
  EXPECT_GT(fx.shadows.lights[0].surfaces.size(), 1700u);
}

TEST(Effects, SmoothShadingOnlyForCurvedMeshesUnlessForced) {
  HalftoneOptions o;
  o.shading.model = ShadingModel::Auto;
  EXPECT_EQ(line(explain(room_with({box("crate", {3, 3, 0})}, {}), o), "smooth shading"),
            "smooth shading: off \u2014 no curved mesh: every polygon is planar, and flat shading lights a plane exactly");
  EXPECT_EQ(line(explain(room_with({torus({3, 3, 1})}, {}), o), "smooth shading"),
            "smooth shading: on \u2014 1 curved mesh ('torus'): Gouraud on their curved polygons, flat elsewhere");
  o.shading.model = ShadingModel::Smooth;
  EXPECT_EQ(line(explain(room_with({}, {}), o), "smooth shading"),
            "smooth shading: on \u2014 smooth shading asked (Wylie), on every polygon");
}

TEST(Effects, FalloffAndColouredLightOnlyWhenAsked) {
  HalftoneOptions o;
  o.shading.model = ShadingModel::Smooth;
  EXPECT_EQ(line(explain(room_with({}, {}), o), "distance falloff"),
            "distance falloff: on \u2014 Wylie's law from the eye beyond 5 m (inverse square)");
  EXPECT_EQ(line(explain(room_with({}, {lamp()}), o), "distance falloff"),
            "distance falloff: on \u2014 Wylie's law from each light beyond 5 m (inverse square)");
  o.shading.falloff_start = 0;
  EXPECT_EQ(line(explain(room_with({}, {lamp()}), o), "distance falloff"),
            "distance falloff: off \u2014 no falloff distance given");
  HalftoneOptions colour;
  EXPECT_EQ(line(explain(room_with({}, {lamp()}), colour), "coloured light"),
            "coloured light: off \u2014 every light is white");
  EXPECT_EQ(line(explain(room_with({}, {lamp({1, 0.5, 0.25})}), colour), "coloured light"),
            "coloured light: on \u2014 light 'lamp' is coloured (1, 0.5, 0.25)");
  colour.colour = false;
  EXPECT_EQ(line(explain(room_with({}, {lamp({1, 0.5, 0.25})}), colour), "coloured light"),
            "coloured light: off \u2014 the picture is grey");
}

TEST(Effects, ColouredLightTintsThePicture) {
  // A red lamp: the lit floor is redder than it is green; a white lamp leaves it grey.
  for (bool red : {false, true}) {
    const CellComplex c = build_cells(room_with({}, {lamp(red ? std::array<double, 3>{1, 0.2, 0.2} : std::array<double, 3>{1, 1, 1})}));
    const Camera cam = Camera::look_at({5, 5, 2.5}, {3, 3, 0}, 60, 64, 48);
    RenderStats st;
    const Image im = render_view(c, cam, find_visible(c, cam, c.locate(cam.eye).cell), {}, &st);
    const uint8_t* px = im.row(24) + 3 * 32;
    if (red) {
      EXPECT_GT(px[0], px[1] + 20);
    } else {
      EXPECT_EQ(px[0], px[1]);
      EXPECT_EQ(px[1], px[2]);
    }
  }
}

TEST(Effects, TrianglesCrossOnlyWhenTheyPassThroughEachOther) {
  const std::array<Vec3, 3> flat{{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}}};
  const std::array<Vec3, 3> through{{{0.5, 0.5, -1}, {0.5, 0.5, 1}, {1.5, 0.2, 0}}};
  const std::array<Vec3, 3> standing{{{0.5, 0.5, 0}, {0.9, 0.5, 0}, {0.5, 0.5, 1}}};  // an edge on the plane
  const std::array<Vec3, 3> above{{{0, 0, 0.5}, {2, 0, 0.5}, {0, 2, 1}}};
  const std::array<Vec3, 3> beside{{{3, 3, -1}, {3, 3, 1}, {4, 3, 0}}};  // crosses the plane, not the triangle
  EXPECT_TRUE(triangles_cross(flat, through, 1e-9));
  EXPECT_FALSE(triangles_cross(flat, standing, 1e-9)) << "touching is not crossing";
  EXPECT_FALSE(triangles_cross(flat, above, 1e-9));
  EXPECT_FALSE(triangles_cross(flat, beside, 1e-9));
  EXPECT_FALSE(triangles_cross(flat, flat, 1e-9)) << "coplanar";
}

// The default picture — no lights but the eye — is byte for byte what the bare pipeline
// (HalftoneOptions::plan_effects = false: every stage as it was before effects were planned)
// makes, whether or not the scene has objects, flat or smooth, one sample or four; and where
// the plan skips the implicit-line search it saves depth sorts.
TEST(Effects, TheDefaultPictureIsUnchangedByteForByte) {
  std::vector<CellComplex> scenes;
  for (const char* name : {"jones-house.toml", "furnished-room.toml", "office-corridor.toml"}) {
    CellComplex c = build_cells(read_plan(plan_path(name)));
    c.lights.clear();
    scenes.push_back(std::move(c));
  }
  scenes.push_back(build_cells(room_with({box("a", {2, 2, 0}), box("b", {3.5, 3.5, 0}, {0.6, 1.2, 2})}, {})));
  scenes.push_back(build_cells(room_with({box("a", {2, 2, 0}), box("b", {2.5, 2.4, 0.3})}, {})));  // crossing
  long saved = 0;
  for (const CellComplex& c : scenes) {
    const Viewpoint vp = default_viewpoint(c);
    const Camera cam = Camera::look_at(vp.eye, c.objects.empty() ? vp.look : Vec3{2.5, 2.5, 0.5}, vp.fov_deg, 240, 160);
    const VisibleSet vs = find_visible(c, cam, c.locate(vp.eye).cell);
    const std::vector<PlacedObject> objects = place_objects(c);
    for (ShadingModel model : {ShadingModel::Flat, ShadingModel::Smooth})
      for (int samples : {1, 4}) {
        HalftoneOptions o;
        o.shading.model = model;
        o.samples = samples;
        RenderStats planned, bare;
        Image a, b;
        render_view(c, objects, cam, vs, o, a, &planned);
        o.plan_effects = false;
        render_view(c, objects, cam, vs, o, b, &bare);
        ASSERT_EQ(a.data, b.data) << c.plan_name << ", " << to_string(model) << ", " << samples << " samples";
        EXPECT_EQ(planned.light_pieces, 0);
        EXPECT_LE(planned.depth_sorts, bare.depth_sorts);
        saved += bare.depth_sorts - planned.depth_sorts;
      }
  }
  EXPECT_GT(saved, 0) << "skipping the implicit-line search saves depth sorts somewhere";
}
