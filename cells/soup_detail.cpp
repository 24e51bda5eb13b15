// Avenues — a large soup's detail (see soup_detail.h).
#include "cells/soup_detail.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <unordered_map>

#include "plans/mesh.h"

namespace avenues {
namespace {

double triangle_area(const SoupTriangle& t) { return 0.5 * length(cross(t.p[1] - t.p[0], t.p[2] - t.p[0])); }

struct PointHash {
  size_t operator()(const Vec3& v) const {
    const auto h = [](double d) { return std::hash<uint64_t>()(std::bit_cast<uint64_t>(d == 0 ? 0.0 : d)); };
    return h(v.x) ^ (h(v.y) * 0x9e3779b97f4a7c15ull) ^ (h(v.z) * 0xc2b2ae3d27d4eb4full);
  }
};
struct PointEqual {
  bool operator()(const Vec3& a, const Vec3& b) const { return a.x == b.x && a.y == b.y && a.z == b.z; }
};

/// One cell's detail as it is gathered: pieces welded by position, one polygon per input
/// polygon, lit from that polygon's centroid.
struct DetailMesh {
  Mesh mesh;
  std::unordered_map<Vec3, int, PointHash, PointEqual> vertex;
  std::unordered_map<int64_t, int> polygon;

  int vertex_of(Vec3 p) {
    auto [it, added] = vertex.try_emplace(p, int(mesh.vertices.size()));
    if (added) mesh.vertices.push_back(p);
    return it->second;
  }
  void add(const std::vector<Vec3>& piece, int64_t input_polygon, MaterialId material, Vec3 light) {
    const auto [it, added] = polygon.try_emplace(input_polygon, int(polygon.size()));
    if (added) mesh.polygon_light.push_back(light);
    const int poly = it->second;
    const int first = vertex_of(piece[0]);
    for (size_t k = 1; k + 1 < piece.size(); ++k) {
      const int b = vertex_of(piece[k]), c = vertex_of(piece[k + 1]);
      if (first == b || b == c || c == first) continue;
      mesh.triangles.push_back({first, b, c});
      mesh.polygon_of.push_back(poly);
      mesh.material_of.push_back(material);
    }
  }
};

}  // namespace

SoupSplit split_detail(const std::vector<SoupTriangle>& soup, const std::vector<int64_t>& polygon, size_t above,
                       size_t budget) {
  SoupSplit s;
  s.detail.assign(soup.size(), false);
  std::vector<double> area(soup.size());
  size_t with_area = 0;
  for (size_t i = 0; i < soup.size(); ++i) with_area += (area[i] = triangle_area(soup[i])) > 0;
  s.structural = with_area;
  if (with_area <= above) return s;
  // The polygons, largest first: their areas and their triangles with area.
  struct Polygon {
    int64_t id = 0;
    double area = 0;
    size_t triangles = 0;
  };
  std::unordered_map<int64_t, size_t> index;
  std::vector<Polygon> polygons;
  for (size_t i = 0; i < soup.size(); ++i) {
    auto [it, added] = index.try_emplace(polygon[i], polygons.size());
    if (added) polygons.push_back({polygon[i], 0, 0});
    Polygon& p = polygons[it->second];
    p.area += area[i];
    p.triangles += area[i] > 0;
  }
  std::vector<size_t> order(polygons.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return polygons[a].area != polygons[b].area ? polygons[a].area > polygons[b].area : polygons[a].id < polygons[b].id;
  });
  std::vector<bool> structural(polygons.size(), false);
  size_t taken = 0;
  for (size_t k : order) {
    if (taken + polygons[k].triangles > budget) break;
    taken += polygons[k].triangles;
    structural[k] = true;
    if (polygons[k].area > 0) s.smallest_structural = polygons[k].area;
  }
  s.structural = taken;
  for (size_t i = 0; i < soup.size(); ++i)
    if (!structural[index.at(polygon[i])]) {
      s.detail[i] = true;
      s.detail_triangles += area[i] > 0;
    }
  return s;
}

double add_detail_objects(CellComplex& out, const std::vector<SoupTriangle>& detail, const std::vector<int64_t>& polygon,
                          const std::string& source) {
  if (out.bands.empty()) out.index();
  const Box3& fb = out.far_box;
  const double scale = std::max({1.0, std::fabs(fb.lo.x), std::fabs(fb.hi.x), std::fabs(fb.lo.y), std::fabs(fb.hi.y),
                                 std::fabs(fb.lo.z), std::fabs(fb.hi.z)});
  const double tol = 1e-9 * scale;           // [m] rounding of the cells' planes
  const double min_area = tol * tol;         // [m²] a piece with less shows nothing
  std::vector<Box3> bounds(out.cells.size());
  for (size_t i = 0; i < out.cells.size(); ++i) bounds[i] = out.cells[i].bounds();
  // Each input polygon's centroid, where flat shading lights all its pieces from (Mesh::polygon_light).
  std::unordered_map<int64_t, std::pair<Vec3, double>> moments;
  for (size_t t = 0; t < detail.size(); ++t) {
    const SoupTriangle& tri = detail[t];
    const double a = triangle_area(tri);
    auto& [sum, area] = moments[polygon[t]];
    sum = sum + (a / 3) * (tri.p[0] + tri.p[1] + tri.p[2]);
    area += a;
  }
  std::vector<std::unique_ptr<DetailMesh>> of(out.cells.size());
  std::vector<CellId> candidates;
  std::vector<Vec3> piece;
  double covered = 0;
  for (size_t t = 0; t < detail.size(); ++t) {
    const SoupTriangle& tri = detail[t];
    if (!(triangle_area(tri) > 0)) continue;
    Box3 tb;
    for (Vec3 p : tri.p) tb.add(p);
    out.cells_near(tb.grown(tol), candidates);
    for (const CellId c : candidates) {
      if (!tb.meets(bounds[size_t(c)], tol)) continue;
      piece.assign(tri.p.begin(), tri.p.end());
      for (const Face& f : out.cells[size_t(c)].faces) {
        piece = cut_polygon(piece, [&](Vec3 p) { return -f.plane.eval(p); });
        if (piece.size() < 3) break;
      }
      if (piece.size() < 3) continue;
      const double a = polygon_area(piece);
      if (!(a > min_area)) continue;
      // A piece lying on a face of the cell lies on the face of the cell beyond it too:
      // the first of the cells holding it draws it.
      const bool on_face = std::any_of(out.cells[size_t(c)].faces.begin(), out.cells[size_t(c)].faces.end(), [&](const Face& f) {
        return std::all_of(piece.begin(), piece.end(), [&](Vec3 p) { return std::fabs(f.plane.eval(p)) <= tol; });
      });
      if (on_face) {
        Vec3 g{0, 0, 0};
        for (Vec3 p : piece) g = g + p;
        const std::vector<CellId> holding = out.cells_holding((1.0 / double(piece.size())) * g, tol);
        if (!holding.empty() && holding.front() != c) continue;
      }
      auto& m = of[size_t(c)];
      if (!m) m = std::make_unique<DetailMesh>();
      const auto& [sum, area] = moments.at(polygon[t]);
      m->add(piece, polygon[t], tri.material, (1 / area) * sum);
      covered += a;
    }
  }
  for (size_t c = 0; c < of.size(); ++c) {
    if (!of[c] || of[c]->mesh.triangles.empty()) continue;
    Mesh& m = of[c]->mesh;
    m.path = source + ": detail in cell " + std::to_string(c);
    m.materials = out.materials;
    // Every piece is seen from both sides: a soup's polygons are (soup_bsp.h).
    m.boundary_edges = boundary_edges(m.triangles);
    m.closed = false;
    smooth_corner_normals(m);
    Object o;
    o.name = "detail in cell " + std::to_string(c);
    o.cell = int32_t(c);
    o.model = std::make_shared<const Mesh>(std::move(m));
    out.objects.push_back(std::move(o));
  }
  return covered;
}

}  // namespace avenues
