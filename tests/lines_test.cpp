// Tests of the hidden-line drawings (render/view_lines.h and its parts), the stereo rig
// (visibility/stereo.h) and walkthrough frames (render/walkthrough.h). Analytic, not golden
// images: endpoints computed by hand from the camera; masks recomputed from the portals;
// every drawn point checked against a brute-force ray caster (tests/ray_oracle.h) and the
// furniture's own triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include "cells/build_cells.h"
#include "ray_oracle.h"
#include "render/line_weight.h"
#include "render/view_lines.h"
#include "render/walkthrough.h"
#include "visibility/stereo.h"
#include "visibility/viewpoint.h"
#include "visibility/visible_set.h"
#include "test_plans.h"

using namespace avenues;
using avenues::testing::plan_path;
using avenues::testing::room_named;
using avenues::testing::first_hit;

namespace {

struct View {
  Camera camera;
  VisibleSet visible;
};

View view_from(const CellComplex& c, const Camera& cam) {
  const Location at = c.locate(cam.eye);
  EXPECT_EQ(at.what, Location::What::Cell) << "eye " << cam.eye.x << "," << cam.eye.y << "," << cam.eye.z;
  return {cam, find_visible(c, cam, at.cell)};
}

/// The projection of world point p in raster coordinates (p in front of the eye).
Vec2 raster_of(const Camera& cam, Vec3 p) {
  const Vec3 q = cam.camera_from_world(p);
  return cam.raster_from_image({q.x / q.z, q.y / q.z});
}

/// Closed containment in a convex polygon of either orientation, with tolerance [px].
bool in_convex(const std::vector<Vec2>& poly, Vec2 p, double tol) {
  bool pos = false, neg = false;
  for (size_t k = 0; k < poly.size(); ++k) {
    const Vec2 a = poly[k], b = poly[(k + 1) % poly.size()];
    const double s = cross(b - a, p - a) / length(b - a);
    pos |= s > tol;
    neg |= s < -tol;
  }
  return !(pos && neg);
}

/// Whether two strokes lie on one line and share a piece longer than tol [px].
bool overlap(const Stroke& s, const Stroke& t, double tol) {
  const double l = length(s.b - s.a);
  if (l == 0) return false;
  const Vec2 u = (1 / l) * (s.b - s.a);
  if (std::fabs(cross(u, t.a - s.a)) > tol || std::fabs(cross(u, t.b - s.a)) > tol) return false;
  double t0 = dot(u, t.a - s.a), t1 = dot(u, t.b - s.a);
  if (t0 > t1) std::swap(t0, t1);
  return std::min(l, t1) - std::max(0.0, t0) > tol;
}

/// A 3D segment a drawn stroke may come from.
struct Segment3 {
  Vec3 a, b;
};

/// All real lines and all furniture edges of the scene.
std::vector<Segment3> drawable_segments(const CellComplex& c, const LineScene& scene) {
  std::vector<Segment3> out;
  for (const RealLine& l : c.lines) out.push_back({l.a, l.b});
  for (const FurniturePiece& p : scene.furniture.pieces)
    for (const FurnitureEdge& e : p.edges) out.push_back({p.mesh.vertices[size_t(e.v[0])], p.mesh.vertices[size_t(e.v[1])]});
  return out;
}

/// The smallest t at which the ray o + t·d passes within 1e-5 m of one of the segments
/// (the 3D point a sample of a stroke was drawn from); infinity if none.
double depth_on_segments(const std::vector<Segment3>& segs, Vec3 o, Vec3 d) {
  double best = std::numeric_limits<double>::infinity();
  for (const Segment3& s : segs) {
    const Vec3 e = s.b - s.a, w0 = o - s.a;
    const double a = dot(d, d), b = dot(d, e), cc = dot(e, e), dd = dot(d, w0), ee = dot(e, w0);
    const double den = a * cc - b * b;
    if (!(den > 1e-12 * a * cc)) continue;  // parallel to the ray
    const double u = std::clamp((a * ee - b * dd) / den, 0.0, 1.0);
    const Vec3 q = s.a + u * e;
    const double t = dot(q - o, d) / a;
    if (t > 0 && length(o + t * d - q) < 1e-5) best = std::min(best, t);
  }
  return best;
}

/// Möller–Trumbore: distance along d to the triangle, or infinity.
double hit_triangle(Vec3 o, Vec3 d, Vec3 p0, Vec3 p1, Vec3 p2) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0, h = cross(d, e2);
  const double a = dot(e1, h);
  if (std::fabs(a) < 1e-15) return std::numeric_limits<double>::infinity();
  const Vec3 s = o - p0;
  const double u = dot(s, h) / a;
  const Vec3 q = cross(s, e1);
  const double v = dot(d, q) / a, t = dot(e2, q) / a;
  if (u < 0 || v < 0 || u + v > 1 || !(t > 0)) return std::numeric_limits<double>::infinity();
  return t;
}

/// Nearest furniture triangle along the ray.
double first_furniture_hit(const LineScene& scene, Vec3 o, Vec3 d) {
  double best = std::numeric_limits<double>::infinity();
  for (const FurniturePiece& p : scene.furniture.pieces)
    for (const auto& tri : p.mesh.triangles)
      best = std::min(best, hit_triangle(o, d, p.mesh.vertices[size_t(tri[0])], p.mesh.vertices[size_t(tri[1])],
                                         p.mesh.vertices[size_t(tri[2])]));
  return best;
}

/// Samples every stroke: the 3D point each sample was drawn from must be no farther than
/// the first opaque wall or furniture polygon on its ray. Returns the samples checked.
int expect_nothing_drawn_behind(const CellComplex& c, const LineScene& scene, const Camera& cam, const Drawing& d) {
  const std::vector<Segment3> segs = drawable_segments(c, scene);
  int checked = 0;
  for (const Stroke& s : d.strokes) {
    if (length(s.b - s.a) < 0.01) continue;  // too short to sample away from its ends
    for (int k = 0; k < 8; ++k) {
      const Vec2 px = s.a + ((k + 0.5) / 8) * (s.b - s.a);
      const Vec3 dir = cam.ray_through_raster(px);
      const double t = depth_on_segments(segs, cam.eye, dir);
      EXPECT_TRUE(std::isfinite(t)) << "a stroke sample at " << px.x << "," << px.y << " lies on no line";
      if (!std::isfinite(t)) continue;
      const double wall = first_hit(c, cam.eye, dir), furniture = first_furniture_hit(scene, cam.eye, dir);
      EXPECT_LE(t, wall * (1 + 1e-7) + 1e-7) << "drawn behind a wall at " << px.x << "," << px.y;
      EXPECT_LE(t, furniture * (1 + 1e-7) + 1e-7) << "drawn behind furniture at " << px.x << "," << px.y;
      ++checked;
    }
  }
  return checked;
}

void expect_no_overlaps(const Drawing& d) {
  for (size_t i = 0; i < d.strokes.size(); ++i)
    for (size_t j = i + 1; j < d.strokes.size(); ++j)
      EXPECT_FALSE(overlap(d.strokes[i], d.strokes[j], 1e-6))
          << "strokes " << i << " and " << j << " overlap: (" << d.strokes[i].a.x << "," << d.strokes[i].a.y << ")-("
          << d.strokes[i].b.x << "," << d.strokes[i].b.y << ") and (" << d.strokes[j].a.x << "," << d.strokes[j].a.y
          << ")-(" << d.strokes[j].b.x << "," << d.strokes[j].b.y << ")";
}

/// Random eyes at eye height in rooms of the complex, looking anywhere level-ish.
std::vector<Camera> random_views(const CellComplex& c, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<CellId> rooms;
  for (CellId id = 0; id < CellId(c.cells.size()); ++id)
    if (c.cells[size_t(id)].kind == CellKind::Room) rooms.push_back(id);
  std::uniform_real_distribution<double> u(0.05, 0.95), yaw(0, 360), pitch(-25, 25), fov(50, 100);
  std::vector<Camera> out;
  while (int(out.size()) < n) {
    const Cell& k = c.cells[size_t(rooms[std::uniform_int_distribution<size_t>(0, rooms.size() - 1)(rng)])];
    std::vector<double> w(k.footprint.size());
    double sum = 0;
    for (double& x : w) sum += (x = u(rng));
    Vec2 p{0, 0};
    for (size_t i = 0; i < w.size(); ++i) p = p + (w[i] / sum) * k.footprint[i];
    const Vec3 eye{p.x, p.y, k.z0 + std::min(1.6, 0.8 * (k.z1 - k.z0))};
    if (c.locate(eye).what != Location::What::Cell) continue;
    out.push_back(Camera::yaw_pitch(eye, yaw(rng), pitch(rng), fov(rng), 320, 240));
  }
  return out;
}

const char* kBoxRoom = R"(
name = "box room"
[[wall]]
thickness = 0.2
path = [[0, 0], [4, 0], [4, 3], [0, 3], [0, 0]]
[[room]]
name = "box"
at = [2, 1.5]
)";

}  // namespace

// --- Lines from the visible set ------------------------------------------------------

TEST(Lines, BoxRoomSeenFromInsideGivesTheExpectedLinesAndEndpoints) {
  // Walls 0.2 m thick centred on the path: the room inside is x 0.1–3.9, y 0.1–2.9, z 0–2.5.
  const CellComplex c = build_cells(parse_plan(kBoxRoom, "box.toml"));
  const LineScene scene = prepare_line_scene(c);
  // Eye 1.25 m up at x = 2, y = 0.3, looking north: camera X = x − 2, Y = z − 1.25, Z = y − 0.3.
  // A 90° field across 800 px: the window spans x ∈ [−1, 1], y ∈ [−0.75, 0.75] on the
  // picture plane, and raster = (400 (1 + x), 400 (0.75 − y)).
  const View v = view_from(c, Camera::look_at({2, 0.3, 1.25}, {2, 2.9, 1.25}, 90, 800, 600));
  const Drawing d = draw_view(c, scene, v.camera, v.visible);
  auto raster = [](double x, double y) { return Vec2{400 * (1 + x), 400 * (0.75 - y)}; };
  // The north wall at Z = 2.6: corners at X = ±1.9, Y = ±1.25.
  const double cx = 1.9 / 2.6, cy = 1.25 / 2.6;
  // The side walls' floor and ceiling lines (X = ±1.9, Y = ±1.25) leave the window at its
  // left and right edges, x = ±1, where Z = 1.9: y = ±1.25 / 1.9.
  const double ey = 1.25 / 1.9;
  const std::vector<std::pair<Vec2, Vec2>> expected = {
      {raster(-cx, -cy), raster(cx, -cy)},  // north wall–floor
      {raster(-cx, cy), raster(cx, cy)},    // north wall–ceiling
      {raster(-cx, -cy), raster(-cx, cy)},  // north-west corner
      {raster(cx, -cy), raster(cx, cy)},    // north-east corner
      {raster(-1, -ey), raster(-cx, -cy)},  // west wall–floor
      {raster(-1, ey), raster(-cx, cy)},    // west wall–ceiling
      {raster(1, -ey), raster(cx, -cy)},    // east wall–floor
      {raster(1, ey), raster(cx, cy)},      // east wall–ceiling
  };
  ASSERT_EQ(d.strokes.size(), expected.size());
  EXPECT_EQ(d.width, 800);
  EXPECT_EQ(d.height, 600);
  for (const auto& [a, b] : expected) {
    const auto found = std::find_if(d.strokes.begin(), d.strokes.end(), [&](const Stroke& s) {
      return (length(s.a - a) < 1e-6 && length(s.b - b) < 1e-6) || (length(s.a - b) < 1e-6 && length(s.b - a) < 1e-6);
    });
    EXPECT_NE(found, d.strokes.end()) << "no stroke (" << a.x << "," << a.y << ")-(" << b.x << "," << b.y << ")";
  }
  for (const Stroke& s : d.strokes) {
    EXPECT_EQ(s.weight, Weight::Crease) << "a room's inner corners are creases";
    EXPECT_EQ(s.layer, Layer::Architecture);
  }
}

TEST(Lines, JonesKitchenLinesAppearOnlyInsideTheDoorsAndTheHatchsMasks) {
  const CellComplex c = build_cells(read_plan(plan_path("jones-house.toml")));
  const LineScene scene = prepare_line_scene(c);
  const View v = view_from(c, Camera::look_at({1.0, 0.5, 1.2}, {6, 3, 1.2}, 100, 400, 300));
  const RoomId L = room_named(c, "L"), K = room_named(c, "K"), D = room_named(c, "D");
  // The openings, projected independently of the traversal: the doors living→kitchen and
  // living→dining and the hatch dining→kitchen.
  auto opening = [&](PortalKind kind, RoomId r0, RoomId r1) {
    for (const Portal& p : c.portals) {
      const RoomId a = c.cells[size_t(p.cell[0])].room, b = c.cells[size_t(p.cell[1])].room;
      if (p.kind == kind && ((a == r0 && b == r1) || (a == r1 && b == r0))) {
        std::vector<Vec2> poly;
        for (Vec3 q : p.poly) poly.push_back(raster_of(v.camera, q));
        return poly;
      }
    }
    ADD_FAILURE() << "no " << to_string(kind) << " between rooms " << r0 << " and " << r1;
    return std::vector<Vec2>{};
  };
  const auto door_lk = opening(PortalKind::Door, L, K), door_ld = opening(PortalKind::Door, L, D),
             hatch = opening(PortalKind::Hatch, D, K);
  // The kitchen's lines alone: the visible set restricted to the kitchen's avenues.
  VisibleSet kitchen = v.visible;
  kitchen.avenues.clear();
  kitchen.cells.clear();
  for (const Avenue& a : v.visible.avenues)
    if (c.cells[size_t(a.cell)].room == K) kitchen.avenues.push_back(a), kitchen.cells.push_back(a.cell);
  std::sort(kitchen.cells.begin(), kitchen.cells.end());
  kitchen.cells.erase(std::unique(kitchen.cells.begin(), kitchen.cells.end()), kitchen.cells.end());
  const Drawing d = draw_view(c, scene, v.camera, kitchen);
  ASSERT_FALSE(d.strokes.empty());
  auto inside_masks = [&](Vec2 p) {
    return in_convex(door_lk, p, 1e-6) || (in_convex(door_ld, p, 1e-6) && in_convex(hatch, p, 1e-6));
  };
  for (const Stroke& s : d.strokes)
    for (int k = 0; k <= 8; ++k) {
      const Vec2 p = s.a + (k / 8.0) * (s.b - s.a);
      EXPECT_TRUE(inside_masks(p)) << "kitchen line drawn at " << p.x << "," << p.y;
    }
  EXPECT_GT(std::count_if(d.strokes.begin(), d.strokes.end(),
                          [&](const Stroke& s) { return in_convex(door_lk, 0.5 * (s.a + s.b), -1e-3); }),
            3)
      << "the kitchen is seen through its door";
  // The check has teeth: the kitchen's lines clipped to the whole window instead of their
  // masks do show outside the openings.
  VisibleSet unmasked = kitchen;
  for (Avenue& a : unmasked.avenues) a.mask = v.visible.avenues[0].mask;
  int outside = 0;
  for (const Stroke& s : draw_view(c, scene, v.camera, unmasked).strokes) outside += !inside_masks(0.5 * (s.a + s.b));
  EXPECT_GT(outside, 3);
  // Jones: "a further opening, the service hatch, gives another view into the kitchen, masked
  // this time by the combined outlines of the two openings": the kitchen is reached through
  // the dining room, and the hatch's frame is drawn inside the dining door.
  bool via_dining = false;
  for (const Avenue& a : kitchen.avenues)
    via_dining |= a.parent >= 0 && c.cells[size_t(v.visible.avenues[size_t(a.parent)].cell)].room == D;
  EXPECT_TRUE(via_dining);
  int hatch_frame = 0;
  for (const Stroke& s : draw_view(c, scene, v.camera, v.visible).strokes) {
    const Vec2 m = 0.5 * (s.a + s.b);
    hatch_frame += in_convex(door_ld, m, 1e-6) && in_convex(hatch, m, 1e-6) && s.weight == Weight::Outline;
  }
  EXPECT_EQ(hatch_frame, 4) << "the hatch's sill, head and jambs, outlined";
}

TEST(Lines, NoDrawnLineCrossesAWallOrFurniture) {
  for (const char* plan : {"jones-house.toml", "furnished-room.toml", "two-storey-house.toml", "office-corridor.toml",
                           "curved-walls.toml"}) {
    SCOPED_TRACE(plan);
    const CellComplex c = build_cells(read_plan(plan_path(plan)));
    const LineScene scene = prepare_line_scene(c);
    std::vector<Camera> cams = random_views(c, 6, 1971);
    const Viewpoint vp = default_viewpoint(c);
    cams.push_back(Camera::look_at(vp.eye, vp.look, vp.fov_deg, 480, 270));
    int samples = 0;
    for (const Camera& cam : cams) {
      const View v = view_from(c, cam);
      const Drawing d = draw_view(c, scene, cam, v.visible);
      samples += expect_nothing_drawn_behind(c, scene, cam, d);
      expect_no_overlaps(d);
    }
    EXPECT_GT(samples, 100);
  }
}

TEST(Lines, EachLineIsDrawnOnceThoughSeenThroughSeveralAvenuesAndCells) {
  // From the living room the dining room is seen through its door, and the kitchen through
  // its door and again through the hatch; the wall between them bounds both.
  const CellComplex c = build_cells(read_plan(plan_path("jones-house.toml")));
  const LineScene scene = prepare_line_scene(c);
  const View v = view_from(c, Camera::look_at({1.0, 0.5, 1.2}, {6, 3, 1.2}, 100, 400, 300));
  const Drawing d = draw_view(c, scene, v.camera, v.visible);
  expect_no_overlaps(d);
  // Merged where they touch: no two strokes of one weight and layer continue each other.
  for (size_t i = 0; i < d.strokes.size(); ++i)
    for (size_t j = 0; j < d.strokes.size(); ++j) {
      const Stroke &s = d.strokes[i], &t = d.strokes[j];
      if (i == j || s.weight != t.weight || s.layer != t.layer || length(s.b - t.a) > 1e-9) continue;
      const Vec2 u = s.b - s.a, w = t.b - t.a;
      EXPECT_GT(std::fabs(cross(u, w)) / (length(u) * length(w)), 1e-9) << "strokes " << i << " and " << j << " continue each other";
    }
  // Dropping the view's duplicated avenues changes nothing: the same lines, once.
  VisibleSet twice = v.visible;
  twice.avenues.insert(twice.avenues.end(), v.visible.avenues.begin(), v.visible.avenues.end());
  EXPECT_EQ(draw_view(c, scene, v.camera, twice).strokes.size(), d.strokes.size());
}

TEST(Lines, NoEdgeOfATransparentFaceIsDrawn) {
  int edges_in_view = 0;
  for (const char* plan : {"curved-walls.toml", "two-storey-house.toml", "office-corridor.toml"}) {
    SCOPED_TRACE(plan);
    const CellComplex c = build_cells(read_plan(plan_path(plan)));
    const LineScene scene = prepare_line_scene(c);
    // Edges of transparent faces that do not run along a real line.
    std::vector<Segment3> artificial;
    for (const Portal& p : c.portals) {
      if (p.kind != PortalKind::Transparent) continue;
      for (size_t k = 0; k < p.poly.size(); ++k) {
        const Vec3 a = p.poly[k], b = p.poly[(k + 1) % p.poly.size()], m = 0.5 * (a + b);
        bool real = false;
        for (const RealLine& l : c.lines) {
          const Vec3 e = l.b - l.a;
          const double t = std::clamp(dot(m - l.a, e) / dot(e, e), 0.0, 1.0);
          real = real || length(l.a + t * e - m) < 1e-6;
        }
        if (!real) artificial.push_back({a, b});
      }
    }
    for (const Camera& cam : random_views(c, 8, 1981)) {
      const View v = view_from(c, cam);
      const Drawing d = draw_view(c, scene, cam, v.visible);
      for (const Segment3& e : artificial) {
        // The edge's part in front of the near plane, projected.
        Vec3 p0 = cam.camera_from_world(e.a), p1 = cam.camera_from_world(e.b);
        if (p0.z < cam.near && p1.z < cam.near) continue;
        if (p0.z < cam.near) p0 = p0 + ((cam.near - p0.z) / (p1.z - p0.z)) * (p1 - p0);
        if (p1.z < cam.near) p1 = p1 + ((cam.near - p1.z) / (p0.z - p1.z)) * (p0 - p1);
        const Stroke edge{cam.raster_from_image({p0.x / p0.z, p0.y / p0.z}), cam.raster_from_image({p1.x / p1.z, p1.y / p1.z})};
        if (std::max(edge.a.x, edge.b.x) < 0 || std::min(edge.a.x, edge.b.x) > cam.width ||
            std::max(edge.a.y, edge.b.y) < 0 || std::min(edge.a.y, edge.b.y) > cam.height)
          continue;
        ++edges_in_view;
        for (const Stroke& s : d.strokes) EXPECT_FALSE(overlap(edge, s, 1e-3)) << "a transparent face's edge is drawn";
      }
    }
  }
  EXPECT_GT(edges_in_view, 10) << "the test saw too few transparent edges to mean anything";
}

// --- Weights ---------------------------------------------------------------------------

TEST(Lines, OutlinesAreWhereTheEyeSeesPastTheLine) {
  auto line_at = [](const CellComplex& c, Vec3 a, Vec3 b) {
    for (LineId id = 0; id < LineId(c.lines.size()); ++id) {
      const RealLine& l = c.lines[size_t(id)];
      if ((length(l.a - a) < 1e-6 && length(l.b - b) < 1e-6) || (length(l.a - b) < 1e-6 && length(l.b - a) < 1e-6))
        return id;
    }
    ADD_FAILURE() << "no line " << a.x << "," << a.y << "," << a.z << " – " << b.x << "," << b.y << "," << b.z;
    return LineId(0);
  };
  {
    // Jones's walls of no thickness: a door's frame is an outline from either side; the
    // corner where the kitchen–dining wall meets the living room's wall is a crease seen
    // from the kitchen, and no line at all from the living room (a flat wall there).
    const CellComplex c = build_cells(read_plan(plan_path("jones-house.toml")));
    const LineFaces f = line_faces(c);
    const LineId frame = line_at(c, {5, 3.9, 0}, {5, 3.9, 2.1});
    EXPECT_EQ(line_weight(c, f, frame, {1.5, 3.0, 1.6}), Weight::Outline);
    EXPECT_EQ(line_weight(c, f, frame, {7.0, 4.5, 1.6}), Weight::Outline);
    const LineId junction = line_at(c, {5, 3, 0}, {5, 3, 2.5});
    EXPECT_EQ(line_weight(c, f, junction, {7.0, 4.5, 1.6}), Weight::Crease);
    const LineScene scene = prepare_line_scene(c);
    const View v = view_from(c, Camera::look_at({1.5, 2.0, 1.6}, {5, 3, 1.4}, 70, 640, 480));
    const Drawing d = draw_view(c, scene, v.camera, v.visible);
    const Stroke junction_seen{raster_of(v.camera, {5, 3, 0.3}), raster_of(v.camera, {5, 3, 2.2})};
    for (const Stroke& s : d.strokes) EXPECT_FALSE(overlap(junction_seen, s, 1e-3)) << "a line behind a sheet is drawn";
  }
  {
    // A window in a thick wall (the north wall's inner face at y = 3.85, outer at 4.15; the
    // window from x = 1.5 to 3.0, sill 0.9, head 2.1), seen from the south-west: the west
    // jamb is turned away, so its room-side arris is an outline; the east jamb is in view,
    // so its room-side arris is a crease and its outer arris, against the outside, an outline.
    const CellComplex c = build_cells(read_plan(plan_path("furnished-room.toml")));
    const LineFaces f = line_faces(c);
    const Vec3 eye{1.4, 0.6, 1.6};
    EXPECT_EQ(line_weight(c, f, line_at(c, {1.5, 3.85, 0.9}, {1.5, 3.85, 2.1}), eye), Weight::Outline);
    EXPECT_EQ(line_weight(c, f, line_at(c, {3.0, 3.85, 0.9}, {3.0, 3.85, 2.1}), eye), Weight::Crease);
    EXPECT_EQ(line_weight(c, f, line_at(c, {3.0, 4.15, 0.9}, {3.0, 4.15, 2.1}), eye), Weight::Outline);
    // The sill seen from above: its room-side arris a crease, its outer one an outline.
    EXPECT_EQ(line_weight(c, f, line_at(c, {1.5, 3.85, 0.9}, {3.0, 3.85, 0.9}), eye), Weight::Crease);
    EXPECT_EQ(line_weight(c, f, line_at(c, {1.5, 4.15, 0.9}, {3.0, 4.15, 0.9}), eye), Weight::Outline);
    // The wall–floor line: a crease.
    EXPECT_EQ(line_weight(c, f, line_at(c, {0.15, 0.15, 0}, {0.15, 3.85, 0}), eye), Weight::Crease);
  }
}

// --- Furniture ---------------------------------------------------------------------------

TEST(Lines, FurnitureShowsSilhouettesAndCreasesButNoDiagonalsAndHidesWhatIsBehind) {
  const CellComplex c = build_cells(read_plan(plan_path("furnished-room.toml")));
  const LineScene scene = prepare_line_scene(c);
  ASSERT_EQ(scene.furniture.pieces.size(), 1u);
  const FurniturePiece& table = scene.furniture.pieces[0];
  EXPECT_EQ(table.edges.size(), 5u * 12u) << "five boxes of twelve edges; no quad's diagonal";
  for (const FurnitureEdge& e : table.edges) EXPECT_NEAR(e.dihedral_deg, 90, 1e-6);
  // Looking down at the table from the door: its top (four creases and silhouettes) and legs.
  const Viewpoint vp = default_viewpoint(c);
  const View v = view_from(c, Camera::look_at(vp.eye, vp.look, vp.fov_deg, 960, 540));
  const Drawing d = draw_view(c, scene, v.camera, v.visible);
  int outlines = 0, creases = 0;
  for (const Stroke& s : d.strokes)
    if (s.layer == Layer::Furniture) (s.weight == Weight::Outline ? outlines : creases)++;
  EXPECT_GT(outlines, 4);
  EXPECT_GT(creases, 2);
  // Every furniture stroke runs along a box edge (not across a face), and nothing is drawn
  // behind the table: its far legs' hidden parts, the wall–floor line behind it.
  std::vector<Segment3> box_edges;
  for (const FurnitureEdge& e : table.edges)
    box_edges.push_back({table.mesh.vertices[size_t(e.v[0])], table.mesh.vertices[size_t(e.v[1])]});
  for (const Stroke& s : d.strokes) {
    if (s.layer != Layer::Furniture || length(s.b - s.a) < 0.01) continue;
    const Vec2 m = 0.5 * (s.a + s.b);
    EXPECT_TRUE(std::isfinite(depth_on_segments(box_edges, v.camera.eye, v.camera.ray_through_raster(m))))
        << "a furniture stroke at " << m.x << "," << m.y << " is on no edge of the table";
  }
  EXPECT_GT(expect_nothing_drawn_behind(c, scene, v.camera, d), 100);
  // Without furniture the wall–floor line is longer: the table hid part of it.
  LineOptions bare;
  bare.furniture = false;
  const Drawing empty = draw_view(c, scene, v.camera, v.visible, bare);
  double with = 0, without = 0;
  for (const Stroke& s : d.strokes) with += s.layer == Layer::Architecture ? length(s.b - s.a) : 0;
  for (const Stroke& s : empty.strokes) without += length(s.b - s.a);
  EXPECT_GT(without, with + 10);
  for (const Stroke& s : empty.strokes) EXPECT_EQ(s.layer, Layer::Architecture);
}

// --- Stereo pairs ------------------------------------------------------------------------

TEST(Stereo, OffAxisFrustaConvergeAtTheStatedDistance) {
  const CellComplex c = build_cells(read_plan(plan_path("furnished-room.toml")));
  const Camera centre = Camera::look_at({2.5, 0.8, 1.6}, {2.3, 3.0, 1.2}, 70, 800, 600);
  StereoOptions o;
  o.interocular = 0.065;
  o.converge = 2.0;
  const StereoRig rig = stereo_rig(c, centre, o);
  ASSERT_EQ(rig.problem, StereoRig::Problem::None) << rig.message();
  EXPECT_FALSE(rig.eyes_apart());
  // Never toed in: both look along the centre's forward vector, eyes 65 mm apart along right.
  EXPECT_LT(length(rig.left.forward - centre.forward), 1e-15);
  EXPECT_LT(length(rig.right.forward - centre.forward), 1e-15);
  EXPECT_NEAR(length(rig.right.eye - rig.left.eye), 0.065, 1e-12);
  EXPECT_NEAR(dot(rig.right.eye - rig.left.eye, centre.right), 0.065, 1e-12);
  // A point on the centre line 2 m ahead is at the same raster position in both pictures.
  auto at = [&](double dist) {
    const Vec3 p = centre.eye + dist * centre.forward;
    return std::pair{raster_of(rig.left, p), raster_of(rig.right, p)};
  };
  const auto [l2, r2] = at(2.0);
  EXPECT_NEAR(l2.x, r2.x, 1e-9);
  EXPECT_NEAR(l2.y, r2.y, 1e-9);
  EXPECT_NEAR(l2.x, 400, 1e-9);
  // Nearer points stand out (crossed parallax), farther ones sink behind the page.
  const auto [l1, r1] = at(1.0);
  EXPECT_GT(l1.x, r1.x);
  const auto [l4, r4] = at(4.0);
  EXPECT_LT(l4.x, r4.x);
}

TEST(Stereo, EyesStraddlingAWallOrInsideOneAreReported) {
  {
    // Jones's walls have no thickness: eyes either side of the living room's east wall.
    const CellComplex c = build_cells(read_plan(plan_path("jones-house.toml")));
    const StereoRig rig = stereo_rig(c, Camera::look_at({4.99, 2.5, 1.6}, {4.99, 5, 1.6}, 60, 640, 480), {});
    EXPECT_TRUE(rig.eyes_apart());
    EXPECT_EQ(rig.problem, StereoRig::Problem::WallBetweenEyes);
    EXPECT_NE(rig.message().find("room 'L'"), std::string::npos) << rig.message();
    EXPECT_NE(rig.message().find("room 'D'"), std::string::npos) << rig.message();
    // Straddling the kitchen door's opening instead is fine: the eyes see each other.
    const StereoRig door = stereo_rig(c, Camera::look_at({4.99, 4.3, 1.6}, {4.99, 6, 1.6}, 60, 640, 480), {});
    EXPECT_TRUE(door.eyes_apart());
    EXPECT_EQ(door.problem, StereoRig::Problem::None) << door.message();
  }
  {
    // Looking east along the furnished room's south wall (0.3 m thick, its inner face at
    // y = 0.15): the right eye, to the south, is inside the wall.
    const CellComplex c = build_cells(read_plan(plan_path("furnished-room.toml")));
    const StereoRig rig = stereo_rig(c, Camera::look_at({2.5, 0.17, 1.6}, {4, 0.17, 1.6}, 60, 640, 480), {});
    EXPECT_EQ(rig.problem, StereoRig::Problem::EyeInSolid);
    EXPECT_EQ(rig.eye, "right");
    EXPECT_NE(rig.message().find("wall 'outside'"), std::string::npos) << rig.message();
  }
  StereoLayout l;
  EXPECT_TRUE(parse_stereo_layout("cross", l));
  EXPECT_EQ(l, StereoLayout::Cross);
  EXPECT_FALSE(parse_stereo_layout("toe-in", l));
}

// --- Walkthrough -----------------------------------------------------------------------

TEST(Walkthrough, FramesWalkStraightAndAFrameInsideAWallIsNamed) {
  const CellComplex c = build_cells(read_plan(plan_path("furnished-room.toml")));
  const Camera lens = Camera::look_at({0, 0, 0}, {1, 0, 0}, 65, 320, 200);
  const auto frames = walk_frames(c, {1, 1, 1.6}, {4, 1, 1.6}, {3, 3, 1.6}, {4, 3, 1.0}, 5, lens);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_LT(length(frames[0].camera.eye - Vec3{1, 1, 1.6}), 1e-12);
  EXPECT_LT(length(frames[2].camera.eye - Vec3{2, 2, 1.6}), 1e-12);
  EXPECT_LT(length(frames[4].camera.eye - Vec3{3, 3, 1.6}), 1e-12);
  EXPECT_LT(length(frames[4].camera.forward - (1 / std::sqrt(1.36)) * Vec3{1, 0, -0.6}), 1e-12);
  for (const WalkFrame& f : frames) {
    EXPECT_EQ(c.locate(f.camera.eye).cell, f.cell);
    EXPECT_EQ(f.camera.width, 320);
    EXPECT_EQ(f.camera.fov_deg, 65);
  }
  // North through the wall (inner face y = 3.85, outer 4.15): the fourth frame, at y = 4.
  try {
    walk_frames(c, {1, 1, 1.6}, {1, 2, 1.6}, {1, 5, 1.6}, {1, 6, 1.6}, 5, lens);
    ADD_FAILURE() << "a frame inside a wall must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 4 of 5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("wall 'outside'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(frame_path("out/walk.svg", 2, 10), "out/walk-0003.svg");
  EXPECT_EQ(frame_path("walk.pdf", 11999, 12000), "walk-12000.pdf");
}

// The occluders binned on the picture plane hide exactly what testing every occluder
// hides: thousands of small triangles (a steel structure's members) and a few that reach
// behind the eye, against segments long and short, steep and level.
TEST(Lines, TheOccluderGridHidesWhatEveryOccluderHides) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1, 1), depth(2, 20), small(-0.3, 0.3);
  const Camera cam = Camera::look_at({0, 0, 0}, {1, 0, 0}, 90, 640, 480);
  FurniturePiece piece;
  for (int t = 0; t < 4000; ++t) {
    const Vec3 c{depth(rng), 10 * u(rng), 5 * u(rng)};
    const int first = int(piece.mesh.vertices.size());
    for (int k = 0; k < 3; ++k) piece.mesh.vertices.push_back(c + Vec3{small(rng), small(rng), small(rng)});
    piece.mesh.triangles.push_back({first, first + 1, first + 2});
    piece.mesh.polygon_of.push_back(t);
  }
  for (int t = 0; t < 3; ++t) {  // reaching behind the eye: unbounded on the picture plane
    const int first = int(piece.mesh.vertices.size());
    piece.mesh.vertices.insert(piece.mesh.vertices.end(), {{-1, double(t) - 3, -1}, {5, 3 - double(t), -1}, {5, 0, 2}});
    piece.mesh.triangles.push_back({first, first + 1, first + 2});
    piece.mesh.polygon_of.push_back(4000 + t);
  }
  piece.mesh.closed = false;
  std::vector<Occluder> all;
  add_occluders(piece, std::vector<uint8_t>(piece.mesh.triangles.size(), 1), cam, all);
  ASSERT_GT(all.size(), 3000u);
  const OccluderGrid grid(all);
  int hidden = 0;
  for (int s = 0; s < 3000; ++s) {
    const double reach = s % 3 == 0 ? 10 : s % 3 == 1 ? 2 : 0.2;
    const Vec3 a{depth(rng) + 2, 10 * u(rng), 5 * u(rng)};
    const Vec3 b = a + reach * Vec3{u(rng), u(rng), s % 5 == 0 ? 0 : u(rng)};
    const Vec3 p0 = cam.camera_from_world(a), p1 = cam.camera_from_world(b);
    if (!(p0.z > 0.1 && p1.z > 0.1)) continue;
    std::vector<detail::Interval> every{{0, 1}}, binned{{0, 1}};
    hide_behind(all, p0, p1, every);
    hide_behind(grid, p0, p1, binned);
    ASSERT_EQ(binned.size(), every.size()) << "segment " << s;
    for (size_t k = 0; k < every.size(); ++k) {
      EXPECT_EQ(binned[k].t0, every[k].t0) << "segment " << s;
      EXPECT_EQ(binned[k].t1, every[k].t1) << "segment " << s;
    }
    hidden += every.size() != 1 || every[0].t0 != 0 || every[0].t1 != 1;
  }
  EXPECT_GT(hidden, 300) << "the occluders hide parts of many segments";
}
