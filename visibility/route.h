// Avenues — a route for the eye through named rooms, on the portal graph.
//
// The cells and their portals are a graph (Jones's Fig. 3). A person walks from cell to
// cell through the portals a person can pass: doors and the transparent faces inside a
// room or the outside (bottom at floor level, at least head height), never windows or
// hatches. route_through() finds, for each room in turn, the shortest such path from
// where the walk is to that room (Dijkstra over portal centres), and returns the
// waypoints at eye height: the start (the centre of the first room's largest cell), the
// centre of every portal crossed, and the centre of the cell by which each room is entered.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "visibility/viewpoint.h"

namespace avenues {

struct RouteOptions {
  double eye_height = kEyeHeight;   ///< [m] above each cell's floor
  double min_height = 1.9;   ///< [m] a portal lower than this cannot be walked through
  double max_step = 0.35;    ///< [m] a portal whose bottom is higher above the floor cannot be stepped into
};

/// Waypoints [m] through the named rooms, in order. Throws std::runtime_error naming a room
/// that the plan does not have (listing the ones it has), or one that cannot be reached
/// on foot from the room before it.
std::vector<Vec3> route_through(const CellComplex& complex, const std::vector<std::string>& rooms,
                                const RouteOptions& options = {});

/// Points every `step` metres along a Catmull–Rom curve through the waypoints (each
/// waypoint is passed exactly); where a point of the curve would leave free space the
/// straight line between the two waypoints is used instead.
std::vector<Vec3> smooth_path(const CellComplex& complex, const std::vector<Vec3>& waypoints, double step);

/// How many points smooth_path() gives for these waypoints and step (and how many a walk
/// straight between them, one point every `step` metres, has): 1 for the first, then for
/// each stretch ceil(length / step), at least 1. Counted in 64 bits without making the
/// points, so a caller can refuse a walk too long to make; a huge count comes back as is.
int64_t path_points(const std::vector<Vec3>& waypoints, double step);
/// The points of the stretch from a to b: ceil(|b - a| / step), at least 1.
int64_t stretch_points(Vec3 a, Vec3 b, double step);

}  // namespace avenues
