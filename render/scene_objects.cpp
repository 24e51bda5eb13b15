// Avenues — a plan's objects placed in their cells (see scene_objects.h).
#include "render/scene_objects.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace avenues {

const Material& MeshPaint::of_polygon(int polygon) const {
  static const Material kDefault;
  if (materials.empty()) return kDefault;
  if (polygon >= 0 && size_t(polygon) < polygon_material.size()) {
    const int m = polygon_material[size_t(polygon)];
    if (m >= 0 && size_t(m) < materials.size()) return materials[size_t(m)];
  }
  return materials[0];
}

MeshPaint paint_of_mesh(const Mesh& mesh) {
  MeshPaint paint;
  if (mesh.material_of.empty() || mesh.materials.empty()) return paint;
  paint.materials = mesh.materials;
  // A polygon of no material of the mesh's own takes the default one, put last.
  const int none = int(paint.materials.size());
  int polygons = 0;
  for (int polygon : mesh.polygon_of) polygons = std::max(polygons, polygon + 1);
  paint.polygon_material.assign(size_t(polygons), none);
  bool uncoloured = false;
  for (size_t t = 0; t < mesh.triangles.size() && t < mesh.polygon_of.size(); ++t) {
    const MaterialId m = t < mesh.material_of.size() ? mesh.material_of[t] : -1;
    const bool own = m >= 0 && size_t(m) < mesh.materials.size();
    paint.polygon_material[size_t(mesh.polygon_of[t])] = own ? m : none;
    uncoloured |= !own;
  }
  if (uncoloured) paint.materials.emplace_back();
  return paint;
}

PolygonRuns polygon_runs(const Mesh& m) {
  constexpr size_t kRun = 16;
  PolygonRuns runs;
  const size_t n = std::min(m.triangles.size(), m.polygon_of.size());
  for (size_t t = 0; t < n; ++t) {
    const bool fresh = runs.first.empty() ||
                       (t - runs.first.back() >= kRun && m.polygon_of[t] != m.polygon_of[t - 1]);
    if (fresh) {
      runs.first.push_back(uint32_t(t));
      runs.boxes.emplace_back();
    }
    for (int v : m.triangles[t]) runs.boxes.back().add(m.vertices[size_t(v)]);
  }
  return runs;
}

void set_coarser(PlacedObject& o, std::vector<MeshLevel> levels) {
  o.coarser = std::move(levels);
  o.coarser_runs.clear();
  for (const MeshLevel& level : o.coarser) o.coarser_runs.push_back(polygon_runs(level.mesh));
}

double floor_of(const CellComplex& complex, const Object& o) {
  return o.storey >= 0 && size_t(o.storey) < complex.storeys.size() ? complex.storeys[size_t(o.storey)].elevation : 0;
}

namespace {

/// Each object's coarser versions from its model among `models` (by mesh_key), each
/// distinct model made coarser once, then placed as the object is.
std::vector<std::vector<MeshLevel>> placed_levels(const CellComplex& complex, const ObjectModels& models) {
  std::vector<const Mesh*> meshes;
  for (const auto& entry : models) meshes.push_back(entry.second.get());
  std::vector<std::vector<MeshLevel>> made =
      coarser_levels_of(meshes, std::vector<double>(std::begin(kDetailFractions), std::end(kDetailFractions)), 500);
  std::map<std::string, const std::vector<MeshLevel>*> of;
  size_t i = 0;
  for (const auto& entry : models) of[entry.first] = &made[i++];
  std::vector<std::vector<MeshLevel>> out;
  for (const Object& o : complex.objects) {
    out.emplace_back();
    // Rotation keeps lengths; the scale stretches them by at most its largest factor.
    const double stretch = std::max({std::fabs(o.scale.x), std::fabs(o.scale.y), std::fabs(o.scale.z)});
    const double floor_z = floor_of(complex, o);
    for (const MeshLevel& level : *of.at(mesh_key(o)))
      out.back().push_back({place(level.mesh, o, floor_z), level.tolerance * stretch});
  }
  return out;
}
}  // namespace

const Mesh& model_of(const Object& o, ObjectModels& models, std::vector<std::string>* warnings) {
  const std::string key = mesh_key(o);
  auto it = models.find(key);
  if (it == models.end())
    it = models.emplace(key, o.model ? o.model : std::make_shared<const Mesh>(load_object_mesh(o, warnings))).first;
  return *it->second;
}

CellId pinned_cell(const CellComplex& complex, const Object& o) {
  return o.cell >= 0 && size_t(o.cell) < complex.cells.size() ? o.cell : kNoCell;
}

std::vector<ObjectCell> cells_met(const CellComplex& complex, const Object& o, const Mesh& placed, const Box3& box) {
  if (const CellId pinned = pinned_cell(complex, o); pinned != kNoCell) return {{pinned, true}};
  std::vector<ObjectCell> out;
  if (placed.vertices.empty()) return out;
  std::vector<CellId> near;
  complex.cells_near(box, near);  // ascending
  const Vec3 corners[8] = {box.lo, {box.hi.x, box.lo.y, box.lo.z}, {box.lo.x, box.hi.y, box.lo.z},
                           {box.hi.x, box.hi.y, box.lo.z}, {box.lo.x, box.lo.y, box.hi.z},
                           {box.hi.x, box.lo.y, box.hi.z}, {box.lo.x, box.hi.y, box.hi.z}, box.hi};
  for (const CellId id : near) {
    const Cell& cell = complex.cells[size_t(id)];
    if (!cell.bounds().meets(box)) continue;
    // It misses the cell when some face plane has every vertex on or beyond it and one
    // beyond (an object standing on the floor above); one lying in the plane (a rug of no
    // height on the floor) meets it. The box's corners decide most planes: an affine
    // function is greatest at a corner.
    bool meets = true, whole = true;
    for (size_t f = 0; f < cell.faces.size() && meets; ++f) {
      const Plane& plane = cell.faces[f].plane;  // outward
      bool beyond = false;
      for (const Vec3& c : corners) beyond |= plane.eval(c) > kOnCellFace;
      if (!beyond) continue;
      bool none_inside = true, one_beyond = false;
      for (const Vec3& v : placed.vertices) {
        const double e = plane.eval(v);
        none_inside &= e >= -kOnCellFace;
        one_beyond |= e > kOnCellFace;
      }
      meets = !(none_inside && one_beyond);
      whole &= !one_beyond;
    }
    if (meets) out.push_back({id, whole});
  }
  return out;
}

ObjectsByCell objects_by_cell(size_t cells, const std::vector<PlacedObject>& objects) {
  ObjectsByCell by;
  by.from.assign(cells + 2, 0);
  auto counted = [cells](CellId c) { return c >= 0 && size_t(c) < cells; };  // kNoCell is -1
  for (const PlacedObject& o : objects)
    for (const ObjectCell& in : o.cells)
      if (counted(in.cell)) ++by.from[size_t(in.cell) + 2];
  for (size_t c = 2; c < by.from.size(); ++c) by.from[c] += by.from[c - 1];
  by.index.resize(by.from.back());
  for (size_t i = 0; i < objects.size(); ++i)
    for (const ObjectCell& in : objects[i].cells)
      if (counted(in.cell)) by.index[by.from[size_t(in.cell) + 1]++] = uint32_t(i) | (in.whole ? 0 : ObjectsByCell::kCut);
  by.from.pop_back();  // from[c] is now cell c's first, from[cells] the end
  return by;
}

std::vector<std::vector<MeshLevel>> coarser_versions(const CellComplex& complex, const ObjectModels& models) {
  return placed_levels(complex, models);
}

std::vector<PlacedObject> place_objects(const CellComplex& complex, std::vector<std::string>* warnings, bool coarser,
                                        ObjectModels* models_read) {
  std::vector<PlacedObject> out;
  ObjectModels loaded;
  CellId hint = kNoCell;
  for (const Object& o : complex.objects) {
    PlacedObject p;
    p.name = o.name;
    p.mesh = place(model_of(o, loaded, warnings), o, floor_of(complex, o));
    Vec3 centroid{0, 0, 0};
    for (Vec3 v : p.mesh.vertices) {
      centroid = centroid + v;
      p.bounds.add(v);
    }
    centroid = (1.0 / double(p.mesh.vertices.size())) * centroid;
    p.cells = cells_met(complex, o, p.mesh, p.bounds);
    p.cell = pinned_cell(complex, o);
    if (p.cell == kNoCell) {
      const Location at = complex.locate(centroid, hint);
      if (at.what == Location::What::Cell) p.cell = hint = at.cell;
      else if (!p.cells.empty()) p.cell = p.cells[0].cell;
    }
    if (o.material >= 0 && size_t(o.material) < complex.materials.size())
      p.paint.materials.push_back(complex.materials[size_t(o.material)]);
    else p.paint = paint_of_mesh(p.mesh);
    p.runs = polygon_runs(p.mesh);
    out.push_back(std::move(p));
  }
  if (coarser) {  // from the models just read, not read again
    std::vector<std::vector<MeshLevel>> levels = placed_levels(complex, loaded);
    for (size_t i = 0; i < out.size(); ++i) set_coarser(out[i], std::move(levels[i]));
  }
  if (models_read) *models_read = std::move(loaded);
  return out;
}

}  // namespace avenues
