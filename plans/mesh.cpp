// Avenues — reading meshes with OpenMesh (see mesh.h).
#include "plans/mesh.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>

namespace avenues {

namespace {
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;
constexpr double kDeg = 3.14159265358979323846 / 180;

Vec3 rotate(Vec3 p, Vec3 deg) {
  const double ax = deg.x * kDeg, ay = deg.y * kDeg, az = deg.z * kDeg;
  Vec3 q{p.x, std::cos(ax) * p.y - std::sin(ax) * p.z, std::sin(ax) * p.y + std::cos(ax) * p.z};
  q = {std::cos(ay) * q.x + std::sin(ay) * q.z, q.y, -std::sin(ay) * q.x + std::cos(ay) * q.z};
  return {std::cos(az) * q.x - std::sin(az) * q.y, std::sin(az) * q.x + std::cos(az) * q.y, q.z};
}
}  // namespace

Mesh load_mesh(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error("cannot read mesh " + path + ": no such file");
  PolyMesh pm;
  OpenMesh::IO::Options opt;
  if (!OpenMesh::IO::read_mesh(pm, path, opt))
    throw std::runtime_error("cannot read mesh " + path + ": not a mesh OpenMesh can read (OBJ, OFF, PLY, STL)");
  if (pm.n_faces() == 0) throw std::runtime_error("mesh " + path + " has no faces");
  Mesh m;
  m.path = path;
  for (auto v : pm.vertices()) {
    auto p = pm.point(v);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw std::runtime_error("mesh " + path + " has a vertex that is not a finite number");
    m.vertices.push_back({p[0], p[1], p[2]});
  }
  // Triangulate each polygon as a fan (OpenMesh keeps polygons; convex ones are the rule).
  int poly = 0;
  std::vector<Vec3> normal_sum(m.vertices.size(), Vec3{0, 0, 0});
  for (auto f : pm.faces()) {
    std::vector<int> idx;
    for (auto v : pm.fv_range(f)) idx.push_back(v.idx());
    if (idx.size() < 3) continue;
    Vec3 n{0, 0, 0};  // Newell's normal, area-weighted
    for (size_t k = 0; k < idx.size(); ++k) n = n + cross(m.vertices[size_t(idx[k])], m.vertices[size_t(idx[(k + 1) % idx.size()])]);
    for (int i : idx) normal_sum[size_t(i)] = normal_sum[size_t(i)] + n;
    for (size_t k = 1; k + 1 < idx.size(); ++k) {
      m.triangles.push_back({idx[0], idx[k], idx[k + 1]});
      m.polygon_of.push_back(poly);
    }
    ++poly;
  }
  for (Vec3 n : normal_sum) {
    double l = length(n);
    m.vertex_normals.push_back(l > 0 ? (1.0 / l) * n : Vec3{0, 0, 1});
  }
  // Closed: every polygon edge is shared by exactly two polygons, in opposite directions.
  std::map<std::pair<int, int>, int> edges;
  for (auto f : pm.faces()) {
    std::vector<int> idx;
    for (auto v : pm.fv_range(f)) idx.push_back(v.idx());
    for (size_t k = 0; k < idx.size(); ++k) {
      int a = idx[k], b = idx[(k + 1) % idx.size()];
      edges[{std::min(a, b), std::max(a, b)}]++;
    }
  }
  for (auto& [e, count] : edges) m.boundary_edges += count == 1;
  m.closed = m.boundary_edges == 0;
  return m;
}

Mesh box_mesh(Vec3 size) {
  Mesh m;
  m.path = mesh_key_of_box(size);
  const double x = size.x / 2, y = size.y / 2, z = size.z;
  m.vertices = {{-x, -y, 0}, {x, -y, 0}, {x, y, 0}, {-x, y, 0}, {-x, -y, z}, {x, -y, z}, {x, y, z}, {-x, y, z}};
  // Counter-clockwise seen from outside: bottom, top, then the four sides.
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (int q = 0; q < 6; ++q) {
    m.triangles.push_back({quads[q][0], quads[q][1], quads[q][2]});
    m.triangles.push_back({quads[q][0], quads[q][2], quads[q][3]});
    m.polygon_of.push_back(q);
    m.polygon_of.push_back(q);
  }
  for (Vec3 v : m.vertices) {
    Vec3 n{v.x / std::max(x, 1e-12), v.y / std::max(y, 1e-12), v.z > 0 ? 1.0 : -1.0};
    m.vertex_normals.push_back((1.0 / length(n)) * n);
  }
  m.closed = true;
  return m;
}

std::string mesh_key_of_box(Vec3 size) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "box %.6g x %.6g x %.6g", size.x, size.y, size.z);
  return buf;
}

std::string mesh_key(const Object& object) {
  return object.mesh.empty() ? mesh_key_of_box(object.box) : object.mesh;
}

Mesh load_object_mesh(const Object& object) {
  if (object.mesh.empty()) {
    if (!(object.box.x > 0 && object.box.y > 0 && object.box.z > 0))
      throw std::runtime_error(object.where.str() + ": object '" + object.name + "' has neither a mesh nor a box size");
    return box_mesh(object.box);
  }
  try {
    return load_mesh(object.mesh);
  } catch (const std::runtime_error& e) {
    const std::string where = object.where.str();
    if (where.empty()) throw;
    throw std::runtime_error(where + ": " + e.what());
  }
}

Mesh place(const Mesh& mesh, const Object& o, double floor_z) {
  Mesh m = mesh;
  const Vec3 at = o.position + Vec3{0, 0, floor_z};
  for (Vec3& v : m.vertices) v = rotate({v.x * o.scale.x, v.y * o.scale.y, v.z * o.scale.z}, o.rotation_deg) + at;
  for (Vec3& n : m.vertex_normals) {
    Vec3 r = rotate({n.x / o.scale.x, n.y / o.scale.y, n.z / o.scale.z}, o.rotation_deg);
    double l = length(r);
    n = l > 0 ? (1.0 / l) * r : n;
  }
  return m;
}

}  // namespace avenues
