// Avenues — the architect's drawings (see architectural_drawing.h).
#include "render/architectural_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>

#include "core/angles.h"
#include "core/thread_arena.h"
#include "render/interval_clip.h"
#include "render/stroke_merge.h"

namespace avenues {

namespace {

constexpr double kOnCut = 1e-9;  ///< [m] a vertex this close to the cut plane lies in it
constexpr double kMargin = 1.0;  ///< [m] around what the picture shows

Vec2 raster_of(const Camera& cam, const ImageToRaster& to_raster, Vec3 world) {
  return to_raster(cam.image_from_camera(cam.camera_from_world(world)));
}

/// Clips the raster segment a→b to the page [0, w] × [0, h]; false when nothing is left.
bool clip_to_page(Vec2& a, Vec2& b, double w, double h) {
  detail::Interval s{0, 1};
  const double f[4][2] = {{a.x, b.x}, {w - a.x, w - b.x}, {a.y, b.y}, {h - a.y, h - b.y}};
  for (const auto& g : f)
    if (!detail::clip_interval(s, g[0], g[1])) return false;
  const Vec2 d = b - a;
  const Vec2 a2 = a + s.t0 * d, b2 = a + s.t1 * d;
  a = a2, b = b2;
  return true;
}

/// The building: every cell inside it and every solid it names, or the far box's middle when it has none.
}  // namespace

DrawingTooLarge::DrawingTooLarge(double metres_across, double pixels)
    : std::runtime_error("the drawing would be " + std::to_string(long(pixels)) + " pixels across, over the " +
                         std::to_string(long(kMaxDrawingPixels)) + " a picture may have"),
      metres(metres_across) {}

Box3 building_bounds(const CellComplex& c) {
  Box3 b{{HUGE_VAL, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
  auto add = [&](Vec3 p) {
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
  };
  for (const Cell& cell : c.cells)
    if (cell.kind != CellKind::Outside && cell.kind != CellKind::Sky) {
      const Box3 cb = cell.bounds();
      add(cb.lo), add(cb.hi);
    }
  for (const auto& s : c.solids)
    for (Vec2 q : s.quad) add({q.x, q.y, s.z0}), add({q.x, q.y, s.z1});
  if (!(b.lo.x <= b.hi.x)) {
    const Vec3 m = 0.5 * (c.far_box.lo + c.far_box.hi);
    b = {m, m};
  }
  return b;
}

namespace {

/// A parallel camera looking along `forward` (unit), its window fitted around `box` as the
/// picture sees it, with its eye on the plane through `on_plane` perpendicular to forward.
Camera fitted_camera(Vec3 forward, const Box3& box, Vec3 on_plane, double px_per_m) {
  Camera cam = Camera::parallel(on_plane, on_plane + forward, 1, 1, 1);
  double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
  for (int k = 0; k < 8; ++k) {
    const Vec3 p{k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y, k & 4 ? box.hi.z : box.lo.z};
    const Vec3 q = cam.camera_from_world(p);
    x0 = std::min(x0, q.x), x1 = std::max(x1, q.x), y0 = std::min(y0, q.y), y1 = std::max(y1, q.y);
  }
  x0 -= kMargin, x1 += kMargin, y0 -= kMargin, y1 += kMargin;
  const double w = std::ceil((x1 - x0) * px_per_m), h = std::ceil((y1 - y0) * px_per_m);
  if (w > kMaxDrawingPixels || h > kMaxDrawingPixels) throw DrawingTooLarge(std::max(x1 - x0, y1 - y0), std::max(w, h));
  cam.width = int(w), cam.height = int(h);
  cam.view_width = w / px_per_m;
  // The window's centre over the middle of the box (shifted in the picture plane, not along the rays).
  cam.eye = cam.eye + (0.5 * (x0 + x1)) * cam.right + (0.5 * (y0 + y1)) * cam.up;
  return cam;
}

}  // namespace

ArchitecturalView plan_view(const CellComplex& c, StoreyId st, double cut_height, double px_per_m) {
  const Box3 b = building_bounds(c);
  const Vec3 mid = 0.5 * (b.lo + b.hi);
  const double z = (st >= 0 ? c.storeys[size_t(st)].elevation : b.lo.z) + cut_height;
  ArchitecturalView s;
  s.kind = "plan";
  s.camera = fitted_camera({0, 0, -1}, b, {mid.x, mid.y, z}, px_per_m);
  s.cut = {{0, 0, 1}, -z};
  s.options.labels = st;
  return s;
}

ArchitecturalView section_view(const CellComplex& c, Vec2 p1, Vec2 p2, double px_per_m) {
  const Box3 b = building_bounds(c);
  const Vec2 d = (1.0 / length(p2 - p1)) * (p2 - p1);
  const Vec3 f{-d.y, d.x, 0};  // to the line's left
  const Box3 span{{std::min(p1.x, p2.x), std::min(p1.y, p2.y), b.lo.z}, {std::max(p1.x, p2.x), std::max(p1.y, p2.y), b.hi.z}};
  const Vec2 m = 0.5 * (p1 + p2);
  ArchitecturalView s;
  s.kind = "section";
  s.camera = fitted_camera(f, span, {m.x, m.y, 0.5 * (b.lo.z + b.hi.z)}, px_per_m);
  s.cut = {f, -dot(f, Vec3{p1.x, p1.y, 0})};
  return s;
}

namespace {

/// Looking at the building from `toward_viewer` (unit), the picture plane just outside it.
ArchitecturalView from_outside(const CellComplex& c, Vec3 toward_viewer, std::optional<double> cut_z, double px_per_m) {
  Box3 b = building_bounds(c);
  if (cut_z) b.hi.z = std::max(b.lo.z, std::min(b.hi.z, *cut_z));  // what is above the cut is not drawn
  const Vec3 mid = 0.5 * (b.lo + b.hi);
  double reach = 0;
  for (int k = 0; k < 8; ++k) {
    const Vec3 p{k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z};
    reach = std::max(reach, dot(p - mid, toward_viewer));
  }
  const Vec3 f = -1.0 * toward_viewer;
  ArchitecturalView s;
  s.camera = fitted_camera(f, b, mid + (reach + 0.5) * toward_viewer, px_per_m);
  s.options.cut = bool(cut_z);
  s.cut = cut_z ? Plane{{0, 0, 1}, -*cut_z} : Plane{f, -dot(f, s.camera.eye)};
  if (!cut_plane_usable(s.camera, s.cut)) throw std::runtime_error("a horizontal cut needs a view from above");
  return s;
}

}  // namespace

ArchitecturalView elevation_view(const CellComplex& c, double azimuth_deg, double px_per_m) {
  const double a = rad_from_deg(azimuth_deg);
  ArchitecturalView s = from_outside(c, {std::cos(a), std::sin(a), 0}, std::nullopt, px_per_m);
  s.kind = "elevation";
  return s;
}

ArchitecturalView axonometric_view(const CellComplex& c, double azimuth_deg, double altitude_deg,
                                   std::optional<double> cut_z, double px_per_m) {
  const double az = rad_from_deg(azimuth_deg), alt = rad_from_deg(altitude_deg);
  ArchitecturalView s =
      from_outside(c, {std::cos(alt) * std::cos(az), std::cos(alt) * std::sin(az), std::sin(alt)}, cut_z, px_per_m);
  s.kind = "axonometric";
  return s;
}

// Closed: a polygon touching the plane along an edge gives that edge (a jamb of a window whose
// sill lies exactly in the cut), so that the wall's outline closes there too.
bool cut_segment(const std::vector<Vec3>& poly, const Plane& cut, Vec3& a, Vec3& b) {
  const double scale = length(cut.n);
  auto side = [&](Vec3 p) {
    const double e = cut.eval(p) / scale;
    return std::fabs(e) <= kOnCut ? 0.0 : e;
  };
  // Most polygons lie wholly to one side: settled without gathering points.
  bool below = false, above = false;
  for (const Vec3& p : poly) {
    const double e = side(p);
    below |= e <= 0, above |= e >= 0;
  }
  if (!below || !above) return false;
  thread_local std::vector<Vec3> at;
  at.clear();
  bool off = false;
  for (size_t k = 0; k < poly.size(); ++k) {
    const Vec3 p = poly[k], q = poly[(k + 1) % poly.size()];
    const double ep = side(p), eq = side(q);
    off |= ep != 0;
    if (ep == 0) at.push_back(p);
    else if ((ep < 0 && eq > 0) || (ep > 0 && eq < 0)) at.push_back(p + (ep / (ep - eq)) * (q - p));
  }
  if (!off || at.size() < 2) return false;  // in the plane, or missed
  // The two points farthest apart (a convex polygon meets a plane in one segment).
  double best = 0;
  for (size_t i = 0; i < at.size(); ++i)
    for (size_t j = i + 1; j < at.size(); ++j)
      if (const Vec3 d = at[j] - at[i]; dot(d, d) > best) best = dot(d, d), a = at[i], b = at[j];
  return best > kOnCut * kOnCut;
}

Drawing draw_architectural(const CellComplex& c, const LineScene& scene, const Camera& cam, const Plane& cut,
                           const VisibleSet& vs, const ArchitecturalOptions& options) {
  LineOptions lo;
  lo.cut = cut;  // the objects beyond it are drawn, and hide the lines behind them
  lo.merge = !options.cut;  // with the cut, merged once below
  lo.threads = options.threads;
  Drawing d = draw_view(c, scene, cam, vs, lo);
  for (Stroke& s : d.strokes)
    if (s.layer == Layer::Architecture) s.layer = Layer::Beyond;

  const ImageToRaster to_raster = cam.image_to_raster();
  if (options.cut) {
    // The cut outlines: each opaque polygon of a cut cell that the plane meets (in chunks
    // of cells on options.threads threads, joined in order).
    const size_t chunks = options.threads == 1 || vs.cut_cells.size() < 1024 ? 1 : 16;
    std::vector<std::vector<Stroke>> outlines(chunks);
    for_each_chunk(options.threads, vs.cut_cells.size(), chunks, [&](size_t chunk, size_t first, size_t last) {
      for (size_t i = first; i < last; ++i)
        for (const Face& f : c.cells[size_t(vs.cut_cells[i])].faces)
          for (const OpaquePoly& op : f.opaque) {
            Vec3 wa, wb;
            if (!cut_segment(op.poly, cut, wa, wb)) continue;
            Vec2 a = raster_of(cam, to_raster, wa), b = raster_of(cam, to_raster, wb);
            if (clip_to_page(a, b, d.width, d.height)) outlines[chunk].push_back({a, b, Weight::Cut, Layer::Cut});
          }
    });
    for (const std::vector<Stroke>& o : outlines) d.strokes.insert(d.strokes.end(), o.begin(), o.end());
    // The fill: the page less the cross-sections (the avenues the search started from).
    d.fill.push_back({{0, 0}, {double(d.width), 0}, {double(d.width), double(d.height)}, {0, double(d.height)}});
    for (const Avenue& a : vs.avenues) {
      if (a.parent >= 0 || a.mask.size() < 3) continue;
      std::vector<Vec2> ring;
      for (Vec2 m : a.mask) ring.push_back(to_raster(m));
      d.fill.push_back(std::move(ring));
    }
    merge_collinear(d.strokes, options.threads);  // the cut keeps what it shares with a line beyond
  }

  if (options.labels >= 0) {
    // Each named room of the storey at its largest cell the cut crosses, as the plan SVG has them.
    std::map<RoomId, std::pair<double, Vec3>> at;
    for (CellId id : vs.cut_cells) {
      const Cell& cell = c.cells[size_t(id)];
      if (cell.kind != CellKind::Room || cell.room < 0 || cell.storey != options.labels) continue;
      const double area = std::fabs(signed_area(cell.footprint));
      const Vec2 m = centroid(cell.footprint);
      auto it = at.find(cell.room);
      if (it == at.end() || area > it->second.first) at[cell.room] = {area, Vec3{m.x, m.y, 0.5 * (cell.z0 + cell.z1)}};
    }
    for (const auto& [room, where] : at) {
      const RoomInfo& r = c.rooms[size_t(room)];
      if (!r.named || r.name.empty()) continue;
      const Vec2 p = raster_of(cam, to_raster, where.second);
      d.labels.push_back({p, r.name, options.label_height});
      if (r.area > 0) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.1f m\xc2\xb2", r.area);
        d.labels.push_back({p + Vec2{0, 1.8 * options.label_height}, buf, 0.75 * options.label_height});
      }
    }
  }
  return d;
}

}  // namespace avenues
