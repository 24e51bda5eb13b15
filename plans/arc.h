// Avenues — a circular arc through three points of a plan, and its tessellation.
//
// Plans give arcs by three points (a TOML wall's `through`, a Sweet Home wall's bulge
// turned into its midpoint): the circle through them, from a through m to b, is cut into
// n >= 2 equal pieces whose sagitta r·(1 − cos(θ/2)) is at most the plan's tolerance.
#pragma once

#include <optional>
#include <vector>

#include "core/geometry.h"

namespace avenues {

struct Arc {
  Vec2 centre;
  double radius = 0;
  double start = 0;  ///< [rad] the angle of a seen from the centre
  double sweep = 0;  ///< [rad] signed: counter-clockwise > 0
  double length() const { return radius * std::fabs(sweep); }
  /// How many equal pieces (>= 2, a whole number) keep each piece's sagitta within `tol`.
  double pieces_for(double tol) const;
  /// Appends the ends of `n` equal pieces after a: the points between, then b exactly.
  void append(long n, Vec2 b, std::vector<Vec2>& out) const;
};

/// The arc from a through m to b; nullopt when the three are collinear (or m equals an end).
std::optional<Arc> arc_through(Vec2 a, Vec2 m, Vec2 b);

}  // namespace avenues
