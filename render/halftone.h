// Avenues — the scanline half-tone renderer (Wylie 1967, Bouknight 1969) fed by the visible
// set: the public face of render/scanline*, render/scene*, render/shading* and render/raster*.
//
//   HalftoneOptions opt;                      // samples, shading, dither, threads, ...
//   RenderStats stats;
//   Image picture = render_view(complex, camera, visible, opt, &stats);
//   write_image(picture, "view.png");
//
// A picture is scanned in bands of rows, each band by its own ScanlineEngine started at
// its first row (scanline.h), over as many threads as asked (TBB). Bands have a fixed
// height and every band computes exactly what a single scan would, so the picture does
// not depend on the number of threads. Within a band each sample row is scanned into
// spans, the spans are lit (shading.h) in linear light, s × s samples are averaged per
// pixel (supersampling as a box filter), and the pixel is encoded to 8-bit sRGB once.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/mesh.h"
#include "render/lighting.h"
#include "render/raster.h"
#include "render/scene_objects.h"
#include "render/scene_screen.h"
#include "render/shading.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues {

struct HalftoneOptions {
  int samples = 1;              ///< per pixel: 1, 4 or 16 (a 1×1, 2×2 or 4×4 grid of sample centres)
  Shading shading;              ///< Flat (Bouknight) or Smooth (Wylie), light at the eye
  Dither dither = Dither::None; ///< not None: the picture comes back bilevel (grey) for print
  bool colour = true;           ///< RGB from the materials' colours; false: grey (their luminance)
  int threads = 0;              ///< 0: as many as TBB offers; otherwise at most this many
  bool cull_back_faces = true;  ///< drop polygons of closed meshes facing away from the eye
  std::array<double, 3> background{0, 0, 0};  ///< linear RGB where nothing is seen (Bouknight's polygon 0)
  Lights lights = Lights::Plan;  ///< the plan's point lights (with shadows) when it has any, else the eye's; or the eye's only
  ObjectShadows object_shadows = ObjectShadows::Auto;  ///< whether objects cast shadows from those lights
  /// Assemble only the stages the scene calls for (effects.h). False: the bare pipeline as
  /// it was before effects were planned — the light at the eye, implicit lines searched
  /// wherever objects meet — for comparison.
  bool plan_effects = true;
  /// > 0: an object with coarser versions (PlacedObject::coarser) is drawn in the coarsest
  /// whose tolerance moves no point of it on the picture by more than this many samples
  /// (SceneOptions::detail_samples); 0: always in full. docs/ACCURACY.md, §5.
  double detail_samples = 0;
  /// [m] objects whose box lies farther than this from the eye are not drawn
  /// (SceneOptions::objects_within): the walkthrough's frame budget gives up far furniture
  /// and detail while the eye moves, when fewer samples and pixels were not enough.
  double objects_within = HUGE_VAL;
  /// SceneOptions::drop_hidden: what lies wholly behind polygons already drawn is not put
  /// on the raster where depth alone decides (the same picture; false: the reference).
  bool drop_hidden = true;
};

/// What a render did and how long it took.
struct RenderStats {
  double render_us = 0;        ///< [µs] wall time: polygons to the raster, scan, light, encode, dither
  long polygons = 0;           ///< polygons on the raster after culling and cutting
  long edges = 0;              ///< non-horizontal edges that crossed a sample row (masks' included)
  long scanlines = 0;          ///< sample rows with a non-empty active edge list
  long intersections = 0;      ///< edge crossings processed (active edges summed over rows)
  long spans = 0;              ///< key squares: runs of one visible polygon (or background) on a row
  long pixels = 0;             ///< samples written from a polygon (background not counted)
  long implicit_lines = 0;     ///< spans split where interpenetrating polygons change order
  long depth_sorts = 0;        ///< nearest-polygon searches among two or more polygons
  long depth_comparisons = 0;  ///< pairwise depth comparisons those searches made
  int active_max = 0;          ///< most edges in the active list on one row
  double active_mean = 0;      ///< mean active list length over the scanlines
  int threads = 0;             ///< threads the bands were spread over
  long light_pieces = 0;       ///< lit pieces and shadow polygons in the secondary scan (0: none needed)
  double effects_us = 0;       ///< [µs] of render_us: deciding the effects and casting shadows (0 when prepared beforehand)
  /// Every field as (key, value), e.g. for `avenues view --stats-json` ("render_us", "spans", ...).
  std::vector<std::pair<std::string, double>> fields() const;
  /// Adds another render's figures (a stereo pair's second eye): sums, the larger maximum.
  void add(const RenderStats& o);
};

/// A view of a cell complex: the visible set's avenues, their cells' faces and the objects
/// of those cells (loaded from the complex's object list on each call; see the overload).
Image render_view(const CellComplex& complex, const Camera& camera, const VisibleSet& visible,
                  const HalftoneOptions& options, RenderStats* stats = nullptr);
/// The same with objects placed beforehand (place_objects), into a picture whose storage
/// is reused from frame to frame (a walkthrough). The scene's effects are decided (and its
/// shadows cast) on each call; see the next overload to do that once.
void render_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const Camera& camera,
                 const VisibleSet& visible, const HalftoneOptions& options, Image& out, RenderStats* stats = nullptr);
struct SceneEffects;
/// The same with the scene's effects prepared beforehand (effects.h: prepare_effects with the
/// same complex, objects and options), shared by every view of the scene.
void render_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const SceneEffects& effects,
                 const Camera& camera, const VisibleSet& visible, const HalftoneOptions& options, Image& out,
                 RenderStats* stats = nullptr);

/// What rendering a picture builds that the next picture can reuse: its screen scene, its
/// edge tables and each thread's scan state. Their arrays run to megabytes (30,000
/// furniture polygons in a big Sweet Home house), beyond the size glibc maps afresh for
/// each allocation: a walkthrough keeps one storage and renders every frame into it, so a
/// frame neither maps nor faults in the memory the frame before it had. One picture at a
/// time. It also keeps each cell's objects (ObjectsByCell), made again only when it is
/// handed another complex or vector of objects, or one of another size: a vector's
/// objects must keep their cells from picture to picture, as placed objects do.
class FrameStorage {
 public:
  FrameStorage();
  ~FrameStorage();
  FrameStorage(const FrameStorage&) = delete;
  FrameStorage& operator=(const FrameStorage&) = delete;
  struct Parts;  ///< halftone.cpp
  Parts& parts() { return *parts_; }

 private:
  std::unique_ptr<Parts> parts_;
};
/// The same, building the picture in `storage`, whose arrays the last picture left.
void render_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const SceneEffects& effects,
                 const Camera& camera, const VisibleSet& visible, const HalftoneOptions& options, Image& out,
                 FrameStorage& storage, RenderStats* stats = nullptr);

/// A stereo pair as one picture: each eye located and its avenues found (the search and
/// kernel `search` asks for), both views rendered, then composed as `composite` asks; a dither, if
/// asked, is applied to the composed picture. Throws std::invalid_argument for a dithered
/// anaglyph (1-bit grey cannot carry its colours) and std::runtime_error when an eye is
/// not in a cell. Stats add up both views (render_us includes the two traversals).
Image render_stereo_view(const CellComplex& complex, const std::vector<PlacedObject>& objects, const Camera& left,
                         const Camera& right, StereoComposite composite, const HalftoneOptions& options,
                         RenderStats* stats = nullptr, const TraverseParams& search = {});

/// Meshes alone (OBJ/OFF/PLY/STL through load_mesh), in the default material.
Image render_meshes(const std::vector<Mesh>& meshes, const Camera& camera, const HalftoneOptions& options,
                    RenderStats* stats = nullptr);
/// Meshes alone, paints[i] for meshes[i].
Image render_meshes(const std::vector<Mesh>& meshes, const std::vector<MeshPaint>& paints, const Camera& camera,
                    const HalftoneOptions& options, RenderStats* stats = nullptr);

/// The engine on polygons already on the raster (scene_screen.h). `item_buffer`, when
/// given, receives the visible polygon of every sample (-1: background), rows of
/// raster.width samples. Throws std::invalid_argument for samples not 1, 4 or 16.
void render_scene(const ScreenScene& scene, const HalftoneOptions& options, Image& out, RenderStats* stats = nullptr,
                  std::vector<int32_t>* item_buffer = nullptr);

/// Samples per pixel side for HalftoneOptions::samples (1, 4, 16 → 1, 2, 4); throws
/// std::invalid_argument otherwise.
int samples_per_side(int samples);
/// SceneOptions for a render with these options.
SceneOptions scene_options(const HalftoneOptions& options);

}  // namespace avenues
