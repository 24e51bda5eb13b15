// Avenues — the architect's drawings: plan, section, elevation and axonometric, exactly,
// from the cells.
//
// Each is a parallel projection (camera.h) searched from a cut plane
// (find_visible_from_cut): the cells the plane crosses are seen through their own
// cross-sections, the rest through the portals beyond. The drawing has, as drawing
// conventions ask (ISO 128 weights):
//   Layer::Cut     where the plane passes through solid: every opaque polygon of a cut cell
//                  met by the plane gives one segment (the wall's face, a jamb, a slab's
//                  edge), drawn with the heaviest pen; together they close each wall's
//                  outline (a door's gap where the plane crosses the doorway). The fill is
//                  the window less every cut cell's cross-section, by the even-odd rule;
//   Layer::Beyond  the real lines beyond the plane, clipped to the avenues' masks exactly as
//                  a perspective's are (view_lines.h), outlines heavier than creases, less
//                  what the plan's objects beyond the plane hide; and those objects' edges
//                  (Layer::Furniture), a roof's or a table's outline;
//   Layer::Annotation  on a plan, each named room's name and area at its largest cell.
// An elevation's plane stands outside the building and cuts nothing: it has no cut layer.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>

#include "cells/cell_complex.h"
#include "render/drawing.h"
#include "render/view_lines.h"
#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues {

struct ArchitecturalOptions {
  bool cut = true;            ///< draw the cut (outlines and fill); false for an elevation
  StoreyId labels = -1;       ///< >= 0: label the rooms of this storey (a plan)
  double label_height = 12;   ///< [px] > 0: height of a room name's capitals
  int threads = 1;            ///< up to this many threads draw (0: as many as TBB offers); the drawing is the same
};

/// Where an architect's drawing looks from: a parallel camera fitted to what it shows (1 m
/// of margin around it), the plane its rays start from, and how it is drawn.
struct ArchitecturalView {
  Camera camera;
  Plane cut;
  ArchitecturalOptions options;
  std::string kind;  ///< plan, section, elevation or axonometric
};

/// A drawing that would be over kMaxDrawingPixels across at the resolution asked for.
struct DrawingTooLarge : std::runtime_error {
  double metres = 0;  ///< [m] the picture's longer side, its margins included
  DrawingTooLarge(double metres_across, double pixels);
};
inline constexpr double kMaxDrawingPixels = 32768;

/// The building: every cell inside it (not outside, not sky) and every solid it names.
Box3 building_bounds(const CellComplex& complex);
/// Storey `storey` cut `cut_height` [m] above its floor, looking down (north up), labelled;
/// storey -1: the whole building (a scene of meshes, which has no storeys) cut that far above
/// its lowest point, unlabelled.
/// Every constructor takes the raster's resolution px_per_m [px per metre of the building]
/// and throws DrawingTooLarge when the picture would be over kMaxDrawingPixels across.
ArchitecturalView plan_view(const CellComplex& complex, StoreyId storey, double cut_height, double px_per_m);
/// A vertical cut along p1→p2, looking to its left; the picture spans the line and the
/// building's height.
ArchitecturalView section_view(const CellComplex& complex, Vec2 p1, Vec2 p2, double px_per_m);
/// From outside the building, the viewer at azimuth_deg (anticlockwise from +x: 90 is north),
/// the picture plane just outside the building; nothing is cut.
ArchitecturalView elevation_view(const CellComplex& complex, double azimuth_deg, double px_per_m);
/// Parallel from above: the viewer at azimuth_deg and altitude_deg in (0, 90]; with cut_z a
/// horizontal cut at that height [m], removing what is above it.
ArchitecturalView axonometric_view(const CellComplex& complex, double azimuth_deg, double altitude_deg,
                                   std::optional<double> cut_z, double px_per_m);

/// The drawing of what `camera` (parallel) sees from `cut`; `visible` is
/// find_visible_from_cut() with the same camera and plane.
Drawing draw_architectural(const CellComplex& complex, const LineScene& scene, const Camera& camera, const Plane& cut,
                           const VisibleSet& visible, const ArchitecturalOptions& options = {});

/// The segment in which the cut plane meets a convex polygon (world [m]); false when it
/// misses it, touches it in a point, or the polygon lies in the plane.
bool cut_segment(const std::vector<Vec3>& poly, const Plane& cut, Vec3& a, Vec3& b);

}  // namespace avenues
