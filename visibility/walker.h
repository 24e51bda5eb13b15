// Avenues — the walking eye: motion that keeps the eye in free space.
//
// A walkthrough moves the eye a little every frame. Every move is a straight segment
// walked through the cell complex from the eye's cell (the cells are convex, so the
// segment leaves each through one face): it passes a face only where a portal opens it,
// and stops at the first opaque face. So the eye never enters a wall or a slab — it can
// only be where a chain of portals leads — and the check costs a few cells per move.
//
// Walk mode (a person): the eye stays at eye height above the floor under it. A move is
// tested at the eye and at the knee (step_height above the feet), so the eye passes an
// opening only if a person could walk through it (a door, not a window or the gap above
// a low wall), steps onto a floor at most step_height higher, and falls (at fall_speed) to
// a lower one. A blocked move slides: along the wall it met, else along each axis alone.
// A stairwell (a hole in a floor slab) holds a stair: while the eye stands in the hole's
// column it keeps its height, and a vertical move climbs or descends through the hole,
// between the lower floor and the upper one (each at eye height). Elsewhere vertical moves
// are refused: walking keeps to the floors.
// Fly mode: any move through portals (windows too), still never into a solid.
// A curved solid that the cells run through (CellComplex::detail_solids) stops a move
// where it enters its surface, as a face does; so does a triangle of a large soup's detail
// (CellComplex::detail_boxes: the walls, slabs and members that were left out of cutting
// space so that it decomposes in seconds), from either side.
//
// Both keep `clearance` between the eye and a wall ahead (the segment is tested that much
// further along its direction) and, sideways, along the four horizontal axes, so that a
// stereo pair's eyes (a few centimetres either side) stay in free space too.
#pragma once

#include <cmath>
#include <cstdint>

#include "cells/cell_complex.h"
#include "visibility/viewpoint.h"

namespace avenues {

/// Where a straight segment walked through the cells from its start stops.
struct SegmentCast {
  double t = 1;             ///< fraction of the segment travelled, [0, 1]; 1 if it was not blocked
  bool blocked = false;     ///< an opaque face (or a face with no portal at that point) stopped it
  CellId cell = kNoCell;    ///< the cell holding the point at t
  Vec3 normal;              ///< for a blocked segment: the outward normal of the face that stopped it
  bool stairwell = false;   ///< the segment crossed a stairwell portal (a hole in a floor)
};

/// Walks the segment a→b from `from` (a cell holding a) through the portals, stopping at the
/// first opaque face, where it first enters one of the complex's detail solids, or at the
/// first triangle of a cell's detail it crosses (one it starts on, it leaves).
/// Conservative: where rounding cannot tell a portal from a wall, a wall.
SegmentCast cast_segment(const CellComplex& complex, CellId from, Vec3 a, Vec3 b);

enum class MoveMode : uint8_t {
  Walk,  ///< on the floors, through openings a person can walk through, up and down stairwells
  Fly,   ///< anywhere in free space
};
const char* to_string(MoveMode m);

struct WalkerOptions {
  double eye_height = kEyeHeight;    ///< [m] > step_height: the eye above the floor (walk mode)
  double step_height = 0.35;  ///< [m] >= 0: the highest floor step taken in one stride
  double clearance = 0.15;    ///< [m] >= 0: kept between the eye and a wall
  double fall_speed = 4;      ///< [m/s] > 0: how fast the eye comes down to a lower floor
};

/// The eye that walks (or flies) through a cell complex; it is always in a cell.
class Walker {
 public:
  /// Starts at `eye`, which must lie in a cell (throws std::runtime_error naming the solid
  /// otherwise). In walk mode the eye keeps the height it is given until it moves or settles.
  Walker(const CellComplex& complex, Vec3 eye, const WalkerOptions& options = {});

  Vec3 eye() const { return eye_; }
  CellId cell() const { return cell_; }
  MoveMode mode() const { return mode_; }
  void set_mode(MoveMode m) { mode_ = m; }
  const WalkerOptions& options() const { return options_; }

  /// Moves the eye by `delta` [m] (world): horizontally in walk mode, sliding where blocked;
  /// the vertical part only in fly mode or up and down a stairwell. Then, in walk mode, lets
  /// the eye settle towards eye height above the floor for `dt` seconds (falling, at most
  /// fall_speed·dt). Returns how far the eye moved [m].
  double move(Vec3 delta, double dt);

  /// Height of the floor under the eye [m]: the first opaque face straight below it, or in
  /// a scene of meshes (no storeys) the ground the model stands on (its lowest point), where
  /// that is higher and the eye above it. A model with no ground of its own (furniture, a
  /// grid of open boxes) is walked around at its foot, not from the far box's bottom below it.
  double floor_below() const;
  /// [m] The ground the eye stands on where no floor is below it: a scene of meshes' lowest
  /// point (of its opaque faces and its detail); -inf for a plan (its storeys' floors and
  /// the outside's ground are faces).
  double ground() const { return ground_; }
  /// True when the eye stands in a stairwell's column (a floor hole above or below it, with
  /// no floor between).
  bool on_stair() const;

 private:
  /// A horizontal (walk) or any (fly) move to eye_ + d, accepted whole or not at all.
  bool try_move(Vec3 d, Vec3* blocked_normal);
  bool try_walk(Vec3 d, Vec3* blocked_normal);
  bool try_fly(Vec3 d, Vec3* blocked_normal);
  bool try_climb(double dz);
  /// [m] The first opaque face straight below p, in `cell`, down to the far box's bottom;
  /// `stairwell`: whether the way down crosses a stairwell.
  double face_under(Vec3 p, CellId cell, bool* stairwell = nullptr) const;
  /// A segment from the eye's cell (or the cell holding p, found from it).
  SegmentCast cast_from(Vec3 p, CellId hint, Vec3 q) const;
  /// The shortest free distance from p along the four horizontal axes, up to clearance.
  double side_room(Vec3 p, CellId cell) const;
  /// Moves the eye to p in cell `c` if p is located in a cell (the final, closed check).
  bool commit(Vec3 p, CellId c);
  void settle(double dt);

  const CellComplex& c_;
  WalkerOptions options_;
  MoveMode mode_ = MoveMode::Walk;
  Vec3 eye_;
  CellId cell_ = kNoCell;
  double ground_ = -HUGE_VAL;  ///< ground()
};

}  // namespace avenues
