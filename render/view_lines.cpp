// Avenues — the hidden-line drawing of a view (see view_lines.h).
#include "render/view_lines.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include "core/thread_arena.h"
#include "render/interval_clip.h"
#include "render/scene_objects.h"
#include "render/shadow_outline.h"
#include "render/stroke_merge.h"

namespace avenues {

namespace {

using detail::clip_interval;
using detail::KeyedInterval;
using detail::Interval;

constexpr double kTouch = 1e-9;   ///< pieces of one line closer than this (in its parameter) are one piece

/// The mask's edges as camera-space half-spaces s·P >= 0 (interval_clip.h): the left side of the
/// edge p→q of a counter-clockwise mask, cross(q − p, (X/Z, Y/Z) − p) >= 0, times Z.
///
/// An exact mask may keep two vertices a rounding apart (two nearly parallel portal edges,
/// both kept in exact arithmetic). The edge between them has a direction made of rounding
/// noise, and its half-plane would cut lines at random; so a vertex within kSameVertex of
/// the last one kept is skipped, and its neighbours' edges bound the mask there (what is
/// lost is a corner smaller than a millionth of a pixel).
void mask_sides(const std::vector<Vec2>& mask, std::vector<Vec3>& sides) {
  constexpr double kSameVertex = 1e-9;  ///< on the picture plane (x = X/Z): ~1e-6 px at 1920 px across 90°
  sides.clear();
  std::vector<Vec2> kept;
  kept.reserve(mask.size());
  auto same = [&](Vec2 a, Vec2 b) {
    return std::fabs(a.x - b.x) + std::fabs(a.y - b.y) <= kSameVertex * (1 + std::fabs(a.x) + std::fabs(a.y));
  };
  for (Vec2 v : mask)
    if (kept.empty() || !same(v, kept.back())) kept.push_back(v);
  while (kept.size() > 1 && same(kept.front(), kept.back())) kept.pop_back();
  if (kept.size() < 3) kept = mask;  // a mask that small: as it is
  for (size_t k = 0; k < kept.size(); ++k) {
    const Vec2 p = kept[k], q = kept[(k + 1) % kept.size()];
    const double dx = q.x - p.x, dy = q.y - p.y;
    sides.push_back({-dy, dx, dy * p.x - dx * p.y});
  }
}

/// How world points reach the picture: in homogeneous picture coordinates (camera space for
/// a perspective, (X, Y, 1) for a parallel projection: both linear along a segment, and the
/// image point is (x/z, y/z)), and how far beyond the near plane they lie (parallel: beyond
/// the cut plane, or the picture plane when there is none).
struct Projector {
  const Camera& cam;
  Plane beyond;  ///< parallel: eval >= 0 beyond the plane the rays start from
  Projector(const Camera& c, const std::optional<Plane>& cut) : cam(c) {
    beyond = cut ? *cut : c.picture_plane();
    if (dot(beyond.n, c.forward) < 0) beyond = {-1.0 * beyond.n, -beyond.d};
  }
  Vec3 picture(Vec3 world) const {
    const Vec3 p = cam.camera_from_world(world);
    return cam.is_parallel() ? Vec3{p.x, p.y, 1} : p;
  }
  double depth(Vec3 world) const {
    return cam.is_parallel() ? beyond.eval(world) : cam.camera_from_world(world).z - cam.near;
  }
};

/// Cuts the world segment w0→w1 (parameters of `s`) to the near plane and the mask.
bool clip_to_avenue(Interval& s, const Projector& pr, Vec3 w0, Vec3 w1, const std::vector<Vec3>& sides) {
  if (!clip_interval(s, pr.depth(w0), pr.depth(w1))) return false;
  const Vec3 p0 = pr.picture(w0), p1 = pr.picture(w1);
  for (const Vec3& n : sides)
    if (!clip_interval(s, dot(n, p0), dot(n, p1))) return false;
  return true;
}

/// Appends the strokes of the intervals of segment p0→p1 in homogeneous picture coordinates.
void add_strokes(const ImageToRaster& to_raster, Vec3 p0, Vec3 p1, const std::vector<Interval>& intervals, Weight weight,
                 Layer layer, std::vector<Stroke>& out) {
  const Vec3 d = p1 - p0;
  auto raster = [&](double t) {
    const Vec3 p = p0 + t * d;
    return to_raster({p.x / p.z, p.y / p.z});
  };
  for (const Interval& s : intervals) out.push_back({raster(s.t0), raster(s.t1), weight, layer});
}

/// Calls f(key, intervals) for each key of merged, sorted pieces [first, last).
template <class F>
void for_each_line(const KeyedInterval* first, const KeyedInterval* last, std::vector<Interval>& intervals, F&& f) {
  for (const KeyedInterval* i = first; i < last;) {
    intervals.clear();
    const KeyedInterval* j = i;
    for (; j < last && j->key == i->key; ++j) intervals.push_back(j->interval);
    f(i->key, intervals);
    i = j;
  }
}
template <class F>
void for_each_line(const std::vector<KeyedInterval>& pieces, std::vector<Interval>& intervals, F&& f) {
  for_each_line(pieces.data(), pieces.data() + pieces.size(), intervals, std::forward<F>(f));
}

/// One furniture edge to draw in this view.
struct SeenEdge {
  int32_t piece, edge;
  Weight weight;
};

/// The outlines of the shadows on the faces each avenue sees, clipped to its mask like the
/// lines of its cell and hidden behind furniture like them (Layer::Shadows, thin).
void draw_shadow_outlines(const CellComplex& c, const LineScene& scene, const Camera& cam, const VisibleSet& vs,
                          const OccluderGrid& occluders, std::vector<Stroke>& out) {
  if (scene.shadows.lights.empty()) return;
  const Projector pr(cam, std::nullopt);
  const ImageToRaster to_raster = cam.image_to_raster();
  std::vector<std::array<Vec3, 2>> segments;  // every outline segment of every face seen, once
  std::map<std::pair<size_t, int32_t>, std::pair<int32_t, int32_t>> of_face;  // (light, global face) -> segments
  std::vector<Vec3> sides;
  std::vector<KeyedInterval> pieces;
  for (const Avenue& a : vs.avenues) {
    mask_sides(a.mask, sides);
    const Cell& cell = c.cells[size_t(a.cell)];
    for (size_t k = 0; k < cell.faces.size(); ++k) {
      const Face& f = cell.faces[k];
      if (f.opaque.empty() || !(f.plane.eval(cam.eye) < 0)) continue;
      for (size_t l = 0; l < scene.shadows.lights.size(); ++l) {
        const SurfaceLight* s = scene.shadows.on_face(l, a.cell, int(k));
        if (!s) continue;
        const int32_t face = scene.shadows.face_base[size_t(a.cell)] + int32_t(k);
        auto [it, fresh] = of_face.try_emplace({l, face}, int32_t(segments.size()), int32_t(segments.size()));
        if (fresh) {
          for (const auto& e : shadow_outline(f.poly, *s)) segments.push_back(e);
          it->second.second = int32_t(segments.size());
        }
        for (int32_t i = it->second.first; i < it->second.second; ++i) {
          Interval iv{0, 1};
          const auto& e = segments[size_t(i)];
          if (clip_to_avenue(iv, pr, e[0], e[1], sides))
            pieces.push_back({i, iv});
        }
      }
    }
  }
  std::vector<Interval> intervals;
  detail::merge_intervals(pieces, kTouch);
  for_each_line(pieces, intervals, [&](int32_t i, std::vector<Interval>& iv) {
    const Vec3 p0 = cam.camera_from_world(segments[size_t(i)][0]), p1 = cam.camera_from_world(segments[size_t(i)][1]);
    hide_behind(occluders, p0, p1, iv);
    add_strokes(to_raster, p0, p1, iv, Weight::Crease, Layer::Shadows, out);
  });
}

}  // namespace

LineScene prepare_line_scene(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                             const LineOptions& options) {
  LineScene scene{line_faces(complex), furniture_of(complex, objects), {}, {}};
  if (!options.shadows) return scene;
  scene.lighting = lighting_of(complex, Shading{}, Lights::Plan, false, false);
  scene.shadows = cast_shadows(complex, objects, scene.lighting);
  return scene;
}

LineScene prepare_line_scene(const CellComplex& complex, const LineOptions& options) {
  return prepare_line_scene(complex, place_objects(complex), options);
}

LineScene prepare_line_scene(const CellComplex& complex) { return prepare_line_scene(complex, LineOptions{}); }

Drawing draw_view(const CellComplex& c, const LineScene& scene, const Camera& cam, const VisibleSet& vs,
                  const LineOptions& options) {
  if (vs.conservative)
    throw std::invalid_argument("a hidden-line drawing needs exact masks, not the hull search's (exact_masks)");
  Drawing d;
  const Projector pr(cam, options.cut);
  const ImageToRaster to_raster = cam.image_to_raster();
  d.width = cam.width;
  d.height = cam.height;
  d.title = c.plan_name;

  // Furniture in a visible cell: the edges it shows from this eye, and the triangles that hide
  // (in a parallel projection what of them lies beyond the cut).
  std::vector<SeenEdge> seen;
  std::vector<int32_t> seen_start;  // per piece, into `seen`; empty unless drawn
  std::map<CellId, std::vector<int32_t>> drawn_in;  // per visible cell: its pieces with edges seen, ascending
  OccluderGrid occluders;
  if (options.furniture) {
    const auto& pieces = scene.furniture.pieces;
    seen_start.assign(pieces.size() + 1, 0);
    std::vector<Occluder> hiding;
    for (size_t i = 0; i < pieces.size(); ++i) {
      const FurniturePiece& p = pieces[i];
      seen_start[i] = int32_t(seen.size());
      const bool visible = std::any_of(p.cells.begin(), p.cells.end(), [&](CellId id) {
        return std::binary_search(vs.cells.begin(), vs.cells.end(), id);
      });
      if (!visible) continue;
      const std::vector<uint8_t> facing = polygons_facing(p, cam);
      for (size_t e = 0; e < p.edges.size(); ++e) {
        Weight w;
        if (edge_is_seen(p.edges[e], facing, options.crease_deg, w)) seen.push_back({int32_t(i), int32_t(e), w});
      }
      if (seen_start[i] != int32_t(seen.size()))
        for (CellId id : p.cells) drawn_in[id].push_back(int32_t(i));
      add_occluders(p, facing, cam, hiding, &pr.beyond);
    }
    seen_start[pieces.size()] = int32_t(seen.size());
    occluders = OccluderGrid(std::move(hiding), cam.is_parallel());
  }

  // A line seen end-on in a parallel projection (a wall's vertical edge in a plan) is a
  // point on paper, shorter than any stroke drawn: none of its pieces need clipping.
  auto seen_end_on = [&](const RealLine& l) {
    const Vec3 p0 = pr.picture(l.a), p1 = pr.picture(l.b);
    const Vec2 across = to_raster({p1.x, p1.y}) - to_raster({p0.x, p0.y});
    return dot(across, across) < kShortestStroke * kShortestStroke;
  };

  // Jones: each avenue's cell, its lines clipped to the avenue's mask. In chunks of
  // avenues on options.threads threads, joined in order: the same pieces with any number.
  const size_t chunks = options.threads == 1 || vs.avenues.size() < 1024 ? 1 : 16;
  std::vector<std::vector<KeyedInterval>> chunk_lines(chunks), chunk_edges(chunks);
  for_each_chunk(options.threads, vs.avenues.size(), chunks, [&](size_t chunk, size_t first, size_t last) {
    std::vector<Vec3> sides;
    std::vector<KeyedInterval>& lines = chunk_lines[chunk];  // keyed by LineId
    std::vector<KeyedInterval>& edges = chunk_edges[chunk];  // keyed by index into `seen`
    for (size_t ai = first; ai < last; ++ai) {
      const Avenue& a = vs.avenues[ai];
      mask_sides(a.mask, sides);
      const Cell& cell = c.cells[size_t(a.cell)];
      const uint8_t* shows = scene.faces.shows.data() + scene.faces.cell_start[size_t(a.cell)];
      // The cell's lines lie anywhere in the complex's table: ask for them all at once, so
      // that their loads overlap instead of waiting one after the other.
      for (const CellLine& cl : cell.lines) __builtin_prefetch(&c.lines[size_t(cl.line)]);
      for (size_t k = 0; k < cell.lines.size(); ++k) {
        if (!shows[k]) continue;  // the far side of a wall of no thickness
        const CellLine& cl = cell.lines[k];
        const RealLine& l = c.lines[size_t(cl.line)];
        if (cam.is_parallel() && seen_end_on(l)) continue;
        Interval s{cl.t0, cl.t1};
        if (clip_to_avenue(s, pr, l.a, l.b, sides))
          lines.push_back({cl.line, s});
      }
      if (seen.empty()) continue;
      const auto in_cell = drawn_in.find(a.cell);
      if (in_cell == drawn_in.end()) continue;
      for (const int32_t i : in_cell->second) {
        const FurniturePiece& p = scene.furniture.pieces[size_t(i)];
        for (int32_t k = seen_start[size_t(i)]; k < seen_start[size_t(i) + 1]; ++k) {
          const FurnitureEdge& e = p.edges[size_t(seen[size_t(k)].edge)];
          const Vec3 w0 = p.mesh.vertices[size_t(e.v[0])], w1 = p.mesh.vertices[size_t(e.v[1])];
          Interval s{0, 1};
          bool alive = true;
          for (size_t f = 0; f < cell.faces.size() && alive; ++f) {  // inside the cell's prism
            const Plane& pl = cell.faces[f].plane;
            alive = clip_interval(s, kOnCellFace - pl.eval(w0), kOnCellFace - pl.eval(w1));
          }
          if (alive && clip_to_avenue(s, pr, w0, w1, sides))
            edges.push_back({k, s});
        }
      }
    }
  });
  auto joined = [](std::vector<std::vector<KeyedInterval>>& parts) {
    std::vector<KeyedInterval> all = std::move(parts[0]);
    for (size_t k = 1; k < parts.size(); ++k) all.insert(all.end(), parts[k].begin(), parts[k].end());
    return all;
  };
  std::vector<KeyedInterval> lines = joined(chunk_lines), edges = joined(chunk_edges);

  // Each line once: the union of its pieces, less what furniture hides, as strokes. In
  // chunks of whole lines on options.threads threads, joined in order (the same strokes).
  std::vector<Interval> intervals;
  detail::merge_intervals(lines, kTouch);
  {
    const size_t line_chunks = options.threads == 1 || lines.size() < 4096 ? 1 : 16;
    std::vector<std::vector<Stroke>> parts(line_chunks);
    for_each_chunk(options.threads, lines.size(), line_chunks, [&](size_t chunk, size_t first, size_t last) {
      // The lines that start in [first, last): a line's pieces all go to the chunk of its first.
      while (first > 0 && first < last && lines[first].key == lines[first - 1].key) ++first;
      while (last < lines.size() && last > first && lines[last].key == lines[last - 1].key) ++last;
      if (first >= last) return;
      std::vector<Interval> pieces;
      for_each_line(lines.data() + first, lines.data() + last, pieces, [&](int32_t id, std::vector<Interval>& s) {
        const RealLine& l = c.lines[size_t(id)];
        const Vec3 p0 = pr.picture(l.a), p1 = pr.picture(l.b);
        hide_behind(occluders, cam.camera_from_world(l.a), cam.camera_from_world(l.b), s);
        const Weight w = cam.is_parallel() ? line_weight_along(c, scene.faces, id, cam.forward)
                                           : line_weight(c, scene.faces, id, cam.eye);
        add_strokes(to_raster, p0, p1, s, w, Layer::Architecture, parts[chunk]);
      });
    });
    for (const std::vector<Stroke>& part : parts) d.strokes.insert(d.strokes.end(), part.begin(), part.end());
  }
  detail::merge_intervals(edges, kTouch);
  for_each_line(edges, intervals, [&](int32_t k, std::vector<Interval>& s) {
    const SeenEdge& se = seen[size_t(k)];
    const FurniturePiece& p = scene.furniture.pieces[size_t(se.piece)];
    const FurnitureEdge& e = p.edges[size_t(se.edge)];
    const Vec3 w0 = p.mesh.vertices[size_t(e.v[0])], w1 = p.mesh.vertices[size_t(e.v[1])];
    hide_behind(occluders, cam.camera_from_world(w0), cam.camera_from_world(w1), s);
    add_strokes(to_raster, pr.picture(w0), pr.picture(w1), s, se.weight, Layer::Furniture, d.strokes);
  });
  if (options.merge) merge_collinear(d.strokes, options.threads);
  if (options.shadows && !cam.is_parallel()) draw_shadow_outlines(c, scene, cam, vs, occluders, d.strokes);
  return d;
}

}  // namespace avenues
