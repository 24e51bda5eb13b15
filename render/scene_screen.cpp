// Avenues — polygons from camera space to the fixed-point raster (see scene_screen.h).
#include "render/scene_screen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "render/shadows.h"

namespace avenues {

namespace {

/// drop_hidden: how many polygons are tested before the picture judges whether remembering
/// what is drawn pays, and the share of them (one in kPaysFrom) it must have dropped.
constexpr long kJudgedAfter = 500;
constexpr long kPaysFrom = 8;

/// The least and largest of 1/Z on the raster `z` at points (each with .x, .y [samples]),
/// and whether the scan's arithmetic holds 1/Z there to 1e-8: false for a plane seen nearly
/// edge-on (its terms far larger than their sum) or not wholly in front. drop_hidden trusts
/// no other plane, as an occluder or as hidden.
template <class Points>
bool trusted_range(const RasterPlane& z, const Points& points, double& least, double& most) {
  double size = 0;
  least = HUGE_VAL, most = -HUGE_VAL;
  for (const auto& p : points) {
    const double v = z.at(p.x, p.y);
    least = std::min(least, v), most = std::max(most, v);
    size = std::max(size, std::fabs(z.a * p.x) + std::fabs(z.b * p.y) + std::fabs(z.c));
  }
  return least > 0 && !(size > 1e8 * least);
}

bool before(Vec3 a, Vec3 b) { return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z; }
bool before(Vec2 a, Vec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; }

/// Sutherland–Hodgman against one half-plane f >= 0. A crossing is interpolated from the
/// edge's end points in canonical (lexicographic) order, whichever way the edge runs.
template <class P, class F>
void cut(const std::vector<P>& in, F f, std::vector<P>& out) {
  out.clear();
  const size_t n = in.size();
  for (size_t i = 0; i < n; ++i) {
    const P a = in[i], b = in[(i + 1) % n];
    const double fa = f(a), fb = f(b);
    if (fa >= 0) out.push_back(a);
    if ((fa >= 0) != (fb >= 0)) {
      const bool ab = before(a, b);
      const P p = ab ? a : b, q = ab ? b : a;
      const double fp = ab ? fa : fb, fq = ab ? fb : fa;
      out.push_back(p + (fp / (fp - fq)) * (q - p));
    }
  }
}

FixedPoint to_fixed(Vec2 r) { return {std::llround(r.x * kSubpixelOne), std::llround(r.y * kSubpixelOne)}; }

/// Twice the signed area of the triangle o, a, b, exactly: > 0 where o → a → b turns
/// counter-clockwise (|terms| < 2^58 within the guard band).
int64_t turn(FixedPoint o, FixedPoint a, FixedPoint b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

/// Corner f moved to each corner of the square [−g, g]², appended to `pts`: the hull of an
/// outline's corners so moved is its Minkowski sum with the square.
void push_moved_by_square(FixedPoint f, int64_t g, std::vector<FixedPoint>& pts) {
  for (int64_t dx : {-g, g})
    for (int64_t dy : {-g, g}) pts.push_back({f.x + dx, f.y + dy});
}

/// Convex hull (Andrew's monotone chain), exact in integers; collinear points dropped. Into
/// `h`'s storage; empty when fewer than three corners are left. Sorts `pts`.
std::vector<FixedPoint> hull(std::vector<FixedPoint>& pts, std::vector<FixedPoint> h) {
  std::sort(pts.begin(), pts.end(), [](FixedPoint a, FixedPoint b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  h.clear();
  if (pts.size() < 3) return h;
  h.resize(2 * pts.size());
  size_t k = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && turn(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  if (h.size() < 3) h.clear();
  return h;
}

}  // namespace

void ScreenScene::clear() {
  for (ScreenPolygon& p : polygons) keep_outline(std::move(p.outline));
  for (ScreenPolygon& p : pieces) keep_outline(std::move(p.outline));
  for (ClipRegion& c : clips) keep_outline(std::move(c.outline));
  polygons.clear();
  pieces.clear();
  clips.clear();
  shades.clear();
  sources.clear();
  light_terms.clear();
  raster = {};
  implicit_lines = true;
}

std::vector<FixedPoint> ScreenScene::take_outline() {
  if (spare_outlines.empty()) return {};
  std::vector<FixedPoint> out = std::move(spare_outlines.back());
  spare_outlines.pop_back();
  out.clear();
  return out;
}

void ScreenScene::keep_outline(std::vector<FixedPoint>&& outline) {
  if (outline.capacity() > 0) spare_outlines.push_back(std::move(outline));
}

void ScreenScene::append(ScreenScene& part) {
  const int32_t clips_before = int32_t(clips.size()), terms_before = int32_t(light_terms.size()),
                pieces_before = int32_t(pieces.size());
  for (ScreenPolygon& p : part.polygons) {
    if (p.clip >= 0) p.clip += clips_before;
    polygons.push_back(std::move(p));
  }
  for (SurfaceShade shade : part.shades) {
    shade.first_term += terms_before;
    shades.push_back(shade);
  }
  sources.insert(sources.end(), part.sources.begin(), part.sources.end());
  for (ClipRegion& c : part.clips) clips.push_back(std::move(c));
  for (LightTerm term : part.light_terms) {
    term.first_piece += pieces_before;
    light_terms.push_back(term);
  }
  for (ScreenPolygon& p : part.pieces) pieces.push_back(std::move(p));
  part.polygons.clear(), part.shades.clear(), part.sources.clear(), part.clips.clear();
  part.light_terms.clear(), part.pieces.clear();
}

void ScreenScene::drop_pieces_from(size_t first) {
  for (size_t i = first; i < pieces.size(); ++i) keep_outline(std::move(pieces[i].outline));
  pieces.resize(std::min(first, pieces.size()));
}

ScreenSceneBuilder::ScreenSceneBuilder(const Camera& camera, const SceneOptions& options, ScreenScene& out)
    : camera_(camera), options_(options), out_(out) {
  if (options.per_side != 1 && options.per_side != 2 && options.per_side != 4)
    throw std::invalid_argument("samples per pixel side must be 1, 2 or 4");
  out_.raster = RasterMap::of(camera, options.per_side);
  if (options.cut) {
    // In camera space, oriented so that what lies beyond it (along forward) is kept.
    const Plane& c = *options.cut;
    const double sign = dot(c.n, camera.forward) >= 0 ? 1 : -1;
    has_cut_ = true;
    cut_n_ = sign * Vec3{dot(c.n, camera.right), dot(c.n, camera.up), dot(c.n, camera.forward)};
    cut_d_ = sign * c.eval(camera.eye);
  }
  guard_ = std::max(out_.raster.width, out_.raster.height);
  if (3 * guard_ >= double(kRasterLimit))
    throw std::invalid_argument("picture too large for the scanline engine's fixed point");
}

int32_t ScreenSceneBuilder::add_clip(const std::vector<Vec2>& picture_polygon, double grow) {
  const int64_t g = std::llround(grow * kSubpixelOne);
  std::vector<FixedPoint>& pts = clip_points_;
  pts.clear();
  for (Vec2 p : picture_polygon) push_moved_by_square(to_fixed(out_.raster.raster_from_image(p)), g, pts);
  std::vector<FixedPoint> h = hull(pts, out_.take_outline());
  if (h.empty()) {
    out_.keep_outline(std::move(h));
    return -1;
  }
  Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (const FixedPoint& f : h) {
    const Vec2 r{double(f.x) / double(kSubpixelOne), double(f.y) / double(kSubpixelOne)};
    lo = {std::min(lo.x, r.x), std::min(lo.y, r.y)}, hi = {std::max(hi.x, r.x), std::max(hi.y, r.y)};
  }
  out_.clips.push_back({std::move(h)});
  clip_box_.resize(out_.clips.size());
  clip_box_.back() = {lo, hi};
  return int32_t(out_.clips.size() - 1);
}

namespace {

/// Whether the box around a fixed-point outline holds the centre (i + ½, j + ½) of some
/// sample of a width × height raster. A sample is inside a polygon only if its centre is
/// (scanline.h), so a polygon whose box holds none (a far piece of furniture's tiny
/// triangle, or one wholly off the picture) colours nothing, takes part in no depth
/// resolution and is better never put on the raster.
bool covers_a_sample_centre(const std::vector<FixedPoint>& outline, int width, int height) {
  int64_t x0 = outline[0].x, x1 = x0, y0 = outline[0].y, y1 = y0;
  for (const FixedPoint& p : outline) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  constexpr int64_t half = kSubpixelOne / 2;
  // The first centre at or after lo (floor division), at least the raster's first, and
  // whether it is at or before hi and on the raster.
  auto holds_centre = [](int64_t lo, int64_t hi, int n) {
    const int64_t a = lo - half;
    const int64_t i = std::max<int64_t>(0, a >= 0 ? (a + kSubpixelOne - 1) / kSubpixelOne : -((-a) / kSubpixelOne));
    return i < n && i * kSubpixelOne + half <= hi;
  };
  return holds_centre(x0, x1, width) && holds_centre(y0, y1, height);
}

}  // namespace

bool ScreenSceneBuilder::clip_holds_a_sample(int32_t clip) const {
  return covers_a_sample_centre(out_.clips[size_t(clip)].outline, out_.raster.width, out_.raster.height);
}

bool ScreenSceneBuilder::add(const std::vector<Vec3>& points, Vec3 n, double d, const SurfaceShade& shade,
                             Placement where, const PolygonSource& source) {
  if (!(std::fabs(d) > 0)) return false;  // the plane passes through the eye: seen edge-on
  ScreenPolygon poly;
  poly.outline = out_.take_outline();
  // Nothing of area on the raster, or it could colour no sample.
  if (!project(points, poly) || !covers_a_sample_centre(poly.outline, out_.raster.width, out_.raster.height)) {
    out_.keep_outline(std::move(poly.outline));
    return false;
  }
  poly.depth = raster_plane(n, d);  // 1/Z on the raster
  poly.clip = where.clip;
  poly.group = where.group;
  poly.rank = where.rank;
  poly.role = where.role;
  out_.polygons.push_back(std::move(poly));
  out_.shades.push_back(shade);
  out_.sources.push_back(source);
  if (drop_hidden_) remember_drawn();
  return true;
}

void ScreenSceneBuilder::cut_to(const Cell* cell) {
  cell_cut_.clear();
  cell_cut_world_.clear();
  if (!cell) return;
  for (const Face& f : cell->faces) {
    cell_cut_.push_back({camera_dir(f.plane.n), f.plane.eval(camera_.eye)});
    cell_cut_world_.push_back(f.plane);
  }
  cell_cut_box_ = cell->bounds();
}

bool ScreenSceneBuilder::beyond_cell(const Box3& box) const {
  if (cell_cut_world_.empty()) return false;
  if (!cell_cut_box_.meets(box, kOnCellFace)) return true;
  for (const Plane& p : cell_cut_world_) {
    // The box's corner least far along the plane's normal.
    const Vec3 least{p.n.x >= 0 ? box.lo.x : box.hi.x, p.n.y >= 0 ? box.lo.y : box.hi.y,
                     p.n.z >= 0 ? box.lo.z : box.hi.z};
    if (p.eval(least) > kOnCellFace) return true;
  }
  return false;
}

bool ScreenSceneBuilder::beyond_cell(const Mesh& mesh, const std::vector<int>& corners) const {
  for (const Plane& p : cell_cut_world_)
    if (std::all_of(corners.begin(), corners.end(),
                    [&](int v) { return p.eval(mesh.vertices[size_t(v)]) > kOnCellFace; }))
      return true;
  return false;
}

void ScreenSceneBuilder::drop_hidden() {
  if (drop_hidden_) return;
  drop_hidden_ = true;
  out_.drawn.reset(out_.raster.width, out_.raster.height, options_.per_side);
}

void ScreenSceneBuilder::remember_drawn() {
  const ScreenPolygon& poly = out_.polygons.back();
  // Remembering what is drawn pays where much is hidden (a steel frame seen down a bay),
  // not where little is (a furnished room): once kJudgedAfter polygons have been tested,
  // a picture that dropped under one in kPaysFrom of them stops remembering and testing.
  if (tested_ >= kJudgedAfter && dropped_ * kPaysFrom < tested_) {
    drop_hidden_ = false;
    return;
  }

  // Its corners [samples]; only a plane the scan's arithmetic holds is an occluder.
  corners_.clear();
  for (const FixedPoint& p : poly.outline)
    corners_.push_back({double(p.x) / kSubpixelOne, double(p.y) / kSubpixelOne});
  double least, most;
  if (!trusted_range(poly.depth, corners_, least, most)) return;
  const std::vector<FixedPoint>* clip =
      poly.clip >= 0 && size_t(poly.clip) < out_.clips.size() ? &out_.clips[size_t(poly.clip)].outline : nullptr;
  out_.drawn.cover(poly.outline, clip, clip ? poly.clip : -1, poly.depth);
}

RasterPlane ScreenSceneBuilder::raster_plane(Vec3 n, double d) const {
  // n·(d_xy·Z) + d = 0 with d_xy = (x, y, 1), x = x0 + step·u, y = y0 − step·v.
  const RasterMap& m = out_.raster;
  return {-n.x * m.step / d, n.y * m.step / d, -(n.x * m.x0 + n.y * m.y0 + n.z) / d};
}

bool ScreenSceneBuilder::hidden(const std::vector<Vec2>& corners, Vec3 n, double d, Vec2 lo, Vec2 hi, int32_t clip) {
  if (!drop_hidden_ || !(std::fabs(d) > 0)) return false;
  if (clip >= 0 && size_t(clip) < clip_box_.size()) {  // no sample outside the clip region's box is coloured
    const auto& [clip_lo, clip_hi] = clip_box_[size_t(clip)];
    lo = {std::max(lo.x, clip_lo.x), std::max(lo.y, clip_lo.y)};
    hi = {std::min(hi.x, clip_hi.x), std::min(hi.y, clip_hi.y)};
  }
  // The largest 1/Z the scan can give the polygon: the largest at a corner, plus the
  // plane's slope (1/Z per sample) over the 1/128 of a sample the rounded outline may reach
  // beyond the corners. Only for a plane the scan's arithmetic holds.
  const RasterPlane z = raster_plane(n, d);
  double least, most;
  if (!trusted_range(z, corners, least, most)) return false;
  ++tested_;
  const bool behind = out_.drawn.hides(lo, hi, most + (std::fabs(z.a) + std::fabs(z.b)) / 128);
  dropped_ += behind;
  return behind;
}

bool ScreenSceneBuilder::project(const std::vector<Vec3>& given, ScreenPolygon& poly) {
  // 2. An architect's cut, then the near plane, in 3D (each only when some corner lies
  // before it).
  const std::vector<Vec3>* kept = &given;
  if (has_cut_) {
    auto beyond = [this](Vec3 p) { return dot(cut_n_, p) + cut_d_; };
    if (!std::all_of(given.begin(), given.end(), [&](Vec3 p) { return beyond(p) >= 0; })) {
      cut(given, beyond, plane_cut_);
      if (plane_cut_.size() < 3) return false;
      kept = &plane_cut_;
    }
  }
  if (!cell_cut_.empty()) {
    std::vector<Vec3>* into = &cell_cut_a_;
    for (const CellPlane& p : cell_cut_) {
      auto inside = [&p](Vec3 q) { return kOnCellFace - (dot(p.n, q) + p.d); };
      if (std::all_of(kept->begin(), kept->end(), [&](Vec3 q) { return inside(q) >= 0; })) continue;
      cut(*kept, inside, *into);
      if (into->size() < 3) return false;
      kept = into;
      into = into == &cell_cut_a_ ? &cell_cut_b_ : &cell_cut_a_;
    }
  }
  const std::vector<Vec3>& points = *kept;
  const double near = camera_.near;
  const bool all_beyond = std::all_of(points.begin(), points.end(), [near](Vec3 p) { return p.z >= near; });
  if (!all_beyond) cut(points, [near](Vec3 p) { return p.z - near; }, near_cut_);
  const std::vector<Vec3>& in_front = all_beyond ? points : near_cut_;
  if (in_front.size() < 3) return false;
  // 3. Picture plane, then raster.
  raster_.clear();
  for (Vec3 p : in_front) raster_.push_back(out_.raster.raster_from_image({p.x / p.z, p.y / p.z}));
  // 4. Guard band (only when some corner lies outside it).
  const double lo = -guard_, hx = out_.raster.width + guard_, hy = out_.raster.height + guard_;
  if (!std::all_of(raster_.begin(), raster_.end(),
                   [&](Vec2 p) { return p.x >= lo && p.x <= hx && p.y >= lo && p.y <= hy; })) {
    cut(raster_, [lo](Vec2 p) { return p.x - lo; }, guard_cut_);
    cut(guard_cut_, [hx](Vec2 p) { return hx - p.x; }, raster_);
    cut(raster_, [lo](Vec2 p) { return p.y - lo; }, guard_cut_);
    cut(guard_cut_, [hy](Vec2 p) { return hy - p.y; }, raster_);
  }
  // 5. Fixed point, once.
  poly.outline.clear();
  for (Vec2 r : raster_) {
    const FixedPoint f = to_fixed(r);
    if (poly.outline.empty() || !(poly.outline.back() == f)) poly.outline.push_back(f);
  }
  while (poly.outline.size() > 1 && poly.outline.front() == poly.outline.back()) poly.outline.pop_back();
  return poly.outline.size() >= 3;
}

// --- the plan's lights ------------------------------------------------------------------

const SurfaceLight* ScreenSceneBuilder::surface_light(size_t k, const PolygonSource& source) const {
  switch (source.kind) {
    case PolygonSource::Kind::Face: return options_.shadows->on_face(k, source.cell, source.face);
    case PolygonSource::Kind::Object: return options_.shadows->on_object(k, source.mesh, source.polygon);
    case PolygonSource::Kind::Mesh: return nullptr;
  }
  return nullptr;
}

/// [fixed point] how far each piece of light or shadow is grown on the raster (a square's
/// Minkowski sum): more than the rounding of its corners, far less than a sample.
constexpr int64_t kPieceGrowth = kSubpixelOne / 64;

bool grow_convex(const std::vector<FixedPoint>& v, int64_t g, std::vector<FixedPoint>& out) {
  const size_t n = v.size();
  out.clear();
  const int sense = orientation(v);
  if (sense == 0) return false;
  const bool ccw = sense > 0;
  // The corners counter-clockwise; each side's outward normal (y, −x) by its quadrant: 0
  // for x > 0, y >= 0, then on counter-clockwise, each with the square's corner extreme there.
  auto corner_at = [&](size_t i) { return ccw ? v[i % n] : v[(n - i % n) % n]; };
  auto quadrant = [](int64_t nx, int64_t ny) {
    if (nx > 0 && ny >= 0) return 0;
    if (nx <= 0 && ny > 0) return 1;
    if (nx < 0 && ny <= 0) return 2;
    return 3;
  };
  auto side_quadrant = [&](size_t i) {
    const FixedPoint a = corner_at(i), b = corner_at(i + 1);
    return quadrant(b.y - a.y, a.x - b.x);
  };
  // Convex: no corner turns clockwise, and the sides' normals go round once.
  bool convex = true;
  int steps = 0;
  for (size_t i = 0, q = size_t(side_quadrant(n - 1)); i < n && convex; ++i) {
    convex = turn(corner_at(i + n - 1), corner_at(i), corner_at(i + 1)) >= 0;
    const size_t q_out = size_t(side_quadrant(i));
    steps += int((q_out + 4 - q) % 4);
    q = q_out;
  }
  if (!convex || steps != 4) {  // rounding left a tiny outline a hair concave: the hull of its moved corners
    std::vector<FixedPoint> pts;
    for (const FixedPoint& f : v) push_moved_by_square(f, g, pts);
    out = hull(pts, std::move(out));
    return out.size() >= 3;
  }
  constexpr int64_t kCornerX[4] = {1, -1, -1, 1}, kCornerY[4] = {1, 1, -1, -1};
  int q_in = side_quadrant(n - 1);
  for (size_t i = 0; i < n; ++i) {
    const FixedPoint p = corner_at(i);
    auto put = [&](int q) {
      const FixedPoint f{p.x + g * kCornerX[q], p.y + g * kCornerY[q]};
      if (out.empty() || !(out.back() == f)) out.push_back(f);
    };
    const int q_out = side_quadrant(i);
    put(q_in);
    for (int q = q_in; q != q_out;) put(q = (q + 1) % 4);
    q_in = q_out;
  }
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  return out.size() >= 3;
}

bool ScreenSceneBuilder::add_pieces(const SurfaceLight& s, LightTerm& term) {
  const size_t before = out_.pieces.size();
  std::vector<Vec3> cam;
  auto put = [&](const std::vector<Vec3>& world) {
    cam.clear();
    for (Vec3 p : world) cam.push_back(camera_.camera_from_world(p));
    ScreenPolygon piece;
    piece.outline = out_.take_outline();
    if (!project(cam, piece)) return out_.keep_outline(std::move(piece.outline));
    if (!grow_convex(piece.outline, kPieceGrowth, clip_points_)) return out_.keep_outline(std::move(piece.outline));
    piece.outline.swap(clip_points_);
    out_.pieces.push_back(std::move(piece));
  };
  term.first_piece = int32_t(before);
  term.whole = s.whole;
  if (!s.whole) {
    for (const auto& p : s.lit) put(p);
    term.lit_pieces = int32_t(out_.pieces.size() - before);
    if (term.lit_pieces == 0) return false;
  }
  const size_t shadows_from = out_.pieces.size();
  for (const auto& p : s.shadow) put(p);
  term.shadow_pieces = int32_t(out_.pieces.size() - shadows_from);
  return true;
}

SurfaceShade ScreenSceneBuilder::lit_planar_shade(const Material& m, Vec3 n, double d, Vec3 centroid, bool per_sample,
                                                  const PolygonSource& source) {
  return lit_shade(m, source, [&](const PointLight& light, Vec3 at, LightTerm& term) {
    return planar_light_term(m, n, d, centroid, at, light, *options_.lighting, per_sample, term);
  });
}

SurfaceShade ScreenSceneBuilder::lit_gouraud_shade(const Material& m, const std::array<Vec3, 3>& points,
                                                   const std::array<Vec3, 3>& normals, const PolygonSource& source) {
  return lit_shade(m, source, [&](const PointLight& light, Vec3 at, LightTerm& term) {
    return gouraud_light_term(m, points, normals, at, light, *options_.lighting, out_.raster, term);
  });
}

bool ScreenSceneBuilder::add_lit(const std::vector<Vec3>& points, Vec3 n, double d, const SurfaceShade& shade,
                                 Placement where, const PolygonSource& source, size_t pieces_before) {
  if (add(points, n, d, shade, where, source)) return true;
  out_.light_terms.resize(size_t(shade.first_term));
  out_.drop_pieces_from(pieces_before);
  return false;
}

bool ScreenSceneBuilder::add_face(const std::vector<Vec3>& polygon, const Plane& plane, const Material& material,
                                  Placement where, const PolygonSource& source, const Vec3* shade_at) {
  std::vector<Vec3>& cam = face_cam_;
  cam.clear();
  Vec3 centroid{0, 0, 0};
  for (Vec3 p : polygon) {
    cam.push_back(camera_.camera_from_world(p));
    centroid = centroid + cam.back();
  }
  centroid = shade_at ? camera_.camera_from_world(*shade_at) : (1.0 / double(cam.size())) * centroid;
  // The face's plane in camera space: n·P + (n·eye + d) = 0.
  const Vec3 n = camera_dir(plane.n);
  const double d = plane.eval(camera_.eye);
  if (drop_hidden_) {
    Vec2 lo, hi;
    if (on_raster(cam, polygon_raster_, lo, hi) && hidden(polygon_raster_, n, d, lo, hi, where.clip)) return false;
  }
  const bool smooth = options_.shading.model == ShadingModel::Smooth;  // Auto: a plane is flat
  if (lit()) {
    if (!(std::fabs(d) > 0)) return false;
    const size_t pieces = out_.pieces.size();
    return add_lit(cam, n, d, lit_planar_shade(material, n, d, centroid, smooth, source), where, source, pieces);
  }
  const SurfaceShade shade = !smooth ? flat_shade(material, n, centroid, options_.shading)
                                     : eye_light_shade(material, std::fabs(d) / length(n), options_.shading);
  return add(cam, n, d, shade, where, source);
}

void ScreenSceneBuilder::cull_outside(int32_t clip, double margin) {
  cull_ = clip >= 0 && size_t(clip) < out_.clips.size();
  if (!cull_) return;
  const std::vector<FixedPoint>& h = out_.clips[size_t(clip)].outline;  // a convex hull, no three corners in line
  const double one = double(kSubpixelOne);
  const auto& [lo, hi] = clip_box_[size_t(clip)];
  cull_lo_ = {lo.x - margin, lo.y - margin}, cull_hi_ = {hi.x + margin, hi.y + margin};
  cull_sides_.clear();
  for (size_t i = 0; i < h.size(); ++i) {
    // hull() turns counter-clockwise in (x, y) as stored: the inside lies to each side's left.
    const FixedPoint p = h[i], q = h[(i + 1) % h.size()];
    const double dx = double(q.x - p.x), dy = double(q.y - p.y), len = std::hypot(dx, dy);
    const double a = -dy / len, b = dx / len;
    cull_sides_.push_back({a, b, -(a * double(p.x) + b * double(p.y)) / one + margin});
  }
}

bool ScreenSceneBuilder::outside_cull_region(std::span<const Vec2> points, Vec2 lo, Vec2 hi) const {
  if (!cull_) return false;
  if (hi.x < cull_lo_.x || lo.x > cull_hi_.x || hi.y < cull_lo_.y || lo.y > cull_hi_.y) return true;
  for (const Side& side : cull_sides_)
    if (std::all_of(points.begin(), points.end(), [&side](Vec2 r) { return side.a * r.x + side.b * r.y + side.c < 0; }))
      return true;
  return false;
}

bool ScreenSceneBuilder::box_on_raster(const Box3& box, BoxOnRaster& out) const {
  out.lo = {HUGE_VAL, HUGE_VAL}, out.hi = {-HUGE_VAL, -HUGE_VAL};
  out.nearest = HUGE_VAL, out.farthest = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3 w{k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y, k & 4 ? box.hi.z : box.lo.z};
    const Vec3 c = camera_.camera_from_world(w);
    if (!(c.z >= camera_.near)) return false;
    const Vec2 r = out_.raster.raster_from_image({c.x / c.z, c.y / c.z});
    out.corners[size_t(k)] = r;
    out.lo = {std::min(out.lo.x, r.x), std::min(out.lo.y, r.y)};
    out.hi = {std::max(out.hi.x, r.x), std::max(out.hi.y, r.y)};
    out.nearest = std::min(out.nearest, c.z), out.farthest = std::max(out.farthest, c.z);
  }
  return true;
}

bool ScreenSceneBuilder::may_show(const Box3& box) const {
  if (!(box.lo.x <= box.hi.x && box.lo.y <= box.hi.y && box.lo.z <= box.hi.z)) return true;
  BoxOnRaster r;
  if (!box_on_raster(box, r)) return true;  // reaches the near plane: cannot tell here
  // What add_mesh_polygon would find of each polygon inside, found once for all of them.
  if (!may_cover_a_sample(r.lo, r.hi) || outside_cull_region(r.corners, r.lo, r.hi)) return false;
  // Behind what is drawn: no point inside is nearer than 1/nearest. A polygon's rounded
  // outline may reach 1/128 of a sample past its corners, where its plane's 1/Z may exceed
  // that by its slope; 1e-3 of 1/Z covers every plane turned more than about 1/4 degree
  // from edge-on (a sample is 1/700 of the window's width; docs/ACCURACY.md). A plane
  // nearer edge-on than that, lying within 1e-3 of the depth of what is drawn in front of
  // it, may lose a sample that rounding alone would have shown through.
  return !(drop_hidden_ && out_.drawn.hides(r.lo, r.hi, (1 + 1e-3) / r.nearest));
}

bool ScreenSceneBuilder::cell_faces_hidden(const Cell& cell, const std::vector<Vec2>& picture_polygon, double grow) {
  if (!drop_hidden_ || picture_polygon.empty()) return false;
  // Where the pieces could colour a sample: inside the clip region's box (the polygon's,
  // grown) and the box of the cell's projected box, whose corners' hull holds every piece.
  Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (Vec2 p : picture_polygon) {
    const Vec2 r = out_.raster.raster_from_image(p);
    lo = {std::min(lo.x, r.x), std::min(lo.y, r.y)}, hi = {std::max(hi.x, r.x), std::max(hi.y, r.y)};
  }
  const double reach = grow + 1.0 / 16;  // more than the clip region's rounding to the fixed point
  lo = {lo.x - reach, lo.y - reach}, hi = {hi.x + reach, hi.y + reach};
  BoxOnRaster box;
  if (!box_on_raster(cell.bounds(), box)) return false;
  lo = {std::max(lo.x, box.lo.x), std::max(lo.y, box.lo.y)}, hi = {std::min(hi.x, box.hi.x), std::min(hi.y, box.hi.y)};
  // What hidden() would find for each piece, from its own corners on the raster (inside the
  // hull of the box's):
  //   - its plane's largest 1/Z at a corner is the corner's own, at most 1/nearest (up to a
  //     rounding, the 1e-7 here), and to it the plane's slope over the 1/128 of a sample a
  //     rounded outline reaches past the corners is added;
  //   - its plane is trusted where |a·x| + |b·y| + |c| (convex: largest at a corner of the
  //     box's hull) stays within 1e8 times its least 1/Z (at least 1/farthest): asked here
  //     within half that.
  double most = (1 + 1e-7) / box.nearest;
  long pieces = 0;
  for (const Face& face : cell.faces) {
    const double d = face.plane.eval(camera_.eye);
    if (face.opaque.empty() || !(d < 0)) continue;
    const RasterPlane z = raster_plane(camera_dir(face.plane.n), d);
    double size = 0;
    for (Vec2 p : box.corners) size = std::max(size, std::fabs(z.a * p.x) + std::fabs(z.b * p.y) + std::fabs(z.c));
    if (!(size <= 0.5e8 / box.farthest)) return false;
    most = std::max(most, (1 + 1e-7) / box.nearest + (std::fabs(z.a) + std::fabs(z.b)) / 128);
    pieces += long(face.opaque.size());
  }
  if (pieces == 0) return true;  // nothing to add
  if (!out_.drawn.hides(lo, hi, most)) return false;
  tested_ += pieces, dropped_ += pieces;  // as add_face would have counted each
  return true;
}

bool ScreenSceneBuilder::may_cover_a_sample(Vec2 lo, Vec2 hi) const {
  const RasterMap& m = out_.raster;
  // Grown by 1/16 of a sample: far more than the 1/512 that rounding to the fixed point
  // moves a corner, so this is never stricter than covers_a_sample_centre on the outline
  // add() would make.
  constexpr double grow = 1.0 / 16;
  auto holds_centre = [](double from, double to, int n) {
    const double i = std::max(0.0, std::ceil(from - grow - 0.5));  // the first centre i + ½ at or after from
    return i < double(n) && i + 0.5 <= to + grow;
  };
  return holds_centre(lo.x, hi.x, m.width) && holds_centre(lo.y, hi.y, m.height);
}

bool ScreenSceneBuilder::on_raster(const std::vector<Vec3>& points, std::vector<Vec2>& corners, Vec2& lo,
                                   Vec2& hi) const {
  corners.clear();
  lo = {HUGE_VAL, HUGE_VAL}, hi = {-HUGE_VAL, -HUGE_VAL};
  for (const Vec3& c : points) {
    if (!(c.z >= camera_.near)) return false;
    const Vec2 r = out_.raster.raster_from_image({c.x / c.z, c.y / c.z});
    corners.push_back(r);
    lo = {std::min(lo.x, r.x), std::min(lo.y, r.y)};
    hi = {std::max(hi.x, r.x), std::max(hi.y, r.y)};
  }
  return true;
}

void ScreenSceneBuilder::add_mesh_polygon(const Mesh& mesh, const std::vector<int>& corners,
                                          const std::vector<Vec3>& corner_normals, const Material& material,
                                          Placement where, const PolygonSource& source) {
  // Wholly beyond the near plane, its corners on the raster tell what cannot show: a
  // polygon outside the region it will be clipped to, or one that holds no sample's centre.
  // Told first, from the corners' raster points alone: a far view of a steel frame drops
  // most of its triangles here.
  if (beyond_cell(mesh, corners)) return;  // cut_to: none of it in the cell
  std::vector<Vec2>& raster = polygon_raster_;
  raster.clear();
  Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  bool in_front = true;
  for (int v : corners) {
    project_vertex(mesh, v);
    const Vec2 r = mesh_raster_[size_t(v)];
    in_front &= !std::isnan(r.x);
    raster.push_back(r);
    lo = {std::min(lo.x, r.x), std::min(lo.y, r.y)};
    hi = {std::max(hi.x, r.x), std::max(hi.y, r.y)};
  }
  if (in_front && (outside_cull_region(raster, lo, hi) || !may_cover_a_sample(lo, hi))) return;
  std::vector<Vec3>& cam = polygon_cam_;
  cam.clear();
  Vec3 n{0, 0, 0}, centroid{0, 0, 0};
  for (size_t k = 0; k < corners.size(); ++k) {
    const Vec3 p = mesh.vertices[size_t(corners[k])], q = mesh.vertices[size_t(corners[(k + 1) % corners.size()])];
    n = n + cross(p, q);  // Newell's normal: outwards for counter-clockwise corners
    cam.push_back(mesh_cam_[size_t(corners[k])]);
    centroid = centroid + cam.back();
  }
  const double area = length(n);
  if (!(area > 0)) return;
  centroid = (1.0 / double(cam.size())) * centroid;
  const Vec3 nc = camera_dir(n);
  const double d = -dot(nc, centroid);
  // Drawn on its own plane (flat, or smooth where it is planar: below), a polygon wholly
  // behind what is drawn already goes too.
  auto behind = [&] { return in_front && hidden(raster, nc, d, lo, hi, where.clip); };
  // A piece of a polygon cut apart is lit from the whole polygon's centroid (Mesh::polygon_light).
  const Vec3 light_from = source.polygon >= 0 && size_t(source.polygon) < mesh.polygon_light.size()
                              ? camera_.camera_from_world(mesh.polygon_light[size_t(source.polygon)])
                              : centroid;
  // Crow 1981: a closed surface seen from inside is hidden, so a polygon facing away goes.
  if (options_.cull_back_faces && mesh.closed && !(d > 0)) return;
  const bool lit_here = lit() && source.kind == PolygonSource::Kind::Object && std::fabs(d) > 0;
  if (options_.shading.model == ShadingModel::Flat) {
    if (behind()) return;
    if (lit_here) {
      const size_t pieces = out_.pieces.size();
      add_lit(cam, nc, d, lit_planar_shade(material, nc, d, light_from, false, source), where, source, pieces);
      return;
    }
    add(cam, nc, d, flat_shade(material, nc, light_from, options_.shading), where, source);
    return;
  }
  // Smooth: a flat part of the mesh (every corner's normal the polygon's) is lit exactly
  // from its plane; a curved part by Gouraud over each triangle. Auto: the flat part flat.
  double min_cos = 1;
  for (const Vec3& cn : corner_normals) min_cos = std::min(min_cos, dot(cn, (1 / area) * n));
  bool planar = min_cos > 1 - 1e-9;
  // Auto: curved means a smooth surface cut into polygons — corner normals near the
  // polygon's own (a box's corners keep their faces' normals: plans/mesh.h).
  if (options_.shading.model == ShadingModel::Auto && min_cos < kCurvedCos) planar = true;
  if (planar) {
    if (behind()) return;
    const bool smooth = options_.shading.model == ShadingModel::Smooth;
    if (lit_here) {
      const size_t pieces = out_.pieces.size();
      add_lit(cam, nc, d, lit_planar_shade(material, nc, d, light_from, smooth, source), where, source, pieces);
      return;
    }
    add(cam, nc, d,
        smooth ? eye_light_shade(material, std::fabs(d) / area, options_.shading)
               : flat_shade(material, nc, light_from, options_.shading),
        where, source);
    return;
  }
  for (size_t k = 1; k + 1 < corners.size(); ++k) {
    const size_t c[3] = {0, k, k + 1};
    std::array<Vec3, 3> points, normals;
    for (size_t i = 0; i < 3; ++i) {
      points[i] = cam[c[i]];
      normals[i] = camera_dir(corner_normals[c[i]]);
    }
    const Vec3 tn = cross(points[1] - points[0], points[2] - points[0]);
    const double td = -dot(tn, points[0]);
    if (lit() && source.kind == PolygonSource::Kind::Object) {
      if (!(std::fabs(td) > 0)) continue;
      // The side the eye sees: a polygon seen from behind (an open mesh) turns its normals.
      // (nc and d, not tn and td: camera space is left-handed, so a cross product of camera
      // coordinates points the other way.)
      if (!(d > 0))
        for (Vec3& v : normals) v = -1.0 * v;
      const size_t pieces = out_.pieces.size();
      add_lit({points.begin(), points.end()}, tn, td, lit_gouraud_shade(material, points, normals, source), where,
              source, pieces);
      continue;
    }
    SurfaceShade shade;
    if (gouraud_shade(material, points, normals, options_.shading, out_.raster, shade))
      add({points.begin(), points.end()}, tn, td, shade, where, source);
  }
}

void ScreenSceneBuilder::add_mesh(const Mesh& mesh, const MeshPaint& paint, Placement where, PolygonSource source,
                                  bool polygons, const PolygonRuns* runs) {
  const size_t n = mesh.triangles.size();
  // Meshes made here and there all carry corner normals; one that does not gets them now.
  Mesh with_normals;
  const Mesh* m = &mesh;
  if (mesh.corner_normals.size() != 3 * n) {
    with_normals = mesh;
    smooth_corner_normals(with_normals);
    m = &with_normals;
  }
  const std::vector<Vec3>& cn = m->corner_normals;
  // Vertices go to camera space and the raster when a polygon looked at first needs them (project_vertex).
  mesh_cam_.resize(mesh.vertices.size());
  mesh_raster_.resize(mesh.vertices.size());
  mesh_cam_mark_.resize(mesh.vertices.size(), 0);
  if (++mesh_mark_ == 0) {
    std::fill(mesh_cam_mark_.begin(), mesh_cam_mark_.end(), 0);
    mesh_mark_ = 1;
  }
  const bool by_runs = runs && !runs->first.empty() && runs->first.size() == runs->boxes.size() &&
                       runs->first[0] == 0 && runs->first.back() < n;
  const size_t run_count = by_runs ? runs->first.size() : 1;
  std::vector<int> corners;
  std::vector<Vec3> normals;
  for (size_t r = 0; r < run_count; ++r) {
    if (by_runs && (beyond_cell(runs->boxes[r]) || !may_show(runs->boxes[r]))) continue;
    const size_t t0 = by_runs ? runs->first[r] : 0, t1 = by_runs && r + 1 < run_count ? runs->first[r + 1] : n;
    for (size_t t = t0; t < t1;) {
      const int polygon = mesh.polygon_of[t];
      size_t end = t + 1;
      while (polygons && end < t1 && mesh.polygon_of[end] == polygon) ++end;
      source.polygon = polygon;
      const Material& material = paint.of_polygon(polygon);
      // The input polygon again, from its fan (plans/mesh.h triangulates a polygon a, b, c,
      // d, ... as abc, acd, ...); a polygon that was not a fan goes triangle by triangle.
      corners.assign(mesh.triangles[t].begin(), mesh.triangles[t].end());
      normals.assign(cn.begin() + std::ptrdiff_t(3 * t), cn.begin() + std::ptrdiff_t(3 * t + 3));
      bool fan = true;
      for (size_t k = t + 1; k < end && fan; ++k) {
        fan = mesh.triangles[k][0] == corners[0] && mesh.triangles[k][1] == corners.back();
        corners.push_back(mesh.triangles[k][2]);
        normals.push_back(cn[3 * k + 2]);
      }
      if (fan) {
        add_mesh_polygon(mesh, corners, normals, material, where, source);
      } else {
        for (size_t k = t; k < end; ++k) {
          triangle_corners_.assign(mesh.triangles[k].begin(), mesh.triangles[k].end());
          triangle_normals_.assign(cn.begin() + std::ptrdiff_t(3 * k), cn.begin() + std::ptrdiff_t(3 * k + 3));
          add_mesh_polygon(mesh, triangle_corners_, triangle_normals_, material, where, source);
        }
      }
      t = end;
    }
  }
}

ScreenScene screen_scene_of_meshes(const std::vector<Mesh>& meshes, const std::vector<MeshPaint>& paints,
                                   const Camera& camera, const SceneOptions& options) {
  ScreenScene out;
  ScreenSceneBuilder b(camera, options, out);
  if (options.drop_hidden) b.drop_hidden();  // one group of objects: depth decides everywhere
  static const MeshPaint kDefault;
  for (size_t i = 0; i < meshes.size(); ++i) {
    PolygonSource source;
    source.kind = PolygonSource::Kind::Mesh;
    source.mesh = int(i);
    b.add_mesh(meshes[i], i < paints.size() ? paints[i] : kDefault, {}, source);
  }
  return out;
}

}  // namespace avenues
