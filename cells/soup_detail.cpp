// Avenues — a large soup's detail (see soup_detail.h).
#include "cells/soup_detail.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <set>
#include <unordered_map>

#include "cells/shared_planes.h"
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

/// A piece of a detail polygon cut to a cell, before it joins its cluster's mesh.
struct DetailPiece {
  std::vector<Vec3> corners;
  int64_t polygon = 0;  ///< the input polygon it is a piece of
  MaterialId material = -1;
  Vec3 light;           ///< where the whole input polygon is lit from
};

/// Triangles a cluster of one cell's detail holds at most (unless one input polygon alone
/// has more): a few of the renderer's runs of polygons (render/scene_objects.h), and under
/// the 500 a model needs for coarser versions. Clusters of 1,024 kept coarser versions for
/// the larger ones, and cost three times the CPU to open with no faster frames; clusters
/// of 96 cost more per object than they culled (docs/PERFORMANCE.md).
constexpr size_t kClusterTriangles = 256;

/// One cell's pieces in compact clusters, each input polygon's pieces in one: the
/// polygons, by the centre of their pieces' corners, halved at the median across the
/// longest side of their box until a half holds at most kClusterTriangles triangles. A
/// cell's detail is thousands of triangles across the whole cell; as one object, its box
/// is the cell's, and culling by box never applies. In order of first appearance, so the
/// same soup gives the same clusters.
void cluster_pieces(const std::vector<DetailPiece>& pieces, std::vector<std::vector<const DetailPiece*>>& out) {
  struct Group {
    Vec3 centre{0, 0, 0};
    size_t triangles = 0;
    std::vector<const DetailPiece*> pieces;
  };
  std::vector<Group> groups;
  std::unordered_map<int64_t, size_t> group_of;
  size_t total = 0;
  for (const DetailPiece& p : pieces) {
    const auto [it, added] = group_of.try_emplace(p.polygon, groups.size());
    if (added) groups.emplace_back();
    Group& g = groups[it->second];
    for (Vec3 v : p.corners) g.centre = g.centre + v;
    g.triangles += p.corners.size() - 2;
    total += p.corners.size() - 2;
    g.pieces.push_back(&p);
  }
  for (Group& g : groups) {
    size_t corners = 0;
    for (const DetailPiece* p : g.pieces) corners += p->corners.size();
    g.centre = (1.0 / double(corners)) * g.centre;
  }
  std::vector<size_t> order(groups.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  // [lo, hi) of order, holding `triangles`.
  auto split = [&](auto&& self, size_t lo, size_t hi, size_t triangles) -> void {
    if (triangles <= kClusterTriangles || hi - lo < 2) {
      std::sort(order.begin() + std::ptrdiff_t(lo), order.begin() + std::ptrdiff_t(hi));  // first appearance
      out.emplace_back();
      for (size_t i = lo; i < hi; ++i)
        out.back().insert(out.back().end(), groups[order[i]].pieces.begin(), groups[order[i]].pieces.end());
      return;
    }
    Box3 box;
    for (size_t i = lo; i < hi; ++i) box.add(groups[order[i]].centre);
    const Vec3 size = box.hi - box.lo;
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    auto along = [axis](const Group& g) { return axis == 0 ? g.centre.x : axis == 1 ? g.centre.y : g.centre.z; };
    const size_t mid = lo + (hi - lo) / 2;
    std::nth_element(order.begin() + std::ptrdiff_t(lo), order.begin() + std::ptrdiff_t(mid),
                     order.begin() + std::ptrdiff_t(hi), [&](size_t a, size_t b) {
                       const double ca = along(groups[a]), cb = along(groups[b]);
                       return ca < cb || (ca == cb && a < b);
                     });
    size_t left = 0;
    for (size_t i = lo; i < mid; ++i) left += groups[order[i]].triangles;
    self(self, lo, mid, left);
    self(self, mid, hi, triangles - left);
  };
  split(split, 0, order.size(), total);
}

}  // namespace

std::vector<int64_t> flat_surfaces(const std::vector<SoupTriangle>& soup, const std::vector<int64_t>& polygon) {
  const size_t n = soup.size();
  std::vector<int64_t> parent(n);
  for (size_t i = 0; i < n; ++i) parent[i] = int64_t(i);
  auto find = [&](int64_t x) {
    while (parent[size_t(x)] != x) x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  };
  auto unite = [&](size_t a, size_t b) {
    const int64_t ra = find(int64_t(a)), rb = find(int64_t(b));
    if (ra != rb) parent[size_t(std::max(ra, rb))] = std::min(ra, rb);
  };
  // Triangles of one input polygon are one surface.
  {
    std::unordered_map<int64_t, size_t> first;
    for (size_t i = 0; i < n; ++i) {
      auto [it, added] = first.try_emplace(polygon[i], i);
      if (!added) unite(it->second, i);
    }
  }
  std::unordered_map<Vec3, uint32_t, PointHash, PointEqual> vid;  // corners welded by position
  auto id = [&](Vec3 p) { return vid.try_emplace(p, uint32_t(vid.size())).first->second; };
  // On one plane: the plane the decomposition cuts each on (nearly coplanar triangles
  // share one, cells/shared_planes.h).
  const SharedPlanes planes = shared_planes(soup);
  std::unordered_map<uint64_t, size_t> edge;  // (lo, hi) corner ids -> a triangle with that edge
  for (size_t i = 0; i < n; ++i) {
    const auto& t = soup[i].p;
    const uint32_t v[3] = {id(t[0]), id(t[1]), id(t[2])};
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = v[k], b = v[(k + 1) % 3];
      if (a == b) continue;
      const uint64_t key = uint64_t(std::min(a, b)) << 32 | std::max(a, b);
      auto [it, added] = edge.try_emplace(key, i);
      if (!added && planes.plane_of[it->second] == planes.plane_of[i]) unite(i, it->second);
    }
  }
  std::vector<int64_t> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = find(int64_t(i));
  return out;
}

SoupSplit split_detail(const std::vector<SoupTriangle>& soup, const std::vector<int64_t>& surface, size_t above,
                       size_t budget, double least_area, const std::vector<bool>& curved) {
  SoupSplit s;
  s.detail.assign(soup.size(), false);
  std::vector<double> area(soup.size());
  auto is_curved_at = [&](size_t i) { return i < curved.size() && curved[i]; };
  size_t with_area = 0;
  for (size_t i = 0; i < soup.size(); ++i) {
    area[i] = triangle_area(soup[i]);
    if (is_curved_at(i)) {
      s.detail[i] = true;
      s.curved += area[i] > 0;
    } else {
      with_area += area[i] > 0;
    }
  }
  s.detail_triangles = s.curved;
  s.structural = with_area;
  if (with_area <= above) return s;
  // The surfaces, largest first: their areas and their triangles with area.
  struct Surface {
    int64_t id = 0;
    double area = 0;
    size_t triangles = 0;
  };
  std::unordered_map<int64_t, size_t> index;
  std::vector<Surface> surfaces;
  for (size_t i = 0; i < soup.size(); ++i) {
    if (is_curved_at(i)) continue;
    auto [it, added] = index.try_emplace(surface[i], surfaces.size());
    if (added) surfaces.push_back({surface[i], 0, 0});
    Surface& p = surfaces[it->second];
    p.area += area[i];
    p.triangles += area[i] > 0;
  }
  std::vector<size_t> order(surfaces.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return surfaces[a].area != surfaces[b].area ? surfaces[a].area > surfaces[b].area : surfaces[a].id < surfaces[b].id;
  });
  std::vector<bool> structural(surfaces.size(), false);
  size_t taken = 0;
  for (size_t k : order) {
    if (surfaces[k].area < least_area) break;
    // A surface of more triangles than the whole budget (a floor tessellated into tiles)
    // could never cut: passed over, so that it does not leave the whole soup as detail.
    if (surfaces[k].triangles > budget) continue;
    if (taken + surfaces[k].triangles > budget) break;
    taken += surfaces[k].triangles;
    structural[k] = true;
    if (surfaces[k].area > 0) s.smallest_structural = surfaces[k].area;
  }
  s.structural = taken;
  for (size_t i = 0; i < soup.size(); ++i)
    if (!is_curved_at(i) && !structural[index.at(surface[i])]) {
      s.detail[i] = true;
      s.detail_triangles += area[i] > 0;
    }
  return s;
}

bool is_curved(const ClosedSolid& solid, size_t directions) {
  if (directions == 0 || solid.triangles.size() < directions) return false;
  // Directions and planes by their rounded numbers: a flat polygon's triangles share
  // theirs, a smooth surface's facets differ by far more than the rounding.
  const double place = 1e-5 * solid.box.magnitude();
  std::set<std::array<int64_t, 3>> facing;
  std::set<std::array<int64_t, 4>> planes;
  for (const Triangle3& t : solid.triangles) {
    const Vec3 n = cross(t[1] - t[0], t[2] - t[0]);
    const double l = length(n);
    if (!(l > 0)) continue;
    const Vec3 u = (1 / l) * n;
    const std::array<int64_t, 3> way{std::llround(u.x * 1e5), std::llround(u.y * 1e5), std::llround(u.z * 1e5)};
    facing.insert(way);
    planes.insert({way[0], way[1], way[2], std::llround(dot(u, t[0]) / place)});
  }
  return facing.size() >= directions && 4 * facing.size() >= 3 * planes.size();
}

double add_detail_objects(CellComplex& out, const std::vector<SoupTriangle>& detail, const std::vector<int64_t>& polygon,
                          const std::string& source) {
  if (out.bands.empty()) out.index();
  const Box3& fb = out.far_box;
  const double scale = fb.magnitude();
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
  std::vector<std::vector<DetailPiece>> of(out.cells.size());
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
      const auto& [sum, area] = moments.at(polygon[t]);
      of[size_t(c)].push_back({piece, polygon[t], tri.material, (1 / area) * sum});
      covered += a;
    }
  }
  std::vector<std::vector<const DetailPiece*>> clusters;
  for (size_t c = 0; c < of.size(); ++c) {
    if (of[c].empty()) continue;
    clusters.clear();
    cluster_pieces(of[c], clusters);
    for (size_t k = 0; k < clusters.size(); ++k) {
      DetailMesh d;
      for (const DetailPiece* p : clusters[k]) d.add(p->corners, p->polygon, p->material, p->light);
      if (d.mesh.triangles.empty()) continue;
      Mesh& m = d.mesh;
      const std::string name =
          "detail in cell " + std::to_string(c) + (clusters.size() > 1 ? ", part " + std::to_string(k + 1) : "");
      m.path = source + ": " + name;
      // The materials its triangles use, in the complex's order (a cluster uses a few of
      // a model's many).
      std::vector<MaterialId> used;
      for (MaterialId id : m.material_of)
        if (id >= 0 && size_t(id) < out.materials.size()) used.push_back(id);
      std::sort(used.begin(), used.end());
      used.erase(std::unique(used.begin(), used.end()), used.end());
      for (MaterialId& id : m.material_of) {
        const auto at = std::lower_bound(used.begin(), used.end(), id);
        id = at != used.end() && *at == id ? MaterialId(at - used.begin()) : -1;
      }
      for (MaterialId id : used) m.materials.push_back(out.materials[size_t(id)]);
      // Every piece is seen from both sides: a soup's polygons are (soup_bsp.h).
      m.boundary_edges = boundary_edges(m.triangles);
      m.closed = false;
      smooth_corner_normals(m);
      Object o;
      o.name = name;
      o.cell = int32_t(c);
      o.model = std::make_shared<const Mesh>(std::move(m));
      out.objects.push_back(std::move(o));
    }
  }
  out.index_detail();  // the walker's index of each cell's detail
  return covered;
}

}  // namespace avenues
