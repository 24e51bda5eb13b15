// Avenues — do any two polygons of a scene pass through each other? Asked once, when the
// scene is loaded, so that the scanline searches for Bouknight's "implicitly defined lines"
// only in a scene that has them.
//
// Bouknight 1969, Appendix 2: where two polygons interpenetrate, the visible one changes
// along a line that is no edge of either, and the scan must split its key squares there. The
// scanline (scanline.h) resolves depth only among polygons covering the same run of samples;
// if the nearest of them changed within the run, their planes would meet at a point inside
// both — the polygons would cross. So with no crossing pairs the nearest polygon at a run's
// left end is the nearest all along it, and the search can be skipped.
//
// Which pairs can compete: objects against each other and against the faces of their own cell
// (a view resolves depth within one cell's avenue: scene_screen.h), or, for meshes alone, every
// polygon against every other. Triangles that share a vertex of one mesh are neighbours, not
// crossings. The test is Möller's (1997): each triangle must have corners strictly on both
// sides of the other's plane (by more than a tolerance, so that touching — a table's legs on
// the floor, a box on a box — is not crossing), and the two segments where each meets the
// other's plane must overlap along their common line by more than the tolerance. Candidate
// pairs are found by sweeping bounding boxes along x.
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/mesh.h"
#include "render/scene_objects.h"

namespace avenues {

struct Interpenetration {
  bool found = false;
  std::string what;        ///< the first crossing found, as a clause ("object 'table' and a face of its cell cross")
  long pairs_tested = 0;   ///< triangle pairs whose boxes met and were tested
};

/// True when triangles a and b cross properly (not merely touch), to `tol` [m].
bool triangles_cross(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b, double tol);

/// The objects of each cell (every cell each meets, PlacedObject::cells) against each other
/// and the faces of that cell.
Interpenetration find_interpenetration(const CellComplex& complex, const std::vector<PlacedObject>& objects);

/// Meshes alone, every polygon against every other.
Interpenetration find_interpenetration(const std::vector<Mesh>& meshes);

}  // namespace avenues
