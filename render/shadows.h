// Avenues — what each point light away from the eye lights: per surface, the pieces it
// reaches and the shadow polygons objects cast on it.
//
// Bouknight 1969, Chapter V: "the shadow cast on the plane of the shadowed polygon will also
// be a polygon. Therefore, there will be a three-space of shadow polygons, all lying in the
// planes of the various polygons of the original three-space structure". In a cell complex
// two things cast shadows, and each is handled where it is simple:
//   - Walls, floors and ceilings. Light reaches a cell only through portals
//     (visibility/light_reach.h): a face of a cell is lit where it lies inside the cone of
//     some chain of portals from the light to the cell — the union of the convex pieces
//     face ∩ cone; a face of the light's own cell is lit whole (a convex cell hides nothing of
//     itself). What lies outside every cone is in the shadow of the walls. No wall is ever
//     tested against another: the portals say it all.
//   - Objects (the plan's furniture). Each triangle of an object that faces the light (every
//     triangle of an open mesh) is an occluder; its shadow volume is the convex region
//     beyond it within the planes through the light and its edges, and its shadow polygon on
//     a surface is the surface cut to that volume (exact, convex, in the surface's plane).
//     A ray from the light to a point of a cell passes only through cells on its chain, so
//     only objects in cells the light reaches can shade anything. An object whose bounds
//     hold the light (the lamp it hangs in) casts no shadow from it.
// A point of a surface is lit when it lies in the surface's lit region (all of it when
// `whole`) and in none of its shadow polygons; the scanline tests both per sample in a
// secondary scan (scanline.h, SecondaryScan).
//
// Surfaces are the faces of cells (each face whole, as the half-tone draws it) and the input
// polygons of the objects, each kept as the triangles it was made of. A surface the light
// reaches only from behind (the light on the outer side of a face, behind a closed mesh's
// triangle) is not lit at all and has no entry.
#pragma once

#include <cstdint>
#include <vector>

#include "cells/cell_complex.h"
#include "render/lighting.h"
#include "render/scene_objects.h"
#include "visibility/light_reach.h"

namespace avenues {

/// What one light does to one surface.
struct SurfaceLight {
  bool whole = false;                      ///< the light reaches every point of it (less the shadows)
  std::vector<std::vector<Vec3>> lit;      ///< otherwise: the convex pieces it reaches, in the surface's plane
  std::vector<std::vector<Vec3>> shadow;   ///< shadow polygons cast by objects, convex, in the surface's plane
};

/// What one point light does to the scene.
struct LightShadows {
  LightReach reach;                      ///< the cells it reaches and through which portals
  std::vector<int32_t> face_surface;     ///< per global face (SceneShadows::face_base): into surfaces; -1: unlit
  std::vector<int32_t> polygon_surface;  ///< per global object polygon (SceneShadows::polygon_base): likewise
  std::vector<SurfaceLight> surfaces;
  long occluders = 0;        ///< object triangles that cast shadows
  long pairs_tested = 0;     ///< occluder–surface pairs cut against each other
  long shadow_polygons = 0;  ///< shadow polygons kept (of some area)
};

/// What every point light of a scene does.
struct SceneShadows {
  std::vector<int32_t> face_base;     ///< per cell: the global index of its first face
  std::vector<int32_t> polygon_base;  ///< per placed object, and one past the last: its first global polygon
  std::vector<LightShadows> lights;   ///< parallel to Lighting::points
  double micros = 0;                  ///< [µs] traversals from the lights and shadow polygons, all lights

  /// What light `light` does to face `face` of `cell`; nullptr: it does not light it.
  const SurfaceLight* on_face(size_t light, CellId cell, int face) const;
  /// What light `light` does to input polygon `polygon` (Mesh::polygon_of) of placed object `object`.
  const SurfaceLight* on_object(size_t light, int object, int polygon) const;
};

/// Traverses the cells from every point light of `lighting` (find_lit, in `kernel`) and casts
/// the shadows of `objects` (place_objects(complex)). Empty when the lighting is at the eye.
/// With `object_shadows` false, objects are lit (through portals, as walls are) but cast no
/// shadows. Lights are cast side by side on at most `threads` threads (0: as many as TBB offers).
SceneShadows cast_shadows(const CellComplex& complex, const std::vector<PlacedObject>& objects,
                          const Lighting& lighting, Kernel kernel = Kernel::Double, bool object_shadows = true,
                          int threads = 0);

/// The convex region of `surface` (a convex polygon) in the shadow volume of the convex
/// polygon `occluder` lit from `light`: beyond the occluder's plane and inside the planes
/// through the light and its edges. Empty if none of some area (relative 1e-9 of the surface).
std::vector<Vec3> shadow_on(const std::vector<Vec3>& surface, const std::vector<Vec3>& occluder, Vec3 light);

}  // namespace avenues
