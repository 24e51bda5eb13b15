// Avenues — the insides of closed solids in a soup (solid_insides.h).
#include "cells/solid_insides.h"

#include "cells/free_regions.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

namespace avenues {

namespace {

/// Union-find over 0..n-1, with path halving.
struct Groups {
  std::vector<size_t> parent;
  explicit Groups(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), size_t(0)); }
  size_t find(size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(size_t a, size_t b) { parent[find(a)] = find(b); }
};

/// The closed solids of one mesh (closed_solids).
void solids_of(const Mesh& m, size_t mesh, std::vector<ClosedSolid>& out) {
  // Corners welded by position: readers split a vertex where its normals or texture
  // coordinates differ, which does not open the surface.
  std::map<std::tuple<double, double, double>, int> id_of;
  std::vector<int> weld(m.vertices.size());
  for (size_t v = 0; v < m.vertices.size(); ++v) {
    const Vec3 p = m.vertices[v];
    weld[v] = id_of.try_emplace({p.x, p.y, p.z}, int(id_of.size())).first->second;
  }
  std::vector<std::array<int, 3>> tris;
  std::vector<size_t> source;  // per entry of tris, its triangle in m
  for (size_t k = 0; k < m.triangles.size(); ++k) {
    const auto& t = m.triangles[k];
    const std::array<int, 3> w{weld[size_t(t[0])], weld[size_t(t[1])], weld[size_t(t[2])]};
    // Two corners at one place: its edges cancel, and it covers nothing.
    if (w[0] != w[1] && w[1] != w[2] && w[2] != w[0]) tris.push_back(w), source.push_back(k);
  }
  Groups g(id_of.size());
  for (const auto& t : tris) g.join(size_t(t[0]), size_t(t[1])), g.join(size_t(t[0]), size_t(t[2]));
  std::map<size_t, std::vector<size_t>> components;  // root -> its triangles, in file order
  for (size_t i = 0; i < tris.size(); ++i) components[g.find(size_t(tris[i][0]))].push_back(i);
  std::vector<std::vector<size_t>> ordered;
  for (auto& [root, list] : components) ordered.push_back(std::move(list));
  std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) { return a.front() < b.front(); });

  std::vector<Vec3> at(id_of.size());
  for (size_t v = 0; v < m.vertices.size(); ++v) at[size_t(weld[v])] = m.vertices[v];
  const std::string file = m.path.empty() ? std::string("mesh") : m.path;
  int number = 0;
  for (const std::vector<size_t>& list : ordered) {
    // Closed and consistently oriented: every edge used as often in one direction as in
    // the other (the surface has no boundary, so its winding number is a whole number off
    // it). Solids touching along a face or an edge (welded there) still qualify; one
    // triangle turned the wrong way, a hole or a dangling sheet do not.
    std::map<std::pair<int, int>, int> balance;  // (low, high) -> uses low→high minus high→low
    for (size_t i : list)
      for (int k = 0; k < 3; ++k) {
        const int a = tris[i][size_t(k)], b = tris[i][size_t((k + 1) % 3)];
        balance[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
      }
    if (std::any_of(balance.begin(), balance.end(), [](const auto& e) { return e.second != 0; })) continue;
    ClosedSolid s;
    s.mesh = mesh;
    const Vec3 o = at[size_t(tris[list.front()][0])];
    for (size_t i : list) {
      const Vec3 a = at[size_t(tris[i][0])], b = at[size_t(tris[i][1])], c = at[size_t(tris[i][2])];
      s.volume += dot(a - o, cross(b - o, c - o)) / 6;
      s.triangles.push_back({a, b, c});
      s.source.push_back(source[i]);
      s.box.add(a), s.box.add(b), s.box.add(c);
    }
    const Vec3 e = s.box.hi - s.box.lo;
    const double size = std::max({e.x, e.y, e.z});
    // Turned inwards (a room modelled from inside) or flat: not a solid.
    if (!(s.volume > 1e-9 * size * size * size)) continue;
    s.name = file + ": solid " + std::to_string(++number);
    out.push_back(std::move(s));
  }
}

}  // namespace

std::vector<ClosedSolid> closed_solids(const std::vector<Mesh>& meshes) {
  std::vector<ClosedSolid> out;
  for (size_t i = 0; i < meshes.size(); ++i) solids_of(meshes[i], i, out);
  return out;
}

std::vector<int> cells_inside_solids(const CellComplex& c, const std::vector<ClosedSolid>& solids) {
  const size_t n = c.cells.size();
  std::vector<int> inside(n, -1);
  if (solids.empty() || n == 0) return inside;
  const FreeRegions regions = free_regions(c);
  std::vector<int> solid_of_region(n, -1);
  for (size_t r = 0; r < n; ++r) {
    if (regions.largest[r] == n || r == regions.outside) continue;  // not a root, or outside everything
    const Vec3 middle = c.cells[regions.largest[r]].middle();
    double w = 0, most = 0;
    int named = -1;  // the solid that winds most about the point: the one it is said to be in
    for (size_t i = 0; i < solids.size(); ++i) {
      if (!solids[i].box.contains(middle)) continue;  // outside its box: its number is 0
      const double wi = winding_number(solids[i].triangles, middle);
      if (named < 0 || wi > most) named = int(i), most = wi;
      w += wi;
    }
    if (w > 0.5) solid_of_region[r] = named;
  }
  for (size_t i = 0; i < n; ++i) inside[i] = solid_of_region[regions.of[i]];
  return inside;
}

}  // namespace avenues
