// Avenues — a Doom map as a Plan.
//
// A Doom level is already a cell-and-portal world in disguise: its sectors are rooms
// with their own floor and ceiling heights, its two-sided linedefs are the openings
// between them (open between the higher floor and the lower ceiling, the "upper" and
// "lower" textures opaque), its one-sided linedefs are walls, and the void around the
// map is solid. The importer turns each sector into a Room with no label point (named
// by the sides of the lines around it), each linedef into a Wall of no thickness whose
// left and right rooms are its sidedefs' sectors, and a two-sided linedef into a Gap
// opening over the line's whole length and height; build_cells() finds the rest.
//
// Units: 1 map unit = 1/32 m (the player, 56 units tall, is 1.75 m), x east, y north.
// Formats: classic Doom (LINEDEFS of 14 bytes, THINGS of 10) and Hexen (16 and 20, the
// BEHAVIOR lump) are read; UDMF (TEXTMAP) is refused with a PlanError saying so.
// Real maps have errors: what can be repaired (a vertex or sidedef out of range, a
// two-sided flag with no back side, a line with only a back side, a zero-length line,
// a side naming a sector out of range, two lines on the same two points with a sector of
// no area between them) is, with a line in Plan::warnings naming the element,
// "freedoom2.wad:MAP07 (linedef 123): ...".
#pragma once

#include <string>
#include <vector>

#include "plans/plan.h"

namespace avenues {

constexpr double kDoomUnit = 1.0 / 32;       ///< [m] per map unit
constexpr double kDoomEyeHeight = 41.0 / 32; ///< [m] the player's view above the floor

/// The maps a WAD holds, in directory order ("MAP01", "E1M1", ...). Throws PlanError naming the file.
std::vector<std::string> doom_map_names(const std::string& wad_path);

/// Reads one map of a WAD as a Plan. Throws PlanError naming the file, lump and element for
/// what cannot be read; repairs what it can, with a line in Plan::warnings for each repair.
Plan read_doom_map(const std::string& wad_path, const std::string& map_name);

}  // namespace avenues
