// Avenues — the polygons of a view, fed by the visible set (see scene_screen.h).
//
// Jones 1971 draws each visible cell's lines clipped to the mask of the avenue that reaches
// it; the half-tone does the same with faces. For each avenue:
//   - its mask becomes a clip region. Masks of one view tile the picture: a deeper mask
//     lies inside the portal it was seen through. A deeper mask is grown by 1/64 of a
//     sample so that rounding never opens a crack between it and the faces around it
//     (the deeper avenue wins where they overlap, a sliver far below a sample's width);
//   - its cell's faces turned towards the eye (the eye on their inner side) are drawn
//     whole — a portal's hole is not cut out, since the deeper avenue seen through it
//     covers it. Within the mask they never overlap (a convex cell), so they need no
//     depth test. A face made of pieces of different materials is drawn piece by piece;
//     a face with no opaque piece at all (wholly a portal) is not drawn. A flat shade is
//     taken at the centroid of the whole surface (cells' Surface), Bouknight's polygon,
//     not of the piece a cell holds, so that no false edge shows where cells meet;
//   - the objects that meet its cell (PlacedObject::cells), which resolve depth against
//     that cell's faces and each other, inside the mask only. One that reaches beyond the
//     cell (a rug under a low wall, a window's frame standing out into a room) is cut in 3D
//     to the cell first: the scan puts an object in front of every deeper avenue where it
//     is nearer than its cell's face, which holds only of what lies inside the cell (a
//     face that is wholly a portal is not drawn at all). Its other parts are drawn with
//     the cells they lie in, as the line drawing's furniture is (furniture.h).
// A conservative visible set (the hull search: masks that may hold more than their cell's
// view, cells perhaps not seen at all) is drawn by depth instead: every face's opaque
// pieces and every object in one group, each cut to its avenue's mask (which holds all
// that can show of it), and Bouknight's depth sort decides what is seen where they
// overlap — the nearest surface along each ray, which the exact masks would have shown.
// There an object meeting several cells is drawn once, whole, cut to the convex hull of
// the masks of its visible cells: wherever a part of it is the nearest surface, the cell
// holding that part is seen there, and so is every surface in front of it.
// A conservative view searched in strips of its window (visibility/strips.h) is built strip
// by strip, side by side, each strip's avenues into a scene of their own, joined in order
// (SceneOptions::threads), unless an object is drawn whole across cells: which avenue draws
// it depends on every strip's. Each part drops only what lies behind what it has drawn
// itself, which changes no picture.
// A parallel view (an architect's drawing, `view --projection parallel`) is drawn as the
// perspective from far behind its picture plane (distant_eye), cut where its rays start
// (VisibleSet::cut): the whole pipeline (lights, shadows, smooth shading, objects) is the
// perspective one, and the error is bounded far below a sample (docs/ACCURACY.md).
#include "render/scene_screen.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/angles.h"
#include "core/thread_arena.h"

namespace avenues {

namespace {

/// [samples] how far a deeper avenue's mask is grown: more than the rounding of a vertex
/// to the fixed-point grid (1/512), far less than a sample.
constexpr double kMaskGrowth = 1.0 / 64;

/// The version of an object to draw: the coarsest whose tolerance τ moves no point of it by
/// more than `samples` on the raster. A point at camera depth Z and picture position (x, y)
/// moved by δ (|δ| <= τ) moves on the picture plane by at most τ·√2·(1 + max(|x|, |y|))/Z;
/// Z is bounded below by the nearest corner of the object's box and |x|, |y| by the
/// raster's extent (what lies outside is not drawn). An object reaching the near plane, or
/// no `samples`, is drawn in full.
int detail_of(const PlacedObject& object, const Camera& camera, const RasterMap& raster, double samples) {
  if (!(samples > 0) || object.coarser.empty()) return -1;
  double z = HUGE_VAL;
  for (int corner = 0; corner < 8; ++corner) {
    const Box3& b = object.bounds;
    const Vec3 p{corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y, corner & 4 ? b.hi.z : b.lo.z};
    z = std::min(z, camera.camera_from_world(p).z);
  }
  if (!(z > camera.near)) return -1;
  const double reach = std::max({std::fabs(raster.x0), std::fabs(raster.x0 + raster.width * raster.step),
                                 std::fabs(raster.y0), std::fabs(raster.y0 - raster.height * raster.step)});
  const double per_metre = std::sqrt(2.0) * (1 + reach) / (z * raster.step);  // [samples / m]
  int best = -1;
  for (size_t k = 0; k < object.coarser.size(); ++k)
    if (object.coarser[k].tolerance * per_metre <= samples) best = int(k);
  return best;
}

const Material& material_of(const CellComplex& c, MaterialId id) {
  static const Material kDefault;
  return id >= 0 && size_t(id) < c.materials.size() ? c.materials[size_t(id)] : kDefault;
}

/// Where a piece is lit from when it is shaded flat: its surface's centroid (one shade for
/// every piece of one plane and material), or its own when the complex has no surfaces.
const Vec3* shade_point(const CellComplex& c, const OpaquePoly& piece) {
  return piece.surface >= 0 && size_t(piece.surface) < c.surfaces.size() ? &c.surfaces[size_t(piece.surface)].centroid
                                                                          : nullptr;
}

/// How far the distant eye stands behind the picture plane, per sample of the picture
/// across and metre of depth: a point z [m] beyond the picture plane is drawn D / (D + z) of
/// its size, so a mask (exact on the picture plane) and what is drawn in it part by at most
/// (half the samples across) · z / D = 1/512 of a sample at the far box's far side, well
/// inside the 1/64 of a sample deeper masks are grown by.
constexpr double kDistance = 256;

/// A parallel camera as a perspective one from far behind its picture plane: the same
/// window at the picture plane (a mask point m [m] is m / D there), and a near plane that
/// cuts nothing of the far box (the view's own cut does the cutting).
struct DistantEye {
  Camera camera;
  double scale = 1;  ///< parallel picture-plane coordinates [m] to the distant camera's
};

/// [m] the nearest a picture's near plane comes to the eye (an eye on a face of its cell).
constexpr double kNearest = 1e-5;

DistantEye distant_eye(const Camera& cam, const Box3& far_box, int per_side) {
  double reach = 1;  // [m] how far the far box lies beyond (or before) the picture plane
  for (int k = 0; k < 8; ++k) {
    const Vec3 p{k & 1 ? far_box.hi.x : far_box.lo.x, k & 2 ? far_box.hi.y : far_box.lo.y,
                 k & 4 ? far_box.hi.z : far_box.lo.z};
    reach = std::max(reach, std::fabs(dot(p - cam.eye, cam.forward)));
  }
  const double samples = double(std::max(cam.width, cam.height) * per_side);
  const double distance = kDistance * samples * reach;
  DistantEye d;
  d.camera = cam;
  d.camera.projection = Projection::Perspective;
  d.camera.eye = cam.eye - distance * cam.forward;
  d.camera.fov_deg = deg_from_rad(2 * std::atan(cam.half_width() / distance));
  d.camera.shift_x = cam.shift_x / distance, d.camera.shift_y = cam.shift_y / distance;
  d.camera.near = distance / 2;
  d.scale = 1 / distance;
  return d;
}

}  // namespace

ScreenScene screen_scene_of_view(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                                 const Camera& camera, const VisibleSet& visible, const SceneOptions& options) {
  ScreenScene out;
  screen_scene_of_view(complex, objects, camera, visible, options, out);
  return out;
}

namespace {

/// What each avenue of one view adds to its scene (the header of this file), made once
/// for the whole view: one part of it after another, or the strips' parts side by side.
struct ViewScene {
  const CellComplex& complex;
  const std::vector<PlacedObject>& objects;
  const VisibleSet& visible;
  const Camera& camera;
  bool parallel;
  const DistantEye& distant;
  const ObjectsByCell& by_cell;
  const SceneOptions& options;
  size_t roots;  ///< avenues with no parent: several meet along lines, grown as deeper masks are

  /// Whether an object with this box is not drawn: a perspective view's object lying
  /// farther from the eye than options.objects_within.
  bool beyond_reach(const Box3& box) const {
    if (parallel || !(options.objects_within < HUGE_VAL)) return false;
    const Vec3 e = camera.eye;
    const Vec3 nearest{std::clamp(e.x, box.lo.x, box.hi.x), std::clamp(e.y, box.lo.y, box.hi.y),
                       std::clamp(e.z, box.lo.z, box.hi.z)};
    return length(nearest - e) > options.objects_within;
  }

  /// Avenues [first, last) into `b`'s scene.
  void add(ScreenSceneBuilder& b, size_t first, size_t last) const {
    std::vector<Vec2> scaled;
    auto mask_of = [&](const Avenue& a) -> const std::vector<Vec2>& {
      if (!parallel) return a.mask;
      scaled.clear();
      for (Vec2 m : a.mask) scaled.push_back(distant.scale * m);
      return scaled;
    };
    // Object o in full, or its coarser version (detail_of), at `where`.
    auto add_object = [&](uint32_t o, ScreenSceneBuilder::Placement where, PolygonSource source) {
      source.kind = PolygonSource::Kind::Object;
      source.face = -1;
      source.mesh = int(o);
      const PlacedObject& object = objects[o];
      const int level = detail_of(object, camera, b.raster(), options.detail_samples);
      const Mesh& mesh = level < 0 ? object.mesh : object.coarser[size_t(level)].mesh;
      const std::vector<PolygonRuns>& runs = object.coarser_runs;
      const PolygonRuns* of_mesh = level < 0 ? &object.runs : size_t(level) < runs.size() ? &runs[size_t(level)] : nullptr;
      b.add_mesh(mesh, object.paint, where, source, level < 0, of_mesh);
    };
    // A conservative set: the objects meeting several cells drawn so far, and a clip region
    // around the masks of every visible avenue into one of an object's cells.
    std::unordered_set<uint32_t> drawn_whole;
    std::vector<std::pair<CellId, uint32_t>> avenue_of_cell;  // (cell, avenue), sorted; made when first needed
    std::vector<Vec2> mask_corners;
    auto clip_around = [&](const PlacedObject& object) -> int32_t {
      if (avenue_of_cell.empty()) {
        for (size_t k = 0; k < visible.avenues.size(); ++k) avenue_of_cell.push_back({visible.avenues[k].cell, uint32_t(k)});
        std::sort(avenue_of_cell.begin(), avenue_of_cell.end());
      }
      mask_corners.clear();
      for (const ObjectCell& in : object.cells)
        for (auto it = std::lower_bound(avenue_of_cell.begin(), avenue_of_cell.end(), std::pair{in.cell, uint32_t(0)});
             it != avenue_of_cell.end() && it->first == in.cell; ++it) {
          const Avenue& a = visible.avenues[it->second];
          if (a.mask.size() < 3) continue;
          for (Vec2 m : mask_of(a)) mask_corners.push_back(m);
        }
      const std::vector<Vec2> hull = convex_hull(mask_corners);
      return hull.size() < 3 ? -1 : b.add_clip(hull, kMaskGrowth);
    };
    for (size_t i = first; i < last; ++i) {
      const Avenue& avenue = visible.avenues[i];
      if (avenue.mask.size() < 3) continue;
      const std::vector<Vec2>& mask = mask_of(avenue);
      const double growth = avenue.depth == 0 && roots == 1 ? 0 : kMaskGrowth;
      const Cell& cell = complex.cells[size_t(avenue.cell)];
      const std::span<const uint32_t> in_cell = by_cell.of(avenue.cell);
      // Resolved by depth, a cell whose faces lie behind what is drawn within its mask (a far
      // cell of a grazing view across an open scene) adds none of them: tested once, not
      // piece by piece. Without objects, nothing of it is drawn.
      const bool faces_hidden = visible.conservative && b.cell_faces_hidden(cell, mask, growth);
      if (faces_hidden && in_cell.empty()) continue;
      const int32_t clip = b.add_clip(mask, growth);
      if (clip < 0) continue;
      // A mask between sample centres (a far cell of a grazing view over thousands) shows
      // nothing of its cell: its faces and the objects cut to it are not looked at. An object
      // drawn whole within the masks of all its cells (resolved by depth) still is, below.
      const bool shows = b.clip_holds_a_sample(clip);
      if (!shows && !visible.conservative) continue;
      ScreenSceneBuilder::Placement where{clip, int32_t(i), avenue.depth, PolygonRole::Face};
      if (visible.conservative) where = {clip, 0, 0, PolygonRole::Object};  // one group: depth decides
      PolygonSource source;
      source.kind = PolygonSource::Kind::Face;
      source.avenue = int(i);
      source.cell = avenue.cell;
      for (size_t k = 0; shows && !faces_hidden && k < cell.faces.size(); ++k) {
        const Face& face = cell.faces[k];
        if (face.opaque.empty() || !(face.plane.eval(camera.eye) < 0)) continue;
        source.face = int(k);
        bool one_material = true;
        for (const OpaquePoly& piece : face.opaque) one_material &= piece.material == face.opaque[0].material;
        // Resolved by depth, a face must not cover what its portals show, nor the pieces of
        // its plane that bound other cells (which a mask would have cut away): its opaque
        // pieces only, each lit as the whole face would be.
        if (one_material && !visible.conservative) {
          b.add_face(face.poly, face.plane, material_of(complex, face.opaque[0].material), where, source,
                     shade_point(complex, face.opaque[0]));
        } else {
          // Lit as the whole face: at its first piece's surface, or without one at the
          // centroid of the face's corners (add_face's own, for the whole face).
          Vec3 corners{0, 0, 0};
          const Vec3* whole = shade_point(complex, face.opaque[0]);
          if (one_material && !whole) {
            for (Vec3 p : face.poly) corners = corners + (1.0 / double(face.poly.size())) * p;
            whole = &corners;
          }
          for (const OpaquePoly& piece : face.opaque)
            b.add_face(piece.poly, face.plane, material_of(complex, piece.material), where, source,
                       one_material ? whole : shade_point(complex, piece));
        }
      }
      if (in_cell.empty()) continue;
      where.role = PolygonRole::Object;
      source.kind = PolygonSource::Kind::Object;
      source.face = -1;
      // The avenue's clip region, a little grown (two samples): what lies wholly outside it
      // cannot show through this avenue.
      b.cull_outside(clip, 2);
      std::optional<Box3> cell_box;
      for (const uint32_t entry : in_cell) {
        const uint32_t o = entry & ~ObjectsByCell::kCut;
        if (beyond_reach(objects[o].bounds)) continue;
        if (visible.conservative && objects[o].cells.size() > 1) {
          // Resolved by depth, an object need not be cut: drawn once, whole, within the hull
          // of the masks of every visible cell it meets (wherever it shows, a cell of its own
          // is seen there, and whatever stands before it is drawn there too).
          if (!drawn_whole.insert(o).second) continue;
          const int32_t around = clip_around(objects[o]);
          if (around < 0) continue;
          b.cull_outside(around, 2);
          if (b.may_show(objects[o].bounds)) {
            b.cut_to(nullptr);
            add_object(o, {around, 0, 0, PolygonRole::Object}, source);
          }
          b.cull_outside(clip, 2);
          continue;
        }
        if (!shows) continue;
        // Reaching beyond the cell, it is drawn here as its part inside the cell: nearer than
        // whatever the avenue sees beyond the cell's portals, as the scan takes it to be.
        const bool cut = entry & ObjectsByCell::kCut;
        Box3 box = objects[o].bounds;
        if (cut) {
          if (!cell_box) cell_box = cell.bounds();
          box = {{std::max(box.lo.x, cell_box->lo.x), std::max(box.lo.y, cell_box->lo.y), std::max(box.lo.z, cell_box->lo.z)},
                 {std::min(box.hi.x, cell_box->hi.x), std::min(box.hi.y, cell_box->hi.y), std::min(box.hi.z, cell_box->hi.z)}};
        }
        if (!b.may_show(box)) continue;  // a cell seen through many avenues: not through this one
        b.cut_to(cut ? &cell : nullptr);
        add_object(o, where, source);
      }
      b.cut_to(nullptr);
      b.no_cull();
    }
  }

  /// Whether the view can be built strip by strip, side by side: a conservative view in
  /// strips, with no object drawn whole across cells (drawn once, by the first avenue into
  /// one of its cells, which one strip alone cannot tell).
  bool in_strips() const {
    if (!visible.conservative || visible.strips.size() < 2 || options.threads == 1 || parallel) return false;
    // Each strip's first avenue, from the first on, ascending, within the set (a set cut
    // short after its search, as the walk's progressive display does, drops them).
    if (visible.strips.front() != 0 || !std::is_sorted(visible.strips.begin(), visible.strips.end()) ||
        size_t(visible.strips.back()) > visible.avenues.size())
      return false;
    for (const Avenue& a : visible.avenues)
      for (const uint32_t entry : by_cell.of(a.cell))
        if (objects[entry & ~ObjectsByCell::kCut].cells.size() > 1) return false;
    return true;
  }
};

}  // namespace

void screen_scene_of_view(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                          const Camera& view_camera, const VisibleSet& visible, const SceneOptions& view_options,
                          ScreenScene& out) {
  out.clear();
  const bool parallel = view_camera.is_parallel();
  const DistantEye distant = parallel ? distant_eye(view_camera, complex.far_box, view_options.per_side) : DistantEye{};
  // Perspective: the near plane no farther than half the eye's way to its cell's nearest
  // face. An eye a few millimetres from a wall would otherwise cut the wall away: a
  // picture cut at its masks then shows nothing there, and one resolved by depth (the
  // hull search's) whatever lies behind the wall.
  Camera near_camera = view_camera;
  if (!parallel && visible.eye_cell >= 0 && size_t(visible.eye_cell) < complex.cells.size())
    for (const Face& f : complex.cells[size_t(visible.eye_cell)].faces) {
      const double clearance = std::fabs(f.plane.eval(view_camera.eye)) / length(f.plane.n);
      near_camera.near = std::min(near_camera.near, std::max(0.5 * clearance, kNearest));
    }
  const Camera& camera = parallel ? distant.camera : near_camera;
  SceneOptions options = view_options;
  if (parallel && visible.cut) options.cut = visible.cut;
  std::optional<ObjectsByCell> made;
  if (!options.objects_by_cell) made = objects_by_cell(complex.cells.size(), objects);
  const ObjectsByCell& by_cell = options.objects_by_cell ? *options.objects_by_cell : *made;
  // An eye on its cell's boundary has several roots whose masks meet along lines, and so
  // has a view searched in strips: grow them as deeper masks are grown, so that no sample
  // on a meeting line falls between.
  size_t roots = 0;
  for (const Avenue& a : visible.avenues) roots += a.parent < 0;
  const ViewScene view{complex, objects, visible, camera, parallel, distant, by_cell, options, roots};
  // Resolved by depth alone, what lies behind polygons already drawn need not be drawn.
  const bool drop_hidden = visible.conservative && options.drop_hidden;
  if (!view.in_strips()) {
    ScreenSceneBuilder b(camera, options, out);
    if (drop_hidden) b.drop_hidden();
    view.add(b, 0, visible.avenues.size());
    return;
  }
  // Each strip's part on its own, the outlines the last picture left shared among them.
  const size_t n = visible.strips.size();
  out.parts.resize(n);
  for (size_t k = 0; !out.spare_outlines.empty(); k = (k + 1) % n) {
    out.parts[k].spare_outlines.push_back(std::move(out.spare_outlines.back()));
    out.spare_outlines.pop_back();
  }
  for_each_chunk(options.threads, n, n, [&](size_t k, size_t, size_t) {
    ScreenScene& part = out.parts[k];
    part.clear();
    ScreenSceneBuilder b(camera, options, part);
    if (drop_hidden) b.drop_hidden();
    view.add(b, size_t(visible.strips[k]), k + 1 < n ? size_t(visible.strips[k + 1]) : visible.avenues.size());
  });
  out.raster = out.parts[0].raster;
  for (ScreenScene& part : out.parts) out.append(part);
}

}  // namespace avenues
