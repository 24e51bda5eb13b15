// Avenues — meshes to draw and what they are made of: a plan's objects placed in their
// cells, or meshes alone (the papers' scenes).
#pragma once

#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/mesh.h"
#include "plans/mesh_detail.h"

namespace avenues {

/// What a mesh is made of: one material, or one per input polygon (Bouknight's cottage
/// gives the undersides of its roof "a smaller index of reflectivity").
struct MeshPaint {
  std::vector<Material> materials;    ///< empty: the default material (plans/plan.h)
  std::vector<int> polygon_material;  ///< per input polygon (Mesh::polygon_of): index into materials; empty: the first
  const Material& of_polygon(int polygon) const;
};

/// A mesh's own materials as its paint, polygon by polygon (Mesh::material_of through
/// Mesh::polygon_of; a polygon of none takes the default material); an empty paint (the
/// default material) when the mesh has no materials of its own.
MeshPaint paint_of_mesh(const Mesh& mesh);

/// A mesh's triangles in runs of whole polygons (about 16 triangles each, in their order)
/// and each run's box, so that a view passes over a run that cannot show (outside the
/// avenue's region, under every sample, behind what is drawn) without looking at its
/// polygons (ScreenSceneBuilder::add_mesh). A soup's detail in one cell is thousands of
/// polygons, a steel member's in a row.
struct PolygonRuns {
  std::vector<uint32_t> first;  ///< per run: its first triangle; a run ends where the next begins
  std::vector<Box3> boxes;      ///< per run: of its triangles' vertices
};
/// The runs of m's triangles: a run ends at the first polygon's end after 16 triangles.
PolygonRuns polygon_runs(const Mesh& m);

/// A cell an object meets, and whether the object lies wholly inside it.
struct ObjectCell {
  CellId cell = kNoCell;
  bool whole = false;  ///< every vertex inside the cell (within kOnCellFace): nothing to cut
};

/// [m] how far outside a cell's face plane a vertex may lie and still be in the cell: an
/// object standing on a floor, or cut to a cell's face, belongs to that cell.
inline constexpr double kOnCellFace = 1e-9;

/// The cells an object placed as `placed` meets, ascending: those whose box meets the
/// mesh's box `box` and none of whose face planes has every vertex beyond it. An object cut
/// to a cell already (pinned_cell) meets that cell only, whole. One rule for the half-tone
/// (PlacedObject::cells) and the line drawing's furniture (furniture.h).
std::vector<ObjectCell> cells_met(const CellComplex& complex, const Object& o, const Mesh& placed, const Box3& box);

/// A plan object loaded, placed, and assigned to the cells it meets. Jones's cells are the
/// space between walls, so an object need not lie in one: a rug reaches under a low wall,
/// a window's frame stands out of its opening into both rooms. It is drawn in every cell
/// it meets, cut in 3D to that cell (scene_view.cpp), so that within an avenue it hides
/// and is hidden as its cell's own contents are.
struct PlacedObject {
  std::string name;
  Mesh mesh;               ///< world coordinates [m]
  /// Its home: the cell holding its centroid (or pinned_cell), else the first it meets;
  /// kNoCell: it meets no cell (inside a solid, outside the far box), never drawn. Lights
  /// reach an object, and decide its shadows, by this cell.
  CellId cell = kNoCell;
  std::vector<ObjectCell> cells;  ///< every cell it meets (cells_met), ascending; empty when cell is kNoCell
  MeshPaint paint;
  Box3 bounds;             ///< of the placed mesh's vertices
  /// Coarser versions, placed like `mesh` (tolerances in metres, ascending), when
  /// place_objects was asked for them: a half-tone draws the coarsest whose tolerance
  /// projects under SceneOptions::detail_samples (scene_view.cpp). Triangles keep their
  /// polygon numbers, so `paint` serves them too.
  std::vector<MeshLevel> coarser;
  /// polygon_runs of `mesh`, and of each coarser version (set_coarser keeps them together).
  PolygonRuns runs;
  std::vector<PolygonRuns> coarser_runs;
};

/// Gives `o` its coarser versions, each with its polygon runs.
void set_coarser(PlacedObject& o, std::vector<MeshLevel> levels);

/// The tolerances of an object's coarser versions, as fractions of its model's bounding
/// box diagonal: 1/1000, 1/250, 1/60 (a 1 m chair: 1, 4 and 17 mm).
inline constexpr double kDetailFractions[] = {1.0 / 1000, 1.0 / 250, 1.0 / 60};

/// The distinct models of a complex's objects as read, by mesh_key (a model the plan
/// carries, Object::model, is shared, not copied).
using ObjectModels = std::map<std::string, std::shared_ptr<const Mesh>>;

/// The model of `o` among `models`, read (load_object_mesh) the first time its mesh_key is
/// asked for; a model the plan carries is shared. What reading it let pass goes to
/// `warnings` when given.
const Mesh& model_of(const Object& o, ObjectModels& models, std::vector<std::string>* warnings = nullptr);

/// The elevation of the storey an object stands on (0 without one): its model is placed
/// from there.
double floor_of(const CellComplex& complex, const Object& o);

/// The cell an object was cut to already (Object::cell, a soup's detail), or kNoCell: such
/// an object is drawn in that cell only, wherever its vertices lie.
CellId pinned_cell(const CellComplex& complex, const Object& o);

/// Loads every object of the complex (plans/mesh.h, each file read once), places it on
/// its storey, and finds the cells it meets (cells_met) and its home among them, the cell
/// holding the centroid of its vertices (an object cut to a cell already keeps that one,
/// pinned_cell). Its paint is its
/// own material (Object::material) where it has one, else its mesh's (paint_of_mesh). Throws
/// std::runtime_error naming the mesh file when one cannot be read; what reading a mesh let
/// pass (an OBJ's missing MTL library or image, load_object_mesh) goes to `warnings`
/// when given, once per mesh file.
/// With `coarser`, every object also gets its coarser versions (coarser_versions), for
/// films, whose many frames repay the second or two it takes in a furnished home.
/// With `models_read`, the models it read are kept there (for coarser_versions later,
/// without reading them again).
std::vector<PlacedObject> place_objects(const CellComplex& complex, std::vector<std::string>* warnings = nullptr,
                                        bool coarser = false, ObjectModels* models_read = nullptr);

/// Each cell's placed objects, in their order: a picture looks up the objects of each cell
/// it sees. Made once for many pictures of the same objects (a walk's FrameStorage): a
/// soup's detail is thousands of objects, and going through them all costs a frame that
/// sees three polygons a tenth of a millisecond.
struct ObjectsByCell {
  /// Set on an entry of `index` whose object reaches beyond the cell (ObjectCell::whole
  /// false): drawn in that cell, it is cut to the cell.
  static constexpr uint32_t kCut = 1u << 31;
  std::vector<uint32_t> from;   ///< per cell c (and one more): cell c's objects are index[from[c] .. from[c + 1])
  std::vector<uint32_t> index;  ///< into the objects, with kCut
  /// Cell c's objects, each with kCut where it must be cut to the cell (none for a cell out of range).
  std::span<const uint32_t> of(CellId c) const {
    if (c < 0 || size_t(c) + 1 >= from.size()) return {};
    return {index.data() + from[size_t(c)], index.data() + from[size_t(c) + 1]};
  }
};
/// The objects of each of `cells` cells (every cell each meets, PlacedObject::cells), by a
/// counting sort (cells out of range left out).
ObjectsByCell objects_by_cell(size_t cells, const std::vector<PlacedObject>& objects);

/// Each object's coarser versions (PlacedObject::coarser), in the order of complex.objects:
/// every distinct model of 500 triangles or more made coarser once (plans/mesh_detail.h,
/// tolerances kDetailFractions of its box's diagonal, the models spread over TBB's threads),
/// then placed as each object is. Safe to run on a thread of its own while the objects
/// placed without them are drawn (the walkthrough hands them over when they are ready).
/// `models`: the objects' models as place_objects read them (ObjectModels), so no file is
/// read again.
std::vector<std::vector<MeshLevel>> coarser_versions(const CellComplex& complex, const ObjectModels& models);

}  // namespace avenues
