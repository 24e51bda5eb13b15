// Avenues — the papers' scenes (see scenes.h).
#include "render/scenes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <tuple>

#include "core/float_rounding.h"

namespace avenues {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSize = 512;  ///< [px] Bouknight's and Wylie's raster

/// Builds a scene's polygons, sharing equal vertices. Coordinates are rounded to float,
/// as an OFF file read by OpenMesh holds them, so the generated mesh and the bundled
/// file are the same to the bit.
class SceneBuilder {
 public:
  explicit SceneBuilder(PaperScene& s) : s_(s) {}
  /// A polygon, reversed if needed so that its normal points along `outward`.
  void polygon(std::vector<Vec3> pts, Vec3 outward, int material = 0) {
    Vec3 n{0, 0, 0};
    for (size_t k = 0; k < pts.size(); ++k) n = n + cross(pts[k], pts[(k + 1) % pts.size()]);
    if (dot(n, outward) < 0) std::reverse(pts.begin(), pts.end());
    std::vector<int> idx;
    for (Vec3 p : pts) idx.push_back(vertex(p));
    s_.polygons.push_back(idx);
    s_.paint.polygon_material.push_back(material);
  }
  int vertex(Vec3 p) {
    const Vec3 f{to_float(p.x), to_float(p.y), to_float(p.z)};
    const auto key = std::make_tuple(f.x, f.y, f.z);
    auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    s_.vertices.push_back(f);
    return index_[key] = int(s_.vertices.size() - 1);
  }

 private:
  PaperScene& s_;
  std::map<std::tuple<double, double, double>, int> index_;
};

Material grey(const char* name, double reflectance) {
  Material m;
  m.name = name;
  m.reflectance = reflectance;
  m.colour = {1, 1, 1};
  return m;
}

Camera camera(Vec3 eye, Vec3 look, double fov) { return Camera::look_at(eye, look, fov, kSize, kSize); }

/// Bouknight's Fig. 8.
PaperScene cottage() {
  PaperScene s;
  s.name = "cottage";
  s.source = "Bouknight 1969, Fig. 8: an A-frame summer cottage";
  s.guesses =
      "Only the counts survive (17 polygons, 60 edges) and the remark that the roof's undersides have a smaller "
      "reflectance. Ours: a 6.4 m A-frame, roof slopes outside (R 0.8) and underneath (R 0.35) with front "
      "fascias, two gable walls, a door, windows and a ramp: 9 quadrilaterals and 8 triangles.";
  s.paint.materials = {grey("roof", 0.8), grey("roof underside", 0.35), grey("wall", 0.6), grey("door", 0.3),
                       grey("glass", 0.15), grey("ramp", 0.5)};
  SceneBuilder b(s);
  const double yf = -0.8, yb = 8.8;  // roof overhangs the gable walls at y = 0 and y = 8
  for (double side : {-1.0, 1.0}) {
    const Vec3 out{side, 0, 0.5};
    b.polygon({{3.2 * side, yf, 0.4}, {3.2 * side, yb, 0.4}, {0, yb, 6.4}, {0, yf, 6.4}}, out, 0);
    b.polygon({{3.2 * side, yf, 0.0}, {3.2 * side, yb, 0.0}, {0, yb, 6.0}, {0, yf, 6.0}}, -1 * out, 1);
    b.polygon({{3.2 * side, yf, 0.4}, {0, yf, 6.4}, {0, yf, 6.0}, {3.2 * side, yf, 0.0}}, {0, -1, 0}, 0);
  }
  b.polygon({{-3.2, 0, 0}, {3.2, 0, 0}, {0, 0, 6.0}}, {0, -1, 0}, 2);
  b.polygon({{-3.2, 8, 0}, {3.2, 8, 0}, {0, 8, 6.0}}, {0, 1, 0}, 2);
  b.polygon({{-0.5, -0.02, 0.5}, {0.5, -0.02, 0.5}, {0.5, -0.02, 2.6}, {-0.5, -0.02, 2.6}}, {0, -1, 0}, 3);
  b.polygon({{-0.9, -0.02, 2.9}, {0.9, -0.02, 2.9}, {0, -0.02, 4.5}}, {0, -1, 0}, 4);
  b.polygon({{-2.3, -0.02, 0.6}, {-1.0, -0.02, 0.6}, {-1.0, -0.02, 2.3}}, {0, -1, 0}, 4);
  b.polygon({{1.0, -0.02, 0.6}, {2.3, -0.02, 0.6}, {1.0, -0.02, 2.3}}, {0, -1, 0}, 4);
  b.polygon({{-0.6, 8.02, 1.0}, {0.6, 8.02, 1.0}, {0.6, 8.02, 2.2}, {-0.6, 8.02, 2.2}}, {0, 1, 0}, 4);
  b.polygon({{-0.8, 8.02, 3.0}, {0.8, 8.02, 3.0}, {0, 8.02, 4.4}}, {0, 1, 0}, 4);
  b.polygon({{-1.5, 0, 0.5}, {1.5, 0, 0.5}, {1.5, -2.5, 0}, {-1.5, -2.5, 0}}, {0, -0.2, 1}, 5);
  b.polygon({{-1.5, 0, 0}, {-1.5, 0, 0.5}, {-1.5, -2.5, 0}}, {-1, 0, 0}, 5);
  b.polygon({{1.5, 0, 0}, {1.5, 0, 0.5}, {1.5, -2.5, 0}}, {1, 0, 0}, 5);
  s.camera = camera({-9, -15, 4.5}, {0, 3, 2.6}, 40);
  s.paper_polygons = 17;
  s.paper_edges = 60;
  s.paper_seconds = 13.5;
  s.paper_machine = "CDC 1604";
  s.paper_figures = "Warnock's algorithm: 2:00";
  return s;
}

/// A 15 × 15 torus of quadrilaterals, each `grow` times its size about its centre.
void torus(PaperScene& s, double grow) {
  constexpr int kN = 15;
  constexpr double kMajor = 1.0, kMinor = 0.45;
  auto at = [](int i, int j) {
    const double u = 2 * kPi * (i % kN) / kN, v = 2 * kPi * (j % kN) / kN;  // the seam closes exactly
    return Vec3{(kMajor + kMinor * std::cos(v)) * std::cos(u), (kMajor + kMinor * std::cos(v)) * std::sin(u),
                kMinor * std::sin(v)};
  };
  s.paint.materials = {grey("torus", 0.85)};
  SceneBuilder b(s);
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j) {
      std::vector<Vec3> q{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      const Vec3 centre = 0.25 * (q[0] + q[1] + q[2] + q[3]);
      const double u = 2 * kPi * (i + 0.5) / kN;
      const Vec3 ring{kMajor * std::cos(u), kMajor * std::sin(u), 0};
      for (Vec3& p : q) p = centre + grow * (p - centre);
      b.polygon(q, centre - ring);
    }
  s.camera = camera({0, -3.3, 2.4}, {0, 0, -0.15}, 45.9);  // the ripple torus spans 326 scanlines, as Bouknight's
  s.paper_polygons = 225;
  s.paper_edges = 900;
}

PaperScene plain_torus() {
  PaperScene s;
  s.name = "torus";
  s.source = "Bouknight 1969, Fig. 9: a torus in free space";
  s.guesses = "225 polygons, 900 edges: a 15 x 15 grid of quadrilaterals; radii 1 and 0.45 and the view are ours.";
  torus(s, 1.0);
  s.paper_seconds = 100;
  s.paper_machine = "CDC 1604";
  s.paper_figures = "Warnock's algorithm: 8:00";
  return s;
}

PaperScene ripple_torus() {
  PaperScene s;
  s.name = "ripple-torus";
  s.source = "Bouknight 1969, Fig. 10: the \"ripple\" torus";
  s.guesses =
      "\"each edge slices through the next\", 450 implicitly defined lines: each quadrilateral of the torus is "
      "enlarged 1.15 times about its centre, so it passes through its four neighbours along their 450 shared "
      "edges (and, near each corner, through its diagonal neighbours a little).";
  torus(s, 1.15);
  s.paper_seconds = 110;
  s.paper_machine = "CDC 1604";
  s.paper_figures =
      "326 scanlines (y 70-395), 884 edges (16 horizontal ones dropped), 22,632 intersections, 77,776 depth "
      "sorts, 2,960 implicit lines, active list at most 100 and 69.4 on average; Warnock's algorithm: 9:40";
  return s;
}

PaperScene cubes() {
  PaperScene s;
  s.name = "cubes";
  s.source = "Bouknight 1969, Fig. 11: an array of cubes";
  s.guesses =
      "Two layers of 4 x 4 unit cubes, each a top and four sides (no bottom), 2 apart, the upper layer 2 above "
      "the lower; the view is ours, chosen so that the array runs out of the window's top and right and about "
      "as many edges as his (444) cross the window.";
  s.paint.materials = {grey("cube", 0.8)};
  SceneBuilder b(s);
  for (int layer = 0; layer < 2; ++layer)
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const double x = 2 * i, y = 2 * j, z = 2 * layer;
        auto p = [&](double dx, double dy, double dz) { return Vec3{x + dx, y + dy, z + dz}; };
        b.polygon({p(0, 0, 1), p(1, 0, 1), p(1, 1, 1), p(0, 1, 1)}, {0, 0, 1});
        b.polygon({p(0, 0, 0), p(1, 0, 0), p(1, 0, 1), p(0, 0, 1)}, {0, -1, 0});
        b.polygon({p(1, 0, 0), p(1, 1, 0), p(1, 1, 1), p(1, 0, 1)}, {1, 0, 0});
        b.polygon({p(1, 1, 0), p(0, 1, 0), p(0, 1, 1), p(1, 1, 1)}, {0, 1, 0});
        b.polygon({p(0, 1, 0), p(0, 0, 0), p(0, 0, 1), p(0, 1, 1)}, {-1, 0, 0});
      }
  s.camera = camera({-3, -3, 6}, {0.6, 2.1, 1.0}, 40);  // about 444 edges in the window, as Bouknight's
  s.paper_polygons = 160;
  s.paper_edges = 640;
  s.paper_seconds = 120;
  s.paper_machine = "CDC 1604";
  s.paper_figures =
      "just over 2:00; 444 of 640 edges processed, the rest outside the window's top and right; Warnock's "
      "algorithm: about 20:00";
  return s;
}

PaperScene wylie_cube() {
  PaperScene s;
  s.name = "wylie-cube";
  s.source = "Wylie 1967, Figs. 13-16: a cube of 12 triangles";
  s.guesses = "Each face split along a diagonal; the \"unusual perspective\" is ours (an eye close to a corner).";
  s.paint.materials = {grey("cube", 0.85)};
  SceneBuilder b(s);
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      auto p = [&](double a, double c) {
        double v[3];
        v[axis] = side;
        v[(axis + 1) % 3] = a;
        v[(axis + 2) % 3] = c;
        return Vec3{v[0], v[1], v[2]};
      };
      Vec3 out{0, 0, 0};
      (axis == 0 ? out.x : axis == 1 ? out.y : out.z) = side;
      b.polygon({p(-1, -1), p(1, -1), p(1, 1)}, out);
      b.polygon({p(-1, -1), p(1, 1), p(-1, 1)}, out);
    }
  s.camera = camera({2.3, -3.0, 1.9}, {0, 0, 0}, 52);
  s.paper_polygons = 12;
  s.paper_seconds = 25;
  s.paper_machine = "Univac 1108 (PIXURE, FORTRAN IV)";
  s.paper_figures = "about 25 s a frame for the cube and the tetrahedron alike";
  return s;
}

PaperScene wylie_tetrahedron() {
  PaperScene s;
  s.name = "wylie-tetrahedron";
  s.source = "Wylie 1967, Figs. 17-18: a tetrahedron";
  s.guesses = "A regular tetrahedron (Fig. 18 removes one side; we keep all four); the view is ours.";
  s.paint.materials = {grey("tetrahedron", 0.85)};
  SceneBuilder b(s);
  const Vec3 v[4] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (int k = 0; k < 4; ++k) {
    const Vec3 a = v[(k + 1) % 4], c = v[(k + 2) % 4], d = v[(k + 3) % 4];
    b.polygon({a, c, d}, (1.0 / 3) * (a + c + d) - v[k]);
  }
  s.camera = camera({2.0, -3.6, 1.1}, {0, 0, 0}, 48);
  s.paper_polygons = 4;
  s.paper_seconds = 25;
  s.paper_machine = "Univac 1108 (PIXURE, FORTRAN IV)";
  s.paper_figures = "about 25 s a frame";
  return s;
}

PaperScene crow_object() {
  PaperScene s;
  s.name = "crow-object";
  s.source = "Crow 1981, table 1b: 10 points, 7 polygons";
  s.guesses =
      "The points and polygons are the table's (a cube with one corner cut off); Crow lists them clockwise seen "
      "from outside, we store them counter-clockwise. The view is ours.";
  s.paint.materials = {grey("object", 0.85)};
  const Vec3 pt[10] = {{1, -1, -1}, {-1, -1, -1}, {-1, -1, 0}, {0, -1, 1}, {1, -1, 1},
                       {-1, 0, 1},  {-1, 1, -1},  {1, 1, -1},  {1, 1, 1},  {-1, 1, 1}};
  const std::vector<std::vector<int>> polys = {{1, 2, 3, 4, 5},  {8, 1, 5, 9},      {7, 8, 9, 10}, {2, 7, 10, 6, 3},
                                               {8, 7, 2, 1},     {5, 4, 6, 10, 9},  {3, 6, 4}};
  SceneBuilder b(s);
  for (const auto& poly : polys) {
    std::vector<Vec3> p;
    Vec3 centre{0, 0, 0};
    for (int i : poly) {
      p.push_back(pt[i - 1]);
      centre = centre + pt[i - 1];
    }
    b.polygon(p, (1.0 / double(p.size())) * centre);  // the object is convex about the origin
  }
  s.camera = camera({4.2, -6.0, 3.4}, {0, 0, 0}, 34);
  s.paper_polygons = 7;
  return s;
}

}  // namespace

std::vector<PaperScene> paper_scenes() {
  return {cottage(), plain_torus(), ripple_torus(), cubes(), wylie_cube(), wylie_tetrahedron(), crow_object()};
}

Mesh mesh_of(const PaperScene& s) {
  // As plans/mesh.cpp reads a file.
  return mesh_of_polygons("plans/scenes/" + s.name + ".off", s.vertices, s.polygons);
}

std::string off_text(const PaperScene& s) {
  std::ostringstream o;
  o.precision(17);  // round-trips a double (the vertices are floats: read as doubles, each the same number)
  o << "OFF\n" << s.vertices.size() << " " << s.polygons.size() << " 0\n";
  for (Vec3 v : s.vertices) o << v.x << " " << v.y << " " << v.z << "\n";
  for (const auto& p : s.polygons) {
    o << p.size();
    for (int i : p) o << " " << i;
    o << "\n";
  }
  return o.str();
}

}  // namespace avenues
