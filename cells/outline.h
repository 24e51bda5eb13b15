// Avenues — pass 1 of build_cells: the plan's walls as 2D outlines.
//
// Every wall segment becomes a convex "region" (its mitred quad, cut into strips at
// its openings) or, for a wall of no thickness, a "sheet" (a segment, cut likewise).
// Each region or sheet strip says over which heights it is open: a solid strip of a
// full-height wall is never open, a door strip is open from sill to head, and a low
// wall is open from its top to the ceiling. Everything here is plain doubles; the
// exact work starts in triangulate.
#pragma once

#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "plans/plan.h"

namespace avenues::detail {

/// [m] Free space thinner than this between walls, or a band of heights this thin, is a
/// gap in the model, not a space: walls of a BIM model or a Sweet Home home stored in
/// single precision miss each other by fractions of a micrometre where they were drawn
/// to meet, and a storey may start 0.2 µm below the ground. Such a gap is closed (wall
/// where the walls beside it are, classify.cpp's close_gaps; nothing is moved) instead of
/// becoming a cell no eye can stand in and no sight can pass through; a hundredth of a
/// millimetre is far below anything built.
constexpr double kGap = 1e-5;

/// Closed height intervals [lo, hi], absolute z [m], sorted and disjoint.
using Intervals = std::vector<std::pair<double, double>>;
Intervals intersect(const Intervals& a, const Intervals& b);
Intervals unite(Intervals a);

/// A wall's sloped top (Wall::height_at_end) as a plane over the plan: the height [m,
/// absolute] z(p) = z0 + dot(grad, p - at). Compared exactly: the regions of one wall
/// segment share one.
struct Slope {
  Vec2 at, grad;
  double z0 = 0;
  double operator()(Vec2 p) const { return z0 + dot(grad, p - at); }
  auto key() const { return std::tuple(at.x, at.y, grad.x, grad.y, z0); }
  bool operator==(const Slope& o) const { return key() == o.key(); }
  bool operator<(const Slope& o) const { return key() < o.key(); }
};

/// A convex piece of a thick wall, or a strip of a wall of no thickness.
struct Region {
  StoreyId storey = 0;
  int wall = -1;             ///< index into Plan::walls
  int opening = -1;          ///< index into the wall's openings, -1 for solid strips
  bool sheet = false;        ///< zero thickness: `poly` holds the segment's two ends
  std::vector<Vec2> poly;    ///< convex, counter-clockwise (or the sheet's 2 ends)
  Intervals open;            ///< heights [m, absolute] at which the strip is open
  /// Set over a sloped wall: the last interval of `open` (the one up to the ceiling) starts
  /// at this plane, the wall's top, not at its stored lower bound (the plane's least
  /// height over `poly`). No height of the strip's own or of an overlapping wall's
  /// intervals lies strictly between the plane's least and greatest over `poly`: the
  /// strip is cut where one would (settle_slopes, outline.cpp).
  std::optional<Slope> top;
};

struct Outline {
  std::vector<Region> regions;
  std::vector<std::vector<Vec2>> holes;  ///< floor openings, same order as Plan::floor_openings
  Vec2 lo, hi;                           ///< far box in plan [m]
  double z_bottom = 0, z_top = 0;        ///< far box heights [m]
  std::vector<int> first_opening;        ///< per wall, the id of its first opening (see opening_id)
};

/// Builds the outlines of every wall of the plan.
Outline make_outline(const Plan& plan);

/// Stable id of a wall opening across the whole plan (for portal/cell `opening`): the
/// openings numbered wall by wall, in order.
int opening_id(const Outline& outline, int wall, int opening);

}  // namespace avenues::detail
