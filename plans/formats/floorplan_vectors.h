// Avenues — vector floor-plan annotations (Raster-to-Vector's text format) as a Plan.
//
// Liu, Wu, Kohli and Furukawa's Raster-to-Vector (ICCV 2017) annotated 870 scanned
// apartment plans as text, one element a line, tab separated, in image pixels (x right,
// y down):
//
//   x1  y1  x2  y2  category  a  b
//
// where category is `wall` (a wall's centre line), `door` (a door: a segment lying on a
// wall), a room type (`bedroom`, `living_room`, `kitchen`, `bathroom`, `restroom`,
// `washing_room`, `closet`, `corridor`, `balcony`, `PS` — the label's box; its centre
// names the room around it) or a fixture (`bathtub`, `toilet`, `washing_basin`,
// `cooking_counter`, `special`, `stairs`: its box; `entrance` marks the way in and is
// not a thing). The two trailing numbers (a line's type and orientation) are not needed.
//
// The Plan: x = x1·scale, y = −y1·scale (north up, not mirrored); each wall line a
// straight wall of `wall_thickness`, lengthened by half of it where its end meets
// another wall (so corners close); each door the opening of the wall it lies on, kept
// clear of walls that cross that wall; each room label a room named from its category
// ("living room", numbered when repeated: "closet 2"); each fixture a box object. One
// storey of `storey_height`. The plan is lenient: a label in a wall or outside every
// room, a door on no wall, an unknown category are warnings naming the line.
#pragma once

#include <string>

#include "plans/plan.h"

namespace avenues {

struct FloorplanVectorOptions {
  /// [m per pixel] > 0. The dataset's plans are apartments some 200–300 pixels across, so
  /// 0.04 m (a 28-pixel entrance door is 1.1 m, a bedroom 3–4 m) is the default; set it
  /// from one dimension you know.
  double metres_per_pixel = 0.04;
  double storey_height = 2.7;   ///< [m] > 0
  double wall_thickness = 0.15; ///< [m] > 0; the annotations give centre lines only
};

/// True when `text` reads as annotations: its first non-blank line has four numbers and
/// a word. For telling the format by content.
bool looks_like_floorplan_vectors(const std::string& text);

/// Reads an annotation file. Throws PlanError naming the file and line for a line that
/// is not `x1 y1 x2 y2 category ...`, or a file with no wall.
Plan read_floorplan_vectors(const std::string& path, const FloorplanVectorOptions& options = {});
/// Same, from text; `name` stands for the file in messages.
Plan parse_floorplan_vectors(const std::string& text, const std::string& name,
                             const FloorplanVectorOptions& options = {});

}  // namespace avenues
