// Avenues — the picture's polygons on the raster: what the scanline engine is fed.
//
// Bouknight's preprocessing, step by step, for every convex polygon drawn:
//   1. into camera space (the eye at the origin, looking along +Z: Bouknight's "standard
//      arrangement");
//   2. cut at the near plane Z = camera.near, in 3D ("a truncation must be applied to those
//      planar polygons that extend behind the observer");
//   3. projected to the picture plane (x = X/Z, y = Y/Z) and on to the raster;
//   4. cut to a guard band one raster size wide around the window, which keeps the fixed
//      point in range (scanline.h) — the window itself is cut during the scan;
//   5. rounded once to the fixed-point grid, with its plane as 1/Z over the raster.
// Every cut computes a crossing from the edge's two end points taken in one canonical
// order, so an edge two polygons share is cut at bit-identical points and stays shared.
//
// For a view (scene_view.cpp) each avenue of sight adds its mask as a clip region and its
// cell's faces turned towards the eye; a cell's objects join the avenues of that cell.
// Meshes alone (the papers' scenes) are one group of objects cut by the window only.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "cells/cell_complex.h"
#include "render/lighting.h"
#include "render/occlusion_buffer.h"
#include "render/raster_map.h"
#include "render/scanline.h"
#include "render/scene_objects.h"
#include "render/shading.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues {

/// Where a screen polygon came from (for item buffers and tests).
struct PolygonSource {
  enum class Kind : uint8_t { Face, Object, Mesh };
  Kind kind = Kind::Mesh;
  int avenue = -1;        ///< Face, Object: index into VisibleSet::avenues
  CellId cell = kNoCell;  ///< Face, Object: the avenue's cell
  int face = -1;          ///< Face: index into the cell's faces
  int mesh = -1;          ///< Object: index into the placed objects; Mesh: into the meshes
  int polygon = -1;       ///< Object, Mesh: the mesh's input polygon (Mesh::polygon_of)
};

struct ScreenScene {
  RasterMap raster;
  std::vector<ScreenPolygon> polygons;
  std::vector<SurfaceShade> shades;     ///< one per polygon
  std::vector<PolygonSource> sources;   ///< one per polygon
  std::vector<ClipRegion> clips;
  /// Lit shades' light terms (SurfaceShade::first_term), when the plan's lights light the view.
  std::vector<LightTerm> light_terms;
  /// The secondary scan's polygons (LightTerm::first_piece): lit pieces and shadow polygons of
  /// the surfaces (shadows.h), on the raster like the polygons they fall on. Only their
  /// outlines matter.
  std::vector<ScreenPolygon> pieces;
  /// Search for implicitly defined lines where objects' polygons change depth order (false:
  /// the scene has no interpenetrating polygons, effects.h; the scan is the same without).
  bool implicit_lines = true;
  /// What is drawn so far, for a scene resolved by depth alone (ScreenSceneBuilder::
  /// drop_hidden); kept between pictures for its storage.
  OcclusionBuffer drawn;
  /// Outlines the last picture used, emptied, for the next one's polygons (clear()).
  std::vector<std::vector<FixedPoint>> spare_outlines;
  /// The scenes of a view's strips (VisibleSet::strips), built side by side and appended
  /// to this one; kept for their storage.
  std::vector<ScreenScene> parts;

  /// Empties the scene for the next picture, keeping every array's storage, the polygons'
  /// outlines included (spare_outlines). A walkthrough builds each frame's scene into the
  /// same one, so a frame neither maps nor faults in the memory the frame before it had.
  void clear();
  /// An empty outline: one clear() kept, when there is one.
  std::vector<FixedPoint> take_outline();
  /// Keeps an outline that was not used for the next polygon (take_outline).
  void keep_outline(std::vector<FixedPoint>&& outline);
  /// Drops the pieces from index `first` on, keeping their outlines.
  void drop_pieces_from(size_t first);
  /// Moves another scene of the same raster in after this one's polygons, clip regions,
  /// light terms and pieces, its indices into them moved on to match; `part` is left empty.
  void append(ScreenScene& part);
};

struct SceneShadows;
struct SurfaceLight;

struct SceneOptions {
  int per_side = 1;              ///< samples along each side of a pixel: 1, 2 or 4
  Shading shading;
  bool cull_back_faces = true;   ///< drop polygons of closed meshes facing away from the eye (Crow 1981)
  /// The plan's lights (lighting.h) and what they reach (shadows.h), for a view of a cell
  /// complex; both must be given, and outlive the builder. Null or at the eye: the light at the eye.
  const Lighting* lighting = nullptr;
  const SceneShadows* shadows = nullptr;
  /// An architect's cut (world; a parallel view's, from its VisibleSet): only what lies on
  /// the far side of the plane, seen along the camera's forward, is drawn; polygons are cut
  /// there in 3D before the near plane.
  std::optional<Plane> cut;
  /// Each cell's objects, made once for many pictures of the same objects (must match the
  /// objects given); null: made for this picture.
  const ObjectsByCell* objects_by_cell = nullptr;
  /// > 0: objects' coarser versions where their tolerance projects under this many samples
  /// (scene_view.cpp); 0: objects in full.
  double detail_samples = 0;
  /// [m] a perspective view draws no object whose box lies farther than this from the eye
  /// (HalftoneOptions::objects_within); a parallel view draws every one.
  double objects_within = HUGE_VAL;
  /// Where depth alone decides (a conservative visible set, meshes alone), polygons wholly
  /// behind what is already drawn are not put on the raster (ScreenSceneBuilder::
  /// drop_hidden): the same picture. False: every polygon, the reference tests compare with.
  bool drop_hidden = true;
  /// A conservative view searched in strips (VisibleSet::strips) with no object drawn whole
  /// across cells: each strip's part of the scene is built on its own thread, up to this
  /// many (0: as many as TBB offers), and the parts joined in order. The same picture: each
  /// part drops only what lies behind what it has drawn itself.
  int threads = 1;
};

/// Adds polygons to a ScreenScene (steps 1–5 above).
class ScreenSceneBuilder {
 public:
  /// What the scan does with a polygon (see ScreenPolygon).
  struct Placement {
    int32_t clip = -1, group = 0, rank = 0;
    PolygonRole role = PolygonRole::Object;
  };
  ScreenSceneBuilder(const Camera& camera, const SceneOptions& options, ScreenScene& out);
  /// The raster the scene is drawn on.
  const RasterMap& raster() const { return out_.raster; }

  /// A clip region from a convex picture-plane polygon, grown by `grow` samples on every
  /// side (by the Minkowski sum with a square). -1 if nothing of area is left.
  int32_t add_clip(const std::vector<Vec2>& picture_polygon, double grow);
  /// Whether clip region `clip` holds the centre of some sample of the raster. A polygon
  /// covers a sample only where the sample's centre is inside its clip region too, so what
  /// is clipped to a region holding none colours nothing and decides no depth.
  bool clip_holds_a_sample(int32_t clip) const;
  /// A planar convex polygon of a cell (world coordinates, on `plane`), lit as
  /// options.shading says (or by the plan's lights, options.lighting: `source` names the
  /// face). A flat shade is the one at `shade_at` (world), the centroid of the surface the
  /// polygon is a piece of (cells' Surface), so that every piece of one surface takes one
  /// shade; nullptr: the polygon's own centroid. False if nothing of it is left to draw.
  bool add_face(const std::vector<Vec3>& polygon, const Plane& plane, const Material& material, Placement where,
                const PolygonSource& source, const Vec3* shade_at = nullptr);
  /// A mesh, input polygon by input polygon (its fan of triangles put back together). Flat:
  /// one intensity each. Smooth: a polygon whose corners' normals are its own is lit from
  /// its plane; a curved one by Gouraud over its triangles. Polygons of a closed mesh
  /// facing away from the eye are dropped when options.cull_back_faces.
  /// `polygons` false: every triangle on its own (a coarser version, whose triangles of one
  /// input polygon no longer lie in one plane), else the runs of triangles of one polygon
  /// drawn as the polygon where they form its fan.
  /// `runs`, when given (polygon_runs of `mesh`): a run whose box cannot show (may_show) is
  /// passed over whole, and only the vertices of runs looked at go to camera space.
  void add_mesh(const Mesh& mesh, const MeshPaint& paint, Placement where, PolygonSource source, bool polygons = true,
                const PolygonRuns* runs = nullptr);
  /// From now on, mesh polygons wholly in front of the near plane and wholly outside clip
  /// region `clip` (add_clip) grown by `margin` samples are not added: they would be
  /// clipped to it, so they could not show. Until no_cull(). The region's box alone lets
  /// through every polygon near a long diagonal sliver of view; beyond one of its sides
  /// (exact integer directions), a polygon goes.
  void cull_outside(int32_t clip, double margin);
  void no_cull() { cull_ = false; }
  /// From now on every polygon is cut in 3D to `cell` (its face planes, kOnCellFace
  /// outside them kept): an object reaching beyond the cell is drawn there only as the part
  /// inside (PlacedObject::cells). nullptr: no longer.
  void cut_to(const Cell* cell);
  /// From now on the scene is resolved by depth alone (one group, every polygon an
  /// Object): a polygon added that covers whole tiles of the raster is remembered
  /// (ScreenScene::drawn), and a planar polygon wholly behind what is already drawn is not added.
  /// The picture is the same; what the scan would never show costs nothing. A picture
  /// where little is hidden (under one polygon in 8 of the first 500 tested) stops.
  void drop_hidden();
  /// Whether something inside a world box could show: false if, every corner beyond the
  /// near plane, its box on the raster holds no sample's centre, or lies outside the cull
  /// region's box or beyond one of its sides (cull_outside), or behind what is drawn
  /// (drop_hidden; with a margin of 1e-3 in 1/Z, see scene_screen.cpp).
  bool may_show(const Box3& box) const;
  /// Resolved by depth (drop_hidden): whether every piece of `cell`'s faces that add_face
  /// would be given (the opaque pieces of faces turned towards the eye), cut to the convex
  /// picture-plane polygon grown by `grow` samples (its clip region), lies behind what is
  /// drawn, so that add_face would drop each of them. One test for the whole cell, from
  /// its box: never true where one of the per-piece tests would keep a piece, and it counts
  /// each piece as tested and dropped, as add_face would (also where the clip region holds no
  /// sample, so that add_face is never called: more dropped only keeps drop_hidden on, which
  /// changes no picture). False when a corner of the box reaches the near plane, or a piece's
  /// plane is seen too nearly edge-on for the test.
  bool cell_faces_hidden(const Cell& cell, const std::vector<Vec2>& picture_polygon, double grow);

 private:
  /// Steps 2–5 for a polygon already in camera space on the plane n·P + d = 0.
  bool add(const std::vector<Vec3>& points, Vec3 n, double d, const SurfaceShade& shade, Placement where,
           const PolygonSource& source);
  /// Steps 2–4 and the fixed point of step 5: the outline on the raster of a camera-space
  /// polygon. False if nothing of area is left.
  bool project(const std::vector<Vec3>& points, ScreenPolygon& poly);
  /// Lit by the plan's point lights (not the eye's).
  bool lit() const { return options_.lighting != nullptr && options_.shadows != nullptr && !options_.lighting->at_eye; }
  /// A Lit shade for a polygon from `source`, its terms appended to the scene (planar: plane
  /// n·P + d = 0 and centroid in camera space; `per_sample`: Plane terms, else Constant).
  SurfaceShade lit_planar_shade(const Material& m, Vec3 n, double d, Vec3 centroid, bool per_sample,
                                const PolygonSource& source);
  /// The same for a Gouraud triangle (corners and unit vertex normals in camera space).
  SurfaceShade lit_gouraud_shade(const Material& m, const std::array<Vec3, 3>& points,
                                 const std::array<Vec3, 3>& normals, const PolygonSource& source);
  /// A Lit shade of material m for the surface `source` came from: a term per point light
  /// that reaches it, made by term_of(light, its position in camera space, term) (false:
  /// no light there), with its lit pieces and shadow polygons on the raster.
  template <class TermOf>
  SurfaceShade lit_shade(const Material& m, const PolygonSource& source, TermOf term_of) {
    const Lighting& lighting = *options_.lighting;
    SurfaceShade shade;
    shade.kind = SurfaceShade::Kind::Lit;
    shade.colour = material_colour(m);
    shade.lit_ambient = lighting.ambient;
    shade.coloured = lighting.coloured;
    shade.first_term = int32_t(out_.light_terms.size());
    for (size_t k = 0; k < lighting.points.size(); ++k) {
      const SurfaceLight* s = surface_light(k, source);
      if (!s) continue;
      const PointLight& light = lighting.points[k];
      LightTerm term;
      if (!term_of(light, camera_.camera_from_world(light.position), term)) continue;
      const size_t pieces = out_.pieces.size();
      if (!add_pieces(*s, term)) {
        out_.drop_pieces_from(pieces);
        continue;
      }
      out_.light_terms.push_back(term);
    }
    shade.terms = int32_t(out_.light_terms.size()) - shade.first_term;
    return shade;
  }
  /// What light k does to the surface `source` came from; nullptr: nothing.
  const SurfaceLight* surface_light(size_t k, const PolygonSource& source) const;
  /// Puts a surface's lit pieces and shadow polygons on the raster for `term`, each grown by
  /// 1/64 of a sample (the union of pieces rounded one by one leaves no sample on a seam
  /// between two of them outside both); false if the light lights none of it on the raster
  /// (the term is dropped).
  bool add_pieces(const SurfaceLight& s, LightTerm& term);
  /// add() for a Lit shade: drops the shade's terms and pieces when nothing is drawn.
  bool add_lit(const std::vector<Vec3>& points, Vec3 n, double d, const SurfaceShade& shade, Placement where,
               const PolygonSource& source, size_t pieces_before);
  Vec3 camera_dir(Vec3 v) const { return {dot(v, camera_.right), dot(v, camera_.up), dot(v, camera_.forward)}; }
  /// One input polygon of a mesh: its corners and, per corner, the normal for smooth shading.
  /// Its corners' camera-space and raster points are mesh_cam_'s and mesh_raster_'s (project_vertex).
  void add_mesh_polygon(const Mesh& mesh, const std::vector<int>& corners, const std::vector<Vec3>& normals,
                        const Material& material, Placement where, const PolygonSource& source);
  /// Whether a polygon whose box on the raster (in samples; every corner beyond the near
  /// plane) is [lo, hi] might hold the centre of one of the raster's samples. Grown by
  /// more than the fixed point's rounding, so that it never says no where add() would
  /// have drawn: a far piece of furniture smaller than a sample, or one off the picture,
  /// goes before it is shaded or projected.
  bool may_cover_a_sample(Vec2 lo, Vec2 hi) const;
  /// 1/Z on the raster [1/m] of the camera-space plane n·P + d = 0 (d != 0).
  RasterPlane raster_plane(Vec3 n, double d) const;
  /// A camera-space polygon's corners on the raster [samples] and their box; false (and
  /// the corners unfinished) if some corner lies before the near plane.
  bool on_raster(const std::vector<Vec3>& points, std::vector<Vec2>& corners, Vec2& lo, Vec2& hi) const;
  /// Whether a polygon drawn on the camera-space plane n·P + d = 0, with these corners on
  /// the raster (every one beyond the near plane) and their box [lo, hi], cut to clip
  /// region `clip` (-1: none), lies behind what is drawn wherever it could colour a sample
  /// (drop_hidden; false without). Only the samples inside both boxes are looked at: the
  /// scan colours none outside its clip region.
  bool hidden(const std::vector<Vec2>& corners, Vec3 n, double d, Vec2 lo, Vec2 hi, int32_t clip);
  /// The polygon just added (the scene's last): remembered where it covers whole pixels.
  void remember_drawn();
  /// A world box's corners on the raster [samples], their box, and the corners' least and
  /// largest camera depth [m].
  struct BoxOnRaster {
    std::array<Vec2, 8> corners;
    Vec2 lo, hi;
    double nearest = 0, farthest = 0;
  };
  /// False (`out` unfinished) if some corner lies before the near plane.
  bool box_on_raster(const Box3& box, BoxOnRaster& out) const;
  /// Whether points on the raster [samples] whose box is [lo, hi] lie wholly outside the
  /// cull region (cull_outside): outside its box, or all beyond one of its sides. False
  /// without one.
  bool outside_cull_region(std::span<const Vec2> points, Vec2 lo, Vec2 hi) const;

  Camera camera_;
  SceneOptions options_;
  ScreenScene& out_;
  double guard_ = 0;  ///< [samples] the guard band's width around the window
  bool cull_ = false;
  bool drop_hidden_ = false;
  long tested_ = 0, dropped_ = 0;  ///< drop_hidden: polygons tested against what is drawn, and dropped
  Vec2 cull_lo_, cull_hi_;  ///< [samples] the cull region's box on the raster, grown by its margin
  std::vector<std::pair<Vec2, Vec2>> clip_box_;  ///< [samples] each clip region's box on the raster, by number
  /// The cull region's sides as half-planes a·u + b·v + c >= 0 on the raster (a, b a unit
  /// normal pointing in; c taking in the margin).
  struct Side {
    double a, b, c;
  };
  std::vector<Side> cull_sides_;
  std::vector<Vec3> near_cut_, plane_cut_;
  std::vector<Vec3> face_cam_;       ///< add_face: the face in camera space (kept: a view adds thousands)
  std::vector<Vec3> mesh_cam_;       ///< add_mesh: the mesh's vertices in camera space, each transformed once
  std::vector<Vec2> mesh_raster_;    ///< and on the raster [samples] (NaN: before the near plane)
  std::vector<uint32_t> mesh_cam_mark_;  ///< per vertex: mesh_mark_ when mesh_cam_ and mesh_raster_ hold it for this mesh
  uint32_t mesh_mark_ = 0;
  /// Vertex v of the mesh add_mesh is adding, in camera space and on the raster (as
  /// on_raster puts it there), each found once per mesh: a vertex is shared by about six
  /// triangles, most of which a far view drops on their corners' raster points alone.
  void project_vertex(const Mesh& mesh, int v) {
    if (mesh_cam_mark_[size_t(v)] == mesh_mark_) return;
    const Vec3 c = camera_.camera_from_world(mesh.vertices[size_t(v)]);
    mesh_cam_[size_t(v)] = c;
    mesh_raster_[size_t(v)] = c.z >= camera_.near ? out_.raster.raster_from_image({c.x / c.z, c.y / c.z})
                                                  : Vec2{std::nan(""), std::nan("")};
    mesh_cam_mark_[size_t(v)] = mesh_mark_;
  }
  std::vector<Vec3> polygon_cam_;    ///< add_mesh_polygon: the polygon's corners in camera space
  std::vector<Vec2> polygon_raster_;  ///< and on the raster [samples]
  std::vector<Vec2> corners_;         ///< remember_drawn: the outline's corners [samples]
  std::vector<int> triangle_corners_;       ///< add_mesh: one triangle of a polygon that is not a fan
  std::vector<Vec3> triangle_normals_;      ///< and its corners' normals
  std::vector<FixedPoint> clip_points_;  ///< add_clip: the grown corners; add_pieces: a grown piece
  /// cut_to: the cell's face planes in camera space, kept where dot(n, P) + d <= kOnCellFace.
  struct CellPlane {
    Vec3 n;
    double d;
  };
  std::vector<CellPlane> cell_cut_;
  std::vector<Plane> cell_cut_world_;  ///< the same planes in the world, outward
  Box3 cell_cut_box_;                  ///< the cell's box
  /// Whether a world box, or a polygon's corners, lie wholly beyond one of cut_to's planes
  /// (false when not cutting): nothing of them is left to draw.
  bool beyond_cell(const Box3& box) const;
  bool beyond_cell(const Mesh& mesh, const std::vector<int>& corners) const;
  std::vector<Vec3> cell_cut_a_, cell_cut_b_;
  bool has_cut_ = false;
  Vec3 cut_n_;          ///< options.cut in camera space, kept where dot(cut_n_, P) + cut_d_ >= 0
  double cut_d_ = 0;
  std::vector<Vec2> raster_, guard_cut_;
};

/// The polygons of a view: every avenue's mask, its cell's faces turned to the eye and
/// the objects of its cell.
ScreenScene screen_scene_of_view(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                                 const Camera& camera, const VisibleSet& visible, const SceneOptions& options);
/// The same into `out`, cleared first (ScreenScene::clear), whose storage is reused.
void screen_scene_of_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const Camera& camera,
                          const VisibleSet& visible, const SceneOptions& options, ScreenScene& out);

/// The polygons of meshes alone, seen by `camera`; paints[i] goes with meshes[i] (missing
/// ones: the default material).
ScreenScene screen_scene_of_meshes(const std::vector<Mesh>& meshes, const std::vector<MeshPaint>& paints,
                                   const Camera& camera, const SceneOptions& options);

/// The convex outline `v` (either orientation, as the engine takes it) grown by the square
/// [−g, g]² (their Minkowski sum) into `out`, counter-clockwise in (x, y) as stored, in one
/// pass: each corner of `v` becomes the square's corners whose outward normals lie between
/// those of its two sides (an outline that rounding left a hair concave: the hull of its
/// corners moved to the square's four corners, which is the same for a convex one). False
/// when `v` has no area. Pieces of light and shadow are grown so (ScreenSceneBuilder::add_pieces).
bool grow_convex(const std::vector<FixedPoint>& v, int64_t g, std::vector<FixedPoint>& out);

}  // namespace avenues
