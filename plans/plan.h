// Avenues — a building plan, as a person wrote it.
//
// The Plan is the parsed, unit-converted, validated input: everything in metres,
// everything indexed (storeys, materials, rooms by position in their arrays), each
// element remembering where in the source it came from so that any later stage can
// name the line a problem stems from. It knows nothing of cells; cells/ builds the
// cell complex from it (data flows plans -> cells -> visibility -> render -> app).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry.h"

namespace avenues {

struct Mesh;  // plans/mesh.h

/// Where an element came from: "house.toml:12:3 (wall 'north')".
struct SourceLoc {
  std::string file;
  int line = 0;    ///< 1-based; 0 when unknown (generated plans)
  int column = 0;  ///< 1-based; 0 when unknown
  std::string element;  ///< e.g. "wall 'north'", "room 'kitchen'"
  std::string str() const;
};

/// A plan mistake: reported with its location, exit status 2 in the CLI.
class PlanError : public std::runtime_error {
 public:
  PlanError(const SourceLoc& where, const std::string& what)
      : std::runtime_error(where.str() + ": " + what), where_(where) {}
  const SourceLoc& where() const { return where_; }

 private:
  SourceLoc where_;
};

using MaterialId = int;  ///< index into Plan::materials; -1 = default
using StoreyId = int;    ///< index into Plan::storeys

struct Material {
  std::string name;
  double reflectance = 0.7;                 ///< R in Bouknight's I = R·RANGE·cos φ + BACK, [0,1]
  std::array<double, 3> colour{0.8, 0.8, 0.8};  ///< linear RGB, each [0,1]
  SourceLoc where;
};

struct Storey {
  std::string name;
  double elevation = 0;  ///< [m] top of this storey's floor
  double height = 2.5;   ///< [m] floor to ceiling, > 0
  double slab = 0.3;     ///< [m] thickness of the slab above the ceiling (floor of the next storey, or roof), >= 0
  SourceLoc where;
};

enum class OpeningKind { Door, Window, Hatch, Gap };
const char* to_string(OpeningKind k);

/// A hole through a wall, from `sill` to `head` above the storey's floor.
struct Opening {
  std::string name;
  OpeningKind kind = OpeningKind::Door;
  double at = 0;     ///< [m] distance along the wall's centre line from its first point to the opening's near edge
  double width = 0;  ///< [m] > 0, along the wall
  double sill = 0;   ///< [m] above the storey floor, >= 0
  double head = 2.1; ///< [m] above the storey floor, > sill, <= storey height
  SourceLoc where;
};

/// A wall: a centre-line polyline with thickness, standing on one storey's floor.
/// Arcs are tessellated into straight pieces (Plan::arc_tolerance) by the reader, so
/// `centre` holds straight segments only; `arc_segments` marks which came from arcs.
struct Wall {
  std::string name;
  StoreyId storey = 0;
  double thickness = 0.2;       ///< [m] >= 0; 0 is Jones's wall of no thickness
  double height = -1;           ///< [m] above floor; < 0 means "up to the ceiling"
  /// [m] >= 0 for a sloped top (a gable wall): the top rises or falls linearly along the
  /// centre line, from `height` at centre.front() to this at centre.back(); where it
  /// passes the storey's ceiling the wall stands up to the ceiling. < 0: level at
  /// `height`. Needs `height`, a thickness and no `footprint`.
  double height_at_end = -1;
  /// Where a sloped top bends between its ends (a gable wall's ridge, under a roof of
  /// several pitches): {distance along the centre line from centre.front() [m], strictly
  /// increasing inside (0, its length); the top's height there above the floor [m], >= 0}.
  /// The top runs straight between `height`, these and `height_at_end`. Needs
  /// `height_at_end`.
  std::vector<Vec2> top_bends;
  std::vector<Vec2> centre;     ///< [m] straight centre line after tessellation, >= 2 points
  std::vector<bool> from_arc;   ///< per segment (centre.size()-1): tessellated from an arc
  std::vector<Opening> openings;
  MaterialId material = -1;        ///< both sides; the left side only when right_material is set
  MaterialId right_material = -1;  ///< the right side, seen walking from centre.front() to back(); -1: `material`
  /// For a wall of no thickness: the rooms (indices into Plan::rooms) on its left and
  /// right, seen walking from centre.front() to centre.back(); -1 when not said. An
  /// imported map names its rooms this way (a Doom linedef's sides) instead of by label
  /// points: an enclosed space with no label takes the room its bounding walls vote for.
  int left_room = -1, right_room = -1;
  /// When not empty: the wall's own footprint [m], a convex polygon, counter-clockwise,
  /// standing instead of the quad of `centre` (then one segment) and `thickness`: a piece
  /// of a curved or L-shaped wall of a BIM model. `centre` and `thickness` are then its
  /// long axis and width; openings are measured along that axis and cut across it.
  std::vector<Vec2> footprint;
  SourceLoc where;

  /// [m] the centre line's length.
  double length() const;
  /// Whether the top slopes somewhere (height_at_end set, and some piece of the top rises).
  bool sloped() const;
  /// [m] the top's height above the floor at distance `along` from centre.front(): straight
  /// between `height`, `top_bends` and `height_at_end` (`height` when level).
  double top_at(double along) const;
};

/// A hole in a storey's floor slab (a stairwell): joins this storey to the one below.
struct FloorOpening {
  std::string name;
  StoreyId storey = 0;           ///< the storey whose floor has the hole (>= 1)
  std::vector<Vec2> outline;     ///< [m] simple polygon, counter-clockwise
  SourceLoc where;
};

struct Room {
  std::string name;
  StoreyId storey = 0;
  std::optional<Vec2> label;     ///< [m] a point inside the room; none: named by its walls' sides
  /// The room's own floor and ceiling, above the storey's floor [m]: a Doom sector's
  /// heights, a raised platform. 0 and < 0 ("the storey's ceiling") for an ordinary room.
  double floor_at = 0, ceiling_at = -1;
  bool sky = false;              ///< open to the sky: free up to the top of the far box (Doom's F_SKY1)
  MaterialId floor = -1, ceiling = -1, walls = -1;
  SourceLoc where;
};

/// How a mesh file's coordinates become Avenues' z-up metres, for formats that do not say
/// (OBJ, PLY, STL, OFF): the file's up axis and its length unit. Unset: z up, metres. A
/// format that declares its own (glTF, COLLADA, FBX, 3DS, IFC) is read as it declares.
struct MeshAxes {
  std::optional<char> up;              ///< 'x', 'y' or 'z': the file's up axis (right-handed)
  std::optional<double> metres_per_unit;  ///< [m] > 0: one file unit in metres
};

/// A mesh placed in a room; carried along for the renderer, it does not change cells.
struct Object {
  std::string name;
  std::string mesh;              ///< path, resolved against the plan's directory
  StoreyId storey = 0;
  Vec3 position;                 ///< [m] storey floor is z = 0 for the object
  Vec3 rotation_deg;             ///< [deg] about x, y, z, applied in that order
  Vec3 scale{1, 1, 1};
  MeshAxes axes;                 ///< the mesh file's up axis and unit (keys 'up', 'unit')
  /// With no mesh: the object is a box this size [m] (x by y, z high), its base centred
  /// on `position` (furniture whose model is not at hand). Scale and rotation apply.
  Vec3 box{0, 0, 0};
  /// A mesh that came with the plan rather than from a file of its own (a model inside a
  /// Sweet Home 3D home), in the object's axes like a file's; `mesh` then only names it.
  std::shared_ptr<const Mesh> model;
  MaterialId material = -1;
  SourceLoc where;
  /// -1 for every object of a plan: it is drawn in the cell holding its centroid. A large
  /// soup's detail (cells/soup_detail.h), its model already cut to one cell, names that
  /// cell here (the only object a plan never holds).
  int32_t cell = -1;
};

/// A point light shines from its position and casts shadows; an ambient light (Bouknight's
/// BACK) lights every surface evenly from nowhere in particular.
enum class LightKind : uint8_t { Point, Ambient };

struct Light {
  std::string name;
  LightKind kind = LightKind::Point;
  Vec3 position;                 ///< [m] absolute (Point only)
  double intensity = 1;          ///< relative, > 0 (Ambient: the share of full light, <= 1)
  std::array<double, 3> colour{1, 1, 1};
  SourceLoc where;
};

struct Viewpoint {
  Vec3 eye;    ///< [m]
  Vec3 look;   ///< [m] centre of interest
  double fov_deg = 60;
};

/// [deg] A model file's vertical angle of view `vertical_rad` (a VRML Viewpoint's
/// fieldOfView, an Irrlicht camera's Fovy) as the horizontal angle of a 16:9 picture, within
/// 40–120°: Viewpoint::fov_deg of the file's own first view.
double fov_deg_of_vertical(double vertical_rad);

struct Plan {
  std::string name;
  std::string source;                ///< file it was read from ("" if generated)
  double arc_tolerance = 0.01;       ///< [m] max sagitta of an arc's straight pieces
  double far_margin = 30;            ///< [m] from the building to the far opaque box, > 0
  MaterialId ground = -1, sky = -1, roof = -1;
  std::vector<Material> materials;
  std::vector<Storey> storeys;       ///< sorted by elevation, contiguous (elevation = below's elevation + height + slab)
  std::vector<Wall> walls;
  std::vector<FloorOpening> floor_openings;
  std::vector<Room> rooms;
  std::vector<Object> objects;
  std::vector<Light> lights;
  std::optional<Viewpoint> view;     ///< the plan's default viewpoint, if it names one
  /// Everything outside the rooms is solid (a Doom map's void): no outside cells, and
  /// the sky only above rooms open to it. Enclosed spaces no room claims are solid too.
  bool outside_solid = false;
  /// Enclosed spaces no room claims are solid, while the outside stays free: a 2D
  /// drawing's wall faces, bounded by walls of no thickness (TOML `unnamed_spaces_solid`).
  /// Implied by outside_solid.
  bool unnamed_spaces_solid = false;
  /// An imported plan (Sweet Home 3D): a room label in a wall or outside the walls is a
  /// warning and the room is dropped; two labels in one space share it (names joined).
  bool lenient = false;
  /// What an importer noticed and repaired or dropped (carried into the cell complex).
  std::vector<std::string> warnings;
};

/// Reads a plan file (TOML). Throws PlanError naming file, line and element.
Plan read_plan(const std::string& path);
/// Same, from text (for tests and fuzzing); `name` stands for the file in messages.
Plan parse_plan(const std::string& text, const std::string& name);
/// Whether `text` is TOML at all (any document, not only a plan): what tells a plan given
/// under a name that says nothing from other text.
bool parses_as_toml(const std::string& text);

/// Finds a pair of segments of the polyline `pts` (closed: last point joins the first)
/// that meet although they should not: non-neighbours that touch or cross, or
/// neighbours that double back over each other. Returns the pair (i < j), or {-1,-1}.
/// A wall's centre line must have none (the reader's rule, which importers that chain
/// walls keep too).
std::pair<int, int> find_self_crossing(const std::vector<Vec2>& pts, bool closed);

/// The plan moved by `by` in plan (every coordinate the decomposition sees: walls, floor
/// openings, room labels, objects, lights, the viewpoint), its name marked "(far from the
/// origin)": the far copies of the accuracy study and the hard cases.
Plan moved(Plan p, Vec2 by);

}  // namespace avenues
