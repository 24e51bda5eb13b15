// Avenues — building the cell complex from a plan (the one CGAL boundary).
//
// build_cells() runs a pipeline of small passes (Recast style), each timed into
// CellComplex::timings:
//   1. outline   — walls become convex solid quads (mitred joins, arcs already
//                  tessellated), zero-thickness walls become "sheets", openings
//                  become footprints, floor openings become holes;
//   2. triangulate — one exact constrained Delaunay triangulation (CGAL, Epeck with
//                  exact intersections) of every outline of every storey and the far box;
//   3. classify  — each triangle, per height band, is solid, or free space of one
//                  room / doorway / stairwell / the outside;
//   3b. cut      — each band's free regions triangulated again from their own
//                  boundaries; where that parts them into fewer convex pieces, its
//                  diagonals are added to the one triangulation as that band's cuts
//                  (band_cuts.cpp);
//   4. merge     — Hertel–Mehlhorn: adjacent free triangles of one class are merged
//                  while convex (never across a cut of the band), giving convex footprints;
//   5. extrude   — footprints become prisms; shared edges become portals, stacked
//                  footprints horizontal portals, the rest opaque faces;
//   6. lines     — the real lines of the architecture, assigned to the cells they bound.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "cells/cell_complex.h"
#include "plans/plan.h"

namespace avenues {

/// Parameters of the plan decomposition (none yet: the passes take what they need from
/// the plan itself).
struct CellParams {};

/// Builds the cell complex. Throws PlanError for plan mistakes found only now
/// (a room label inside a wall, a room open to the outside, ...).
CellComplex build_cells(const Plan& plan, const CellParams& params = {});

/// Independent checks of the complex (the same the tests run): convex cells that do not
/// overlap, free volume accounted for, convex portals lying in a face of both cells,
/// no portal joining a cell to itself. Returns "" when valid, else what is wrong.
std::string cells_are_valid(const CellComplex& complex);

/// In builds with invariant checks (core/check.h: -DAVENUES_INVARIANTS=ON, the default
/// for Debug), runs cells_are_valid and throws InvariantError naming `what` (the plan or
/// file) when the complex is invalid; otherwise does nothing. Every builder and loader
/// of complexes calls it on what it returns.
void check_complex(const CellComplex& complex, const std::string& what);

/// Saves / loads a decomposed complex (binary, versioned). Throws std::runtime_error
/// naming the file on failure; load_cells rebuilds the spatial index.
void save_cells(const CellComplex& complex, const std::string& path);
CellComplex load_cells(const std::string& path);
/// The same bytes in memory (what an MPI walk broadcasts to its ranks): cells_bytes() is
/// the whole file save_cells() writes; cells_from_bytes() checks and reads them as
/// load_cells() does, `name` standing for the file in its messages.
/// Objects' mesh paths are stored relative to `cells_dir` (the folder of the .cells file;
/// empty: the current folder, which every rank of a walk shares) and read back against it.
std::string cells_bytes(const CellComplex& complex, const std::filesystem::path& cells_dir = {});
CellComplex cells_from_bytes(std::string_view bytes, const std::string& name,
                             const std::filesystem::path& cells_dir = {});

/// Writes the opaque surfaces as a Wavefront OBJ triangle mesh, one group per cell
/// named "cell<id>", so other tools can read the building.
void export_obj(const CellComplex& complex, const std::string& path);

}  // namespace avenues
