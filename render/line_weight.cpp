// Avenues — line weights (see line_weight.h).
#include "render/line_weight.h"

#include <cmath>
#include <vector>

namespace avenues {

namespace {

constexpr double kOnPlane = 1e-7;  ///< [m] a line lies in a face's plane (coordinates are snapped to 1 nm)
constexpr double kProbe = 1e-4;    ///< [m] how far from the line a face is probed (openings are centimetres wide)
constexpr double kInPolygon = 1e-9; ///< [m] a probe this close to a polygon's edge is inside it
constexpr double kEdgeOn = 1e-9;   ///< |cos| below which a surface is seen edge-on

Vec3 unit(Vec3 v) { return (1.0 / length(v)) * v; }

}  // namespace

LineFaces line_faces(const CellComplex& c) {
  LineFaces out;
  std::vector<std::vector<Vec3>> dirs(c.lines.size());
  out.cell_start.reserve(c.cells.size() + 1);
  // Per face of the cell, each opaque piece's box: a face of the outside cell (the ground
  // around a building) holds thousands of pieces, and each probe is tested only against
  // the pieces whose box holds it.
  std::vector<std::vector<Box3>> boxes;
  std::vector<Box3> face_boxes;  // and each face's, to skip the faces a line cannot lie on
  for (const Cell& cell : c.cells) {
    out.cell_start.push_back(int32_t(out.shows.size()));
    if (cell.lines.empty()) continue;
    boxes.resize(cell.faces.size());
    face_boxes.assign(cell.faces.size(), Box3{});
    for (size_t f = 0; f < cell.faces.size(); ++f) {
      for (const Vec3& v : cell.faces[f].poly) face_boxes[f].add(v);
      boxes[f].assign(cell.faces[f].opaque.size(), Box3{});
      for (size_t k = 0; k < cell.faces[f].opaque.size(); ++k)
        for (const Vec3& v : cell.faces[f].opaque[k].poly) boxes[f][k].add(v);
    }
    for (const CellLine& cl : cell.lines) {
      const RealLine& l = c.lines[size_t(cl.line)];
      const Vec3 u = unit(l.b - l.a);
      const Vec3 m = l.a + (0.5 * (cl.t0 + cl.t1)) * (l.b - l.a);
      int faces = 0, opaque_sides = 0;
      for (size_t fi = 0; fi < cell.faces.size(); ++fi) {
        const Face& f = cell.faces[fi];
        if (!face_boxes[fi].contains(m, kOnPlane)) continue;  // the line's middle lies in the face it lies on
        if (std::fabs(f.plane.eval(l.a)) > kOnPlane || std::fabs(f.plane.eval(l.b)) > kOnPlane) continue;
        ++faces;
        const Vec3 w = unit(cross(f.plane.n, u));  // in the face, perpendicular to the line
        for (Vec3 side : {w, -1.0 * w}) {
          bool opaque = false;
          const Vec3 probe = m + kProbe * side;
          for (size_t k = 0; k < f.opaque.size() && !opaque; ++k)
            opaque = boxes[fi][k].contains(probe, kOnPlane) && in_convex_polygon(f.opaque[k].poly, f.plane.n, probe, kInPolygon);
          if (!opaque) continue;
          ++opaque_sides;
          bool known = false;
          for (Vec3 k : dirs[size_t(cl.line)]) known = known || length(k - side) < 1e-6;
          if (!known) dirs[size_t(cl.line)].push_back(side);
        }
      }
      out.shows.push_back(!(faces == 1 && opaque_sides == 2));
    }
  }
  out.cell_start.push_back(int32_t(out.shows.size()));
  out.start.reserve(c.lines.size() + 1);
  out.start.push_back(0);
  for (const auto& d : dirs) {
    out.dirs.insert(out.dirs.end(), d.begin(), d.end());
    out.start.push_back(int32_t(out.dirs.size()));
  }
  return out;
}

namespace {

/// The test of line_weight.h with n the normal of Π.
Weight weight_about(const CellComplex& c, const LineFaces& faces, LineId id, Vec3 n) {
  const RealLine& l = c.lines[size_t(id)];
  const int32_t first = faces.start[size_t(id)], last = faces.start[size_t(id) + 1];
  // No face found (never expected): fall back on the line's kind.
  if (first == last) return l.kind == LineKind::Concave ? Weight::Crease : Weight::Outline;
  const double nn = length(n);
  if (!(nn > 0)) return Weight::Crease;  // seen end-on: a point
  bool pos = false, neg = false;
  for (int32_t k = first; k < last; ++k) {
    const double s = dot(n, faces.dirs[size_t(k)]) / nn;
    pos |= s > kEdgeOn;
    neg |= s < -kEdgeOn;
  }
  return pos && neg ? Weight::Crease : Weight::Outline;
}

}  // namespace

Weight line_weight(const CellComplex& c, const LineFaces& faces, LineId id, Vec3 eye) {
  const RealLine& l = c.lines[size_t(id)];
  return weight_about(c, faces, id, cross(l.a - eye, l.b - l.a));  // Π through the eye and the line
}

Weight line_weight_along(const CellComplex& c, const LineFaces& faces, LineId id, Vec3 direction) {
  const RealLine& l = c.lines[size_t(id)];
  return weight_about(c, faces, id, cross(direction, l.b - l.a));  // Π through the line, along the rays
}

}  // namespace avenues
