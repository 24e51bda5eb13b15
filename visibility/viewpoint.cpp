// Avenues — the default viewpoint (see viewpoint.h).
#include "visibility/viewpoint.h"

#include <cmath>

#include "visibility/camera.h"
#include "visibility/visible_set.h"

namespace avenues {

Viewpoint default_viewpoint(const CellComplex& c) {
  if (c.view) return *c.view;
  // The first room that has a cell, preferring named rooms.
  CellId best = kNoCell;
  for (int pass = 0; pass < 2 && best == kNoCell; ++pass)
    for (size_t r = 0; r < c.rooms.size() && best == kNoCell; ++r) {
      if (pass == 0 && !c.rooms[r].named) continue;
      best = c.largest_cell_of(RoomId(r));
    }
  Viewpoint v;
  v.fov_deg = 60;
  if (best == kNoCell) {  // no rooms at all: stand outside, looking at the box's centre
    v.eye = {c.far_box.lo.x + 1, c.far_box.lo.y + 1, kEyeHeight};
    v.look = {(c.far_box.lo.x + c.far_box.hi.x) / 2, (c.far_box.lo.y + c.far_box.hi.y) / 2, kEyeHeight};
    return v;
  }
  const Cell& cell = c.cells[size_t(best)];
  Vec2 m = centroid(cell.footprint);
  v.eye = {m.x, m.y, cell.z0 + std::min(kEyeHeight, (cell.z1 - cell.z0) * 0.65)};
  // Look through the first door of the cell, else the first window or hatch.
  const Portal* through = nullptr;
  for (PortalKind want : {PortalKind::Door, PortalKind::Window, PortalKind::Hatch})
    for (PortalId p : cell.portals)
      if (!through && c.portals[size_t(p)].kind == want && std::fabs(c.portals[size_t(p)].plane.n.z) < 0.5)
        through = &c.portals[size_t(p)];
  if (through) {
    Vec3 mid{0, 0, 0};
    for (Vec3 q : through->poly) mid = mid + q;
    mid = (1.0 / double(through->poly.size())) * mid;
    v.look = {mid.x, mid.y, v.eye.z};
    return v;
  }
  // A cell with none (a room parted into several cells, its doors in another; a drawing's
  // room whose door was not recognised): of sixteen headings, the one that sees the most
  // cells, i.e. along the room and out of it, not at the nearest wall. The first of equals.
  size_t most = 0;
  v.look = v.eye + Vec3{1, 0, 0};
  for (int k = 0; k < 16; ++k) {
    const double yaw = k * 22.5;
    const Camera cam = Camera::yaw_pitch(v.eye, yaw, 0, v.fov_deg, 64, 36);
    const size_t seen = find_visible(c, cam, best, Kernel::Double).cells.size();
    if (seen > most) most = seen, v.look = v.eye + cam.forward;
  }
  return v;
}

}  // namespace avenues
