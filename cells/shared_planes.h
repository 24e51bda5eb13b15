// Avenues — nearly coplanar neighbours of a soup cut space by one plane.
//
// A quad whose corners are coplanar only to a rounding (written to 17 digits, stored in
// floats, or a UV sphere's trapezoid computed in double) reaches the soup BSP as two
// triangles on two planes a hair's breadth apart, meeting along the diagonal. Each plane
// cuts the whole cell it crosses, so the pair makes a wedge of free space running from the
// diagonal to the cell's far side, thinner than rounding: a sliver, which drop_slivers
// (cells/mesh_scene.h) closes where it cannot join across it, leaving walls of no material
// in open space (a UV sphere written at 17 digits: 1,300 m² of them). Two panels meant to
// be one plane but stored a rounding apart make a slab of the same kind. Quake's qbsp
// meets these with ON_EPSILON; here the input is made planar where it is meant to be:
// triangles whose corners lie within a rounding of one plane take that plane, exactly, and
// the BSP sees one plane where the file meant one. Each corner moves at most that rounding,
// along the plane's dominant axis; two triangles on one plane that share an edge still
// share it exactly.
#pragma once

#include <array>
#include <vector>

#include "cells/soup_bsp.h"

namespace avenues {

/// How near "nearly coplanar" is: a triangle takes a plane when each of its corners lies
/// within `angle` times its longest edge of it, plus the rounding of the coordinates as
/// stored (a float's where every coordinate of the soup is a float's, as from glTF, FBX and
/// everything Assimp reads; else a double's), and its normal within `normal_turn` radians
/// of the plane's.
struct SharedPlaneParams {
  double angle = 1e-12;       ///< [rad] a plane's own rounding; what a model means tilted is kept
  double normal_turn = 1e-3;  ///< [rad] so that a standing sliver keeps its own plane
};

/// A plane the decomposition cuts on, as three corners of the soup's triangles (exact
/// input points, so the exact plane through them has small coefficients), its normal
/// cross(p[1] − p[0], p[2] − p[0]).
struct SharedPlane {
  std::array<Vec3, 3> p;
};

/// The planes of a soup's triangles: each triangle's own, or one that nearly coplanar
/// neighbours share.
struct SharedPlanes {
  std::vector<SharedPlane> planes;
  std::vector<int> plane_of;  ///< per triangle, the index of its plane
  /// Per triangle, true when its plane is its own: through its three corners, as they are.
  std::vector<bool> own;
};

/// The plane each triangle of `soup` lies on in the decomposition. Triangles are taken
/// largest first; each takes the first plane so far it lies on (SharedPlaneParams), or
/// makes its own. A group's plane is then made again through three of its members' corners
/// spread across it, so that its rounding tilts it by the rounding over the group's size,
/// not over its first triangle's, and the triangles are grouped again on those planes: the
/// triangles of a face tessellated finely, each coplanar with its neighbours only to a
/// rounding, come to one plane. The planes of the last grouping are the ones returned, so
/// every triangle lies on its plane within the tolerance. A triangle of no area (in
/// doubles) keeps its own plane.
SharedPlanes shared_planes(const std::vector<SoupTriangle>& soup, const SharedPlaneParams& params = {});

}  // namespace avenues
