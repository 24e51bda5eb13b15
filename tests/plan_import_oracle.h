// Shared checks for plans imported from 2D drawings (floor-plan annotations, DXF): the
// complex is valid, and views from each room's label, looking four ways, agree with
// ray casting (tests/ray_oracle.h).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cells/build_cells.h"
#include "ray_oracle.h"
#include "visibility/visible_set.h"

namespace avenues::testing {

/// Views from every room label that lies in a cell, at eye height, looking east, north,
/// west and south; returns how many views were checked.
inline int check_views_from_rooms(const Plan& plan, const CellComplex& c) {
  int views = 0;
  for (const Room& r : plan.rooms) {
    if (!r.label) continue;
    const Vec3 eye{r.label->x, r.label->y, 1.6};
    const Location at = c.locate(eye);
    if (at.what != Location::What::Cell) continue;
    for (int k = 0; k < 4; ++k) {
      const double a = k * std::numbers::pi / 2;
      const Camera cam = Camera::look_at(eye, eye + Vec3{std::cos(a), std::sin(a), -0.1}, 70, 64, 40);
      const VisibleSet vs = find_visible(c, cam, at.cell, Kernel::Double);
      const OracleResult res = check_visible_set(c, cam, vs, 2);
      EXPECT_EQ(res.missing, 0) << "room '" << r.name << "' looking " << k * 90 << " deg";
      EXPECT_EQ(res.extra, 0) << "room '" << r.name << "' looking " << k * 90 << " deg";
      ++views;
    }
  }
  return views;
}

/// Portals of `kind` onto an outside cell: a way out of the building (from a room, or
/// from the doorway cell of a window's glass).
inline int portals_out(const CellComplex& c, PortalKind kind) {
  int n = 0;
  for (const Portal& p : c.portals)
    n += p.kind == kind && (c.cells[size_t(p.cell[0])].kind == CellKind::Outside ||
                            c.cells[size_t(p.cell[1])].kind == CellKind::Outside);
  return n;
}

/// Door portals in the complex.
inline int door_portals(const CellComplex& c) {
  int n = 0;
  for (const Portal& p : c.portals) n += p.kind == PortalKind::Door;
  return n;
}

}  // namespace avenues::testing
