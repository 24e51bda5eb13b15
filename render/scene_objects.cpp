// Avenues — a plan's objects placed in their cells (see scene_objects.h).
#include "render/scene_objects.h"

#include <algorithm>
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

std::vector<PlacedObject> place_objects(const CellComplex& complex, std::vector<std::string>* warnings) {
  std::vector<PlacedObject> out;
  std::map<std::string, Mesh> loaded;
  CellId hint = kNoCell;
  for (const Object& o : complex.objects) {
    auto it = loaded.find(mesh_key(o));
    if (it == loaded.end()) it = loaded.emplace(mesh_key(o), load_object_mesh(o, warnings)).first;
    const double floor_z =
        o.storey >= 0 && size_t(o.storey) < complex.storeys.size() ? complex.storeys[size_t(o.storey)].elevation : 0;
    PlacedObject p;
    p.name = o.name;
    p.mesh = place(it->second, o, floor_z);
    Vec3 centroid{0, 0, 0};
    for (Vec3 v : p.mesh.vertices) {
      centroid = centroid + v;
      p.bounds.add(v);
    }
    centroid = (1.0 / double(p.mesh.vertices.size())) * centroid;
    const Location at = complex.locate(centroid, hint);
    if (at.what == Location::What::Cell) p.cell = hint = at.cell;
    if (o.material >= 0 && size_t(o.material) < complex.materials.size())
      p.paint.materials.push_back(complex.materials[size_t(o.material)]);
    else p.paint = paint_of_mesh(p.mesh);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace avenues
