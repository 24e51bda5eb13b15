// Avenues tests — checks of a soup BSP scene (cells/soup_bsp.h) shared by soup_bsp_test.cpp
// and hard_cases_test.cpp: every input triangle kept as opaque surface, and random views
// against the ray oracle.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "cells/mesh_scene.h"
#include "cells/solid_insides.h"
#include "core/float_rounding.h"
#include "hull_checks.h"
#include "ray_oracle.h"
#include "test_files.h"
#include "test_plans.h"
#include "visibility/visible_set.h"

namespace avenues::testing {


/// Input triangles (of some area) with no opaque piece of the complex, and no detail
/// object's triangle, covering their centroid, on their plane, as (mesh, triangle) indices. Each triangle is looked up among
/// the opaque pieces whose bounds hold the centroid (found in a BoxTree). `near` [m]: how
/// far off the triangle's plane a covering piece may lie (0: the rounding of one
/// coordinate, 1e-9 of the far box).
inline std::vector<std::pair<size_t, size_t>> missing_triangles(const CellComplex& c, const std::vector<Mesh>& meshes,
                                                                double near = 0) {
  struct Piece {
    const std::vector<Vec3>* poly;
    Plane plane;
    Box3 box;
  };
  std::vector<Piece> pieces;
  std::vector<Box3> boxes;
  auto add = [&](const std::vector<Vec3>& poly, const Plane& plane) {
    Box3 b;
    for (Vec3 p : poly) b.add(p);
    pieces.push_back({&poly, plane, b});
    boxes.push_back(b);
  };
  for (const Cell& cell : c.cells)
    for (const Face& f : cell.faces)
      for (const OpaquePoly& op : f.opaque) add(op.poly, f.plane);
  // Detail (a large soup's small polygons, a curved solid's facets) is kept as the
  // triangles of objects cut to one cell each.
  std::vector<std::vector<Vec3>> detail;
  for (const Object& o : c.objects)
    if (o.cell >= 0 && o.model)
      for (const auto& t : o.model->triangles)
        detail.push_back({o.model->vertices[size_t(t[0])], o.model->vertices[size_t(t[1])], o.model->vertices[size_t(t[2])]});
  for (const std::vector<Vec3>& t : detail) {
    Vec3 n = cross(t[2] - t[0], t[1] - t[0]);  // the triangle turns clockwise about it, as a face's pieces do
    if (!(length(n) > 0)) continue;
    n = (1 / length(n)) * n;
    add(t, {n, -dot(n, t[0])});
  }
  const BoxTree tree(std::move(boxes));
  const double scale = c.far_box.magnitude();
  const double tol = std::max(near, 1e-9 * scale);
  std::vector<std::pair<size_t, size_t>> missing;
  for (size_t mi = 0; mi < meshes.size(); ++mi)
    for (size_t ti = 0; ti < meshes[mi].triangles.size(); ++ti) {
      const Mesh& m = meshes[mi];
      const auto& t = m.triangles[ti];
      const Vec3 a = m.vertices[size_t(t[0])], b = m.vertices[size_t(t[1])], d = m.vertices[size_t(t[2])];
      const Vec3 n = cross(b - a, d - a);
      if (!(length(n) > 1e-20 * scale * scale)) continue;  // no area: dropped, with a warning
      const Vec3 g = (1.0 / 3) * (a + b + d);
      bool found = false;
      tree.visit_holding(g, tol, [&](uint32_t k) {
        const Piece& p = pieces[k];
        if (!p.box.contains(g, tol) || std::fabs(p.plane.eval(g)) > tol) return false;
        bool in = true;
        const auto& q = *p.poly;
        for (size_t e = 0; e < q.size() && in; ++e) {
          // Two corners a rounding apart bound nothing: the edge between them has no
          // direction of its own, and may turn the rounded piece inward.
          const Vec3 side = q[(e + 1) % q.size()] - q[e];
          if (length(side) <= 1e-12 * scale) continue;
          in = dot(cross(side, g - q[e]), p.plane.n) <= tol * length(side);
        }
        found = in;
        return found;
      });
      if (!found) missing.emplace_back(mi, ti);
    }
  return missing;
}

/// How many input triangles missing_triangles finds.
inline int triangles_missing_from_export(const CellComplex& c, const std::vector<Mesh>& meshes) {
  return int(missing_triangles(c, meshes).size());
}

/// Whether p lies inside a closed, outward-oriented solid of the meshes (closed_solids):
/// their winding numbers about it sum to over ½.
inline bool inside_closed_solid(const std::vector<ClosedSolid>& solids, Vec3 p) {
  double w = 0;
  for (const ClosedSolid& s : solids)
    if (s.box.contains(p, 1e-9 * length(s.box.hi - s.box.lo))) w += winding_number(s.triangles, p);  // else about 0
  return w > 0.5;
}

/// How far a triangle of the meshes may lie off the plane it is cut on: a larger nearly
/// coplanar triangle's (cells/shared_planes.h), whose corners and its own lie off one plane
/// by up to the rounding of the coordinates as stored: a float's where every coordinate is
/// a float's (whatever Assimp reads), else a micrometre, the checks' own tolerance.
inline double snapping_reach(const std::vector<Mesh>& meshes) {
  bool floats = true;
  double largest = 0;
  for (const Mesh& m : meshes)
    for (Vec3 v : m.vertices)
      for (double x : {v.x, v.y, v.z}) floats = floats && is_float(x), largest = std::max(largest, std::fabs(x));
  return floats ? std::max(1e-6, 2 * std::ldexp(largest, -23)) : 1e-6;
}

/// Input triangles missing from the export (triangles_missing_from_export) that someone
/// could see: those with a side not inside a closed solid, and not hidden by another
/// surface within a micrometre of them (coincident faces of two elements, of which the
/// complex keeps the one in front), or within snapping_reach where that is more. A triangle
/// between two solids that touch, or inside a solid, is seen from neither side, and is not
/// counted. Its sides are tested twice that far off its centroid: a floor of floats whose
/// height wanders by a float's rounding lies that far above the slab it stands on.
inline int visible_triangles_missing_from_export(const CellComplex& c, const std::vector<Mesh>& meshes) {
  const std::vector<ClosedSolid> solids = closed_solids(meshes);
  const double near = snapping_reach(meshes);
  int missing = 0;
  for (const auto& [mi, ti] : missing_triangles(c, meshes, near)) {
    const Mesh& m = meshes[mi];
    const auto& t = m.triangles[ti];
    const Vec3 a = m.vertices[size_t(t[0])], b = m.vertices[size_t(t[1])], d = m.vertices[size_t(t[2])];
    const Vec3 g = (1.0 / 3) * (a + b + d);
    Vec3 n = cross(b - a, d - a);
    n = (2 * near / length(n)) * n;
    missing += !inside_closed_solid(solids, g + n) || !inside_closed_solid(solids, g - n);
  }
  return missing;
}

/// The volume of the meshes' closed solids (closed_solids), which are not free space:
/// with solids that do not overlap, the far box's volume less this is the free volume.
/// With a complex: less the curved solids it draws as detail (CellComplex::detail_solids),
/// whose insides its cells run through.
inline double closed_solids_volume(const std::vector<Mesh>& meshes, const CellComplex* c = nullptr) {
  double v = 0;
  for (const ClosedSolid& s : closed_solids(meshes)) {
    bool detail = false;
    if (c)
      for (const ClosedSurface& d : c->detail_solids) detail |= d.name() == s.name;
    if (!detail) v += s.volume;
  }
  return v;
}

/// `views` random views from random cells at `width` × `height`, one ray every `step`
/// pixels checked against the ray oracle: no missing cell, no extra avenue. With
/// `needles` > 0, only the first `needles` views where a search settles a mask
/// (VisibleSet::masks_settled: a portal clipped a mask to a needle with a corner strayed
/// past its parent's) are checked, and `checked` counts them.
inline void expect_soup_views_agree_with_rays(const CellComplex& c, int views, unsigned seed, int width, int height,
                                              int step, int first = 0, int needles = 0, int* checked = nullptr) {
  int needle_views = 0;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<size_t> pick(0, c.cells.size() - 1);
  std::uniform_real_distribution<double> yaw(0, 360), pitch(-60, 60), fov(40, 110);
  for (int v = 0; v < views; ++v) {
    Vec3 eye = random_point_in(c.cells[pick(rng)], rng);
    // Cells run through the curved solids drawn as detail, and a point weighted towards a
    // cell's middle is often inside one: no eye stands there, so another is drawn, evenly
    // over a cell's bounds.
    for (int again = 0; again < 1000 && !c.detail_solids.empty() && c.locate(eye).what == Location::What::Solid;
         ++again) {
      const Cell& cell = c.cells[pick(rng)];
      const Box3 b = cell.bounds();
      std::uniform_real_distribution<double> u(0, 1);
      const Vec3 p{b.lo.x + u(rng) * (b.hi.x - b.lo.x), b.lo.y + u(rng) * (b.hi.y - b.lo.y),
                   b.lo.z + u(rng) * (b.hi.z - b.lo.z)};
      if (cell.contains(p)) eye = p;
    }
    const Location loc = c.locate(eye);
    ASSERT_EQ(loc.what, Location::What::Cell) << "view " << v;
    const double y = yaw(rng), p = pitch(rng), f = fov(rng);
    if (v < first) continue;  // drawn, so that view `first` is the one a longer run makes
    Camera cam = Camera::yaw_pitch(eye, y, p, f, width, height);
    // A soup's cells can be millimetres across, and the eye as near a surface: a near plane
    // cutting a surface in view shows what lies behind it in a picture resolved by depth and
    // nothing in one drawn by masks (the search never looks behind an opaque surface).
    cam.near = 1e-4;
    if (needles > 0) {
      if (needle_views == needles) return;
      long settled = 0;
      for (int search = 0; search < 3; ++search) {  // Jones's, merged, hull
        TraverseParams params;
        params.merge_pieces = search > 0;
        params.hull_pieces = search == 2;
        settled += find_visible(c, cam, loc.cell, params).masks_settled;
      }
      if (settled == 0) continue;
      ++needle_views;
    }
    if (checked) ++*checked;
    SCOPED_TRACE("view " + std::to_string(v) + ": eye " + std::to_string(eye.x) + "," + std::to_string(eye.y) + "," +
                 std::to_string(eye.z) + " yaw " + std::to_string(y) + " pitch " + std::to_string(p));
    // Jones's search and the merged one (TraverseParams::merge_pieces), which the
    // walkthrough uses: the soups' finely sliced outsides are what it is for.
    for (bool merge : {false, true}) {
      SCOPED_TRACE(merge ? "merged search" : "Jones's search");
      TraverseParams params;
      params.merge_pieces = merge;
      const VisibleSet vs = find_visible(c, cam, loc.cell, params);
      const OracleResult r = check_visible_set(c, cam, vs, step);
      EXPECT_EQ(r.missing, 0);
      EXPECT_EQ(r.extra, 0);
      // The hull search, which the walkthrough's half-tone may use: conservative, and the
      // merged search's picture.
      static const std::vector<PlacedObject> no_objects;
      HullTally tally;
      if (merge) expect_hull_holds_merged(c, cam, loc.cell, Kernel::Double, vs, &no_objects, tally);
    }
  }
}

}  // namespace avenues::testing
