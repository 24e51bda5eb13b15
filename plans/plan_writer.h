// Avenues — a Plan written back as Avenues' own TOML (docs/PLAN_FORMAT.md).
//
// For a plan that came from elsewhere (a DXF drawing, floor-plan annotations, a Sweet
// Home 3D home) so that a person can correct by hand what the importer understood:
// read_plan() of what write_plan() wrote gives the same walls, openings, rooms,
// storeys, materials, lights, objects with meshes and view. What the format cannot say
// is left out with a comment at the top of the file naming it: furniture boxes and
// models that came inside a file, rooms named by their walls' sides instead of a label
// point (a Doom sector), a lenient or outside-solid plan's import rules. Walls are
// written as their straight centre lines (arcs already tessellated), openings measured
// along them, everything in metres.
#pragma once

#include <string>

#include "plans/plan.h"

namespace avenues {

/// The plan as TOML text.
std::string plan_as_toml(const Plan& plan);

/// Writes plan_as_toml(plan) to `path` (atomically). Throws std::runtime_error naming the file.
void write_plan(const Plan& plan, const std::string& path);

}  // namespace avenues
