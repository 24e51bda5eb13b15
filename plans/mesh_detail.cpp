// Avenues — coarser versions of a mesh with OpenMesh's decimater (see mesh_detail.h).
#include "plans/mesh_detail.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModHausdorffT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>
#include <tbb/parallel_for.h>

#include "plans/quiet_openmesh.h"

namespace avenues {

namespace {

/// Double precision: a millimetre's tolerance must not drown in single-precision rounding.
struct DoubleTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

}  // namespace

std::vector<MeshLevel> coarser_levels(const Mesh& m, const std::vector<double>& tolerances, size_t min_triangles) {
  std::vector<MeshLevel> levels;
  if (m.triangles.size() < min_triangles || tolerances.empty()) return levels;
  TriMesh tm;
  std::vector<TriMesh::VertexHandle> vh;
  vh.reserve(m.vertices.size());
  for (const Vec3& v : m.vertices) vh.push_back(tm.add_vertex({v.x, v.y, v.z}));
  OpenMesh::FPropHandleT<int> source;  // the input triangle a face was
  tm.add_property(source);
  std::vector<size_t> kept;  // not manifold: kept as they are
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const TriMesh::FaceHandle f = tm.add_face(vh[size_t(tri[0])], vh[size_t(tri[1])], vh[size_t(tri[2])]);
    if (f.is_valid()) tm.property(source, f) = int(t);
    else kept.push_back(t);
  }
  tm.update_face_normals();
  OpenMesh::Decimater::DecimaterT<TriMesh> dec(tm);
  OpenMesh::Decimater::ModQuadricT<TriMesh>::Handle quadric;
  OpenMesh::Decimater::ModHausdorffT<TriMesh>::Handle hausdorff;
  OpenMesh::Decimater::ModNormalFlippingT<TriMesh>::Handle flipping;
  dec.add(quadric);
  dec.add(hausdorff);
  dec.add(flipping);
  dec.module(quadric).unset_max_err();
  if (!dec.initialize()) return levels;
  size_t before = m.triangles.size();
  for (double tolerance : tolerances) {
    dec.module(hausdorff).set_tolerance(tolerance);
    dec.decimate();
    // A snapshot of the faces left (deleted ones are skipped), vertices renumbered.
    Mesh out;
    out.path = m.path;
    out.materials = m.materials;
    out.polygon_light = m.polygon_light;  // polygons keep their numbers
    out.closed = m.closed;  // collapses keep a closed manifold closed, and flips are refused
    out.boundary_edges = m.boundary_edges;
    std::vector<int> index(tm.n_vertices(), -1);
    auto add = [&](std::array<int, 3> tri, size_t from) {
      out.triangles.push_back(tri);
      if (from < m.polygon_of.size()) out.polygon_of.push_back(m.polygon_of[from]);
      if (from < m.material_of.size()) out.material_of.push_back(m.material_of[from]);
    };
    for (const auto& f : tm.faces()) {
      std::array<int, 3> tri{};
      int k = 0;
      for (const auto& v : tm.fv_range(f)) {
        int& i = index[size_t(v.idx())];
        if (i < 0) {
          const auto& p = tm.point(v);
          i = int(out.vertices.size());
          out.vertices.push_back({p[0], p[1], p[2]});
        }
        tri[size_t(k++)] = i;
      }
      add(tri, size_t(tm.property(source, f)));
    }
    for (size_t t : kept) {  // as they were, with vertices of their own
      std::array<int, 3> tri{};
      for (int k = 0; k < 3; ++k) {
        tri[size_t(k)] = int(out.vertices.size());
        out.vertices.push_back(m.vertices[size_t(m.triangles[t][size_t(k)])]);
      }
      add(tri, t);
    }
    if (4 * out.triangles.size() > 3 * before) continue;  // not a quarter fewer: not worth keeping
    if (out.polygon_of.size() != out.triangles.size()) out.polygon_of.clear();
    if (out.material_of.size() != out.triangles.size()) out.material_of.clear();
    smooth_corner_normals(out);
    before = out.triangles.size();
    levels.push_back({std::move(out), tolerance});
  }
  return levels;
}

std::vector<std::vector<MeshLevel>> coarser_levels_of(const std::vector<const Mesh*>& meshes,
                                                      const std::vector<double>& fractions, size_t min_triangles) {
  const QuietOpenMesh quiet;  // refused faces (kept as they are) are no news to a user
  std::vector<std::vector<MeshLevel>> out(meshes.size());
  tbb::parallel_for(size_t(0), meshes.size(), [&](size_t i) {
    const Mesh& m = *meshes[i];
    if (m.triangles.size() < min_triangles) return;
    Box3 b;
    for (Vec3 v : m.vertices) b.add(v);
    std::vector<double> tolerances;
    for (double f : fractions) tolerances.push_back(f * length(b.hi - b.lo));
    out[i] = coarser_levels(m, tolerances, min_triangles);
  });
  return out;
}

}  // namespace avenues
