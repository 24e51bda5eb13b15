// Avenues — a Plan written back as Avenues' own TOML (docs/PLAN_FORMAT.md).
//
// For a plan that came from elsewhere (a DXF drawing, floor-plan annotations, a Sweet
// Home 3D home) so that a person can correct by hand what the importer understood:
// read_plan() of what write_plan() wrote gives the same walls, openings, rooms,
// storeys, materials, lights, objects (with meshes of their own files, or written beside
// the plan: furniture boxes and models that came inside a file) and view. What the format
// cannot say is left out with a comment at the top of the file naming it: rooms named by
// their walls' sides instead of a label point (a Doom sector), a lenient or outside-solid
// plan's import rules. Walls are written as their straight centre lines (arcs already
// tessellated), openings measured along them, everything in metres.
#pragma once

#include <string>
#include <vector>

#include "plans/plan.h"

namespace avenues {

/// The plan as TOML text. An object that carries its own mesh (Object::model) or is a box
/// is left out (with a comment) unless `model_files` (per object) names the mesh file
/// written for it, relative to the plan's folder.
std::string plan_as_toml(const Plan& plan, const std::vector<std::string>& model_files = {});

/// Writes the plan to `path` as TOML, and the meshes of the objects that carry their own
/// (a model that came inside the file, a box) as OBJ files with their MTL libraries
/// (plans/obj_writer.h: z-up metres, each material's colour as Kd) in a folder beside it,
/// FILE.models/ (FILE: the plan's name without its extension), one pair per mesh, named
/// from the first object that uses it; the objects name them as their `mesh`. All or
/// nothing: the folder is made aside and renamed into place with the plan; a failure
/// leaves the plan and folder that were there. Throws std::runtime_error naming the file.
void write_plan(const Plan& plan, const std::string& path);

}  // namespace avenues
