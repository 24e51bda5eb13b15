// Avenues — the papers' test scenes (app/paper_bench.h runs them beside the papers' figures).
//
// Bouknight 1969 timed LINESCAN on four scenes at 512 × 512 on a CDC 1604 (Figs. 8–11):
// an A-frame cottage, a torus, a "ripple" torus and an array of cubes. Wylie 1967 drew a
// cube of 12 triangles and a tetrahedron (about 25 s a frame at 512 × 512 on a Univac
// 1108). Crow 1981 lists an object of 10 points and 7 polygons (table 1b). The scans of the
// papers lost their figures, so only the counts and the words remain; what each scene
// had to guess is in its `guesses`. The scenes are generated here and bundled as OFF
// files in plans/scenes/ (written by off_text; a test keeps the two in step).
#pragma once

#include <string>
#include <vector>

#include "core/geometry.h"
#include "plans/plan.h"
#include "render/halftone.h"
#include "plans/mesh.h"
#include "render/scene_objects.h"
#include "visibility/camera.h"

namespace avenues {

struct PaperScene {
  std::string name;      ///< key, e.g. "ripple-torus"; the bundled file is plans/scenes/<name>.off
  std::string source;    ///< where in which paper
  std::string guesses;   ///< what the paper does not say and we chose
  std::vector<Vec3> vertices;              ///< [scene units]
  std::vector<std::vector<int>> polygons;  ///< convex, counter-clockwise seen from outside
  MeshPaint paint;                         ///< materials per polygon (the cottage's darker roof undersides)
  Camera camera;                           ///< 512 × 512, looking at the scene
  // What the paper reports (at 512 × 512).
  int paper_polygons = 0, paper_edges = 0;  ///< 0: not given
  double paper_seconds = -1;                ///< < 0: not given
  std::string paper_machine;                ///< what those seconds were measured on
  std::string paper_figures;                ///< other figures the paper gives, as text
};

/// Bouknight's cottage, torus, ripple torus and array of cubes; Wylie's cube and
/// tetrahedron; Crow's object.
std::vector<PaperScene> paper_scenes();

/// The scene as a Mesh, exactly as load_mesh reads its OFF file (fan triangles, polygon
/// indices, averaged vertex normals, closedness).
Mesh mesh_of(const PaperScene& scene);
/// The scene's OFF file (as bundled in plans/scenes/).
std::string off_text(const PaperScene& scene);

}  // namespace avenues
