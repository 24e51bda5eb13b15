// Avenues — an IFC building model (ISO 16739, as BIM tools export it) as a Plan.
//
// Assimp reads the model (plans/assimp_reader.h): it evaluates the IFC geometry, cuts the
// openings out of the walls, and names each node by its IFC type, name and GUID
// ("IfcWallStandardCase_Basic Wall:Interior_2O2Fr$t4X7Zf8NOew3FNld"). This reader slices
// that geometry into the 2.5D plan (docs/IFC.md says why, with the measurements):
// - each IfcBuildingStorey is a storey, its elevation the floor its spaces (else its
//   walls) stand on, its height up to the next storey's floor less the slab between;
// - walls, curtain walls and columns are walls: the centre line and thickness of the
//   smallest rectangle around their footprint where their section fills it, else the
//   convex pieces of their section (Wall::footprint), on every storey their height spans
//   or whose floor they stand on; one that stands on no floor (a bulkhead) is an object;
// - IfcDoor and IfcWindow are door and window openings in the wall they stand in, as wide
//   as they reach along it, from their lowest to their highest point;
// - IfcSpace is a room, named by its LongName (else its Name) as the STEP file writes it
//   (plans/formats/ifc_step.h), labelled at a point of its floor;
// - furniture, stairs, railings, roofs, members and fittings are objects (their meshes, in
//   their IFC colours) drawn but not cut out of the free space; slabs and coverings give
//   the rooms over and under them their floor and ceiling colours, else are objects.
// Elements whose geometry cannot be used are dropped with one warning each.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/stage_timer.h"
#include "plans/mesh.h"
#include "plans/plan.h"

namespace avenues {

/// A model with no walls or columns to walk between (a structural model of beams and
/// members, a single piece of equipment): not a building's plan, though its elements have
/// faces that can be shown as a scene. `faces` holds them, as the reader read them (IFC4
/// rewritten for Assimp, ifc4_for_assimp.h), in their colours, its spaces' volumes left out.
class IfcWithoutWalls : public PlanError {
 public:
  IfcWithoutWalls(SourceLoc where, const std::string& what, std::shared_ptr<const Mesh> faces)
      : PlanError(std::move(where), what), faces(std::move(faces)) {}
  std::shared_ptr<const Mesh> faces;
};

/// Reads an IFC file (STEP physical file, IFC2X3 or IFC4) as a
/// lenient Plan, its first view at eye height in the largest named space of the entrance
/// storey (the storey with spaces whose floor is nearest the ground, z = 0), looking along
/// its longest free direction. Throws PlanError naming the file for a file that is not a
/// STEP file, is cut short or has a broken record or dangling reference (naming the line),
/// with Assimp's reason (naming the entity) for what it cannot read or that its reader
/// crashed (it reads the model in a child process first), and IfcWithoutWalls for a model
/// with no walls or columns to walk between. When `stages` is given,
/// the time of Assimp's own import ("assimp import") and of the slicing after it ("IFC to
/// plan") are appended to it.
Plan read_ifc_building(const std::string& path, std::vector<StageTime>* stages = nullptr);

}  // namespace avenues
