// Avenues — writing a Mesh as OBJ and MTL (see obj_writer.h).
#include "plans/obj_writer.h"

#include <set>
#include <sstream>

#include "core/number_format.h"
#include "core/srgb.h"

namespace avenues {
namespace {

/// The materials' names as MTL statements can hold them: one line, no comment sign, no
/// blank at either end, none empty, no two alike.
std::vector<std::string> material_names(const Mesh& mesh) {
  std::vector<std::string> out;
  std::set<std::string> taken;
  for (size_t i = 0; i < mesh.materials.size(); ++i) {
    std::string name;
    for (char c : mesh.materials[i].name) name += (c == '#' || c == '\n' || c == '\r' || c == '\t') ? '_' : c;
    while (!name.empty() && name.front() == ' ') name.erase(name.begin());
    while (!name.empty() && name.back() == ' ') name.pop_back();
    if (name.empty()) name = "material " + std::to_string(i + 1);
    const std::string base = name;
    for (int k = 2; !taken.insert(name).second; ++k) name = base + " (" + std::to_string(k) + ")";
    out.push_back(name);
  }
  return out;
}

}  // namespace

std::string obj_of_mesh(const Mesh& mesh, const std::string& mtl_file) {
  std::ostringstream out;
  out << "# " << mesh.path << ", as Avenues holds it: z up, metres\n";
  const bool materials = !mesh.materials.empty() && mesh.material_of.size() == mesh.triangles.size();
  if (materials) out << "mtllib " << mtl_file << "\n";
  for (const Vec3& v : mesh.vertices)
    out << "v " << format_exact(v.x) << " " << format_exact(v.y) << " " << format_exact(v.z) << "\n";
  const std::vector<std::string> names = material_names(mesh);
  MaterialId current = -2;  // none said yet
  auto use = [&](MaterialId m) {
    if (!materials || m == current) return;
    // A triangle of no material: one the reader leaves to the default ("default" before
    // any usemtl; after one, a name no library defines).
    out << "usemtl " << (m >= 0 && size_t(m) < names.size() ? names[size_t(m)] : std::string("none")) << "\n";
    current = m;
  };
  auto face = [&](const std::vector<int>& corners) {
    out << "f";
    for (int c : corners) out << " " << c + 1;
    out << "\n";
  };
  // Each polygon's triangles, in order, as mesh_of_polygons made them: a fan from an apex.
  const size_t n = mesh.triangles.size();
  for (size_t t = 0; t < n;) {
    size_t end = t + 1;
    const int polygon = t < mesh.polygon_of.size() ? mesh.polygon_of[t] : -1;
    while (end < n && polygon >= 0 && end < mesh.polygon_of.size() && mesh.polygon_of[end] == polygon) ++end;
    const MaterialId m = materials ? mesh.material_of[t] : -1;
    bool fan = true;
    std::vector<int> corners{mesh.triangles[t][0], mesh.triangles[t][1], mesh.triangles[t][2]};
    for (size_t k = t + 1; k < end && fan; ++k) {
      const auto& tr = mesh.triangles[k];
      fan = tr[0] == corners[0] && tr[1] == corners.back() && (!materials || mesh.material_of[k] == m);
      corners.push_back(tr[2]);
    }
    if (fan) {
      use(m);
      face(corners);
    } else {
      for (size_t k = t; k < end; ++k) {
        use(materials ? mesh.material_of[k] : -1);
        face({mesh.triangles[k][0], mesh.triangles[k][1], mesh.triangles[k][2]});
      }
    }
    t = end;
  }
  return out.str();
}

std::string mtl_of_mesh(const Mesh& mesh) {
  if (mesh.materials.empty()) return "";
  std::ostringstream out;
  out << "# the materials of " << mesh.path << ": Kd sRGB-encoded\n";
  const std::vector<std::string> names = material_names(mesh);
  for (size_t i = 0; i < mesh.materials.size(); ++i) {
    const auto& c = mesh.materials[i].colour;
    out << "newmtl " << names[i] << "\nKd " << format_exact(srgb_from_linear(c[0])) << " "
        << format_exact(srgb_from_linear(c[1])) << " " << format_exact(srgb_from_linear(c[2])) << "\n";
  }
  return out.str();
}

}  // namespace avenues
