// Avenues — coarser versions of a mesh, each within a stated distance of it (levels of
// detail for furniture far from the eye).
//
// OpenMesh's decimater collapses edges in the order of their quadric error (Garland and
// Heckbert) and refuses any collapse that would move the surface more than a tolerance
// from the points it had (its Hausdorff module keeps, for every face, the original vertices
// collapsed into it, and measures them against the faces that would replace it) or would
// flip a face. The tolerances are taken in turn in one pass, each level a snapshot when
// no collapse within its tolerance is left, so that every level is bounded against the
// original vertices, not against the level before. A renderer that draws a level only
// where its tolerance projects to less than half a sample moves no edge of the picture by
// more than that (docs/ACCURACY.md). Triangles keep the polygon, and so the material, they
// came from.
#pragma once

#include <vector>

#include "plans/mesh.h"

namespace avenues {

/// A coarser version of a mesh and how far from the original it may lie.
struct MeshLevel {
  Mesh mesh;
  double tolerance = 0;  ///< [mesh units] every vertex of the original lies within this of the level's surface
};

/// Coarser versions of `m`, one per tolerance (ascending). A level that would keep more than
/// three quarters of the triangles of the level before it (or of `m`) is left out, as are all
/// when `m` has fewer than `min_triangles`. Triangles OpenMesh cannot take into a manifold
/// (a third face on an edge, a face repeated) are kept in every level as they are. Corner
/// normals are made afresh (smooth_corner_normals).
std::vector<MeshLevel> coarser_levels(const Mesh& m, const std::vector<double>& tolerances, size_t min_triangles = 64);

/// coarser_levels of each mesh, its tolerances `fractions` of its bounding box's diagonal,
/// the meshes spread over TBB's threads (OpenMesh kept quiet meanwhile).
std::vector<std::vector<MeshLevel>> coarser_levels_of(const std::vector<const Mesh*>& meshes,
                                                      const std::vector<double>& fractions, size_t min_triangles = 64);

}  // namespace avenues
