// Avenues — an IFC building model as a Plan (see ifc_building.h, docs/IFC.md).
#include "plans/formats/ifc_building.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <csignal>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>
#include <tuple>

#include "core/number_format.h"
#include "plans/assimp_reader.h"
#include "plans/formats/ifc_step.h"
#include "plans/formats/ifc4_for_assimp.h"
#include "plans/mesh.h"

namespace avenues {
namespace {

constexpr double kMinWall = 0.05;       ///< [m] a footprint shorter than this is no wall
constexpr double kMinOpening = 0.2;     ///< [m] narrower or lower than this is no opening
constexpr double kDoorReach = 0.25;     ///< [m] a door's centre may lie this far outside its wall's faces
constexpr double kOnFloor = 0.1;        ///< [m] a wall whose foot is this near a storey's floor stands on it
constexpr double kSnapPerMetre = 1e4;   ///< walls' centre lines and thicknesses within a rounding of this grid are read on it
constexpr double kMinFill = 0.7;        ///< a wall's hull fills at least this share of its rectangle
constexpr double kEyeHeight = 1.6;      ///< [m] above the floor
constexpr size_t kWarningsListed = 40;
constexpr int kChildRead = 0, kChildFailed = 3;  ///< exit statuses of the reading child  ///< dropped elements named one by one; the rest counted

enum class Role { None, Container, Storey, Space, Wall, Door, Window, Surface, Object, Skip };

/// "IfcWallStandardCase" of "IfcWallStandardCase_Basic Wall:Interior_2O2Fr$t4X7Zf8NOew3FNld".
std::string ifc_type(const std::string& node) {
  if (node.rfind("Ifc", 0) != 0) return {};
  return node.substr(0, node.find('_'));
}

/// The element's own name: between the type and the 22-character GUID.
std::string ifc_name(const std::string& node, const std::string& type) {
  std::string rest = node.size() > type.size() + 1 ? node.substr(type.size() + 1) : std::string();
  if (rest.size() >= 23 && rest[rest.size() - 23] == '_') rest.resize(rest.size() - 23);
  else if (rest.size() == 22) rest.clear();  // only a GUID
  return rest;
}

std::string ifc_guid(const std::string& node) { return node.size() >= 22 ? node.substr(node.size() - 22) : node; }

Role role_of(const std::string& type) {
  if (type.empty() || type == "IfcMappedItem") return Role::None;
  if (type == "IfcProject" || type == "IfcSite" || type == "IfcBuilding") return Role::Container;
  if (type == "IfcBuildingStorey") return Role::Storey;
  if (type == "IfcSpace") return Role::Space;
  if (type.rfind("IfcWall", 0) == 0 || type == "IfcCurtainWall" || type == "IfcColumn") return Role::Wall;
  if (type == "IfcDoor") return Role::Door;
  if (type == "IfcWindow") return Role::Window;
  // Floors and ceilings: the rooms' floor and ceiling materials where they lie at a storey's
  // floor or ceiling, else objects (make_surfaces).
  if (type == "IfcSlab" || type == "IfcCovering") return Role::Surface;
  // An opening element has no surface; footings lie under the lowest floor.
  if (type == "IfcOpeningElement" || type == "IfcFooting" || type == "IfcAnnotation" || type == "IfcGrid")
    return Role::Skip;
  return Role::Object;  // furniture, stairs, railings, roofs, beams, members, fittings, proxies
}

/// One element and the triangles of its node and of its parts.
struct Element {
  std::string type, name, guid;
  Role role = Role::None;
  int storey = -1;  ///< index into Builder::storey_nodes; -1 outside every storey
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::array<double, 3> colour{0.8, 0.8, 0.8};
  bool coloured = false;
  Box3 box;
  bool as_object = false;  ///< a wall or surface drawn as an object (it stands on no floor, lies on none)
  /// [m] A wall of the top storey rising above its band (a gable over a flat ceiling, an
  /// attic no space claims): what of it lies above this height is drawn as an object.
  double above = HUGE_VAL;
  std::string kind;  ///< the file's own kind where Assimp read it as another (IFC4's "IfcSanitaryTerminal"), else empty
  std::string label() const { return (kind.empty() ? type : kind) + " '" + (name.empty() ? guid : name) + "'"; }
};

/// The smallest rectangle around a convex polygon (one side lies on a hull edge).
struct Rect {
  Vec2 centre, along;  ///< along: unit, the long side's direction
  double length = 0, width = 0, fill = 0;  ///< fill: hull area / rectangle area
};

std::optional<Rect> min_area_rect(const std::vector<Vec2>& hull) {
  if (hull.size() < 3) return std::nullopt;
  const double area = std::fabs(signed_area(hull));
  std::optional<Rect> best;
  double best_area = HUGE_VAL;
  for (size_t i = 0; i < hull.size(); ++i) {
    Vec2 d = hull[(i + 1) % hull.size()] - hull[i];
    const double l = length(d);
    if (l < 1e-9) continue;
    d = (1 / l) * d;
    const Vec2 n{-d.y, d.x};
    double a0 = HUGE_VAL, a1 = -HUGE_VAL, b0 = HUGE_VAL, b1 = -HUGE_VAL;
    for (Vec2 q : hull) {
      a0 = std::min(a0, dot(q, d)), a1 = std::max(a1, dot(q, d));
      b0 = std::min(b0, dot(q, n)), b1 = std::max(b1, dot(q, n));
    }
    const double ar = (a1 - a0) * (b1 - b0);
    if (ar >= best_area) continue;
    best_area = ar;
    Rect r;
    r.centre = (0.5 * (a0 + a1)) * d + (0.5 * (b0 + b1)) * n;
    if (a1 - a0 >= b1 - b0) r.along = d, r.length = a1 - a0, r.width = b1 - b0;
    else r.along = n, r.length = b1 - b0, r.width = a1 - a0;
    r.fill = ar > 0 ? area / ar : 0;
    best = r;
  }
  return best;
}

std::vector<Vec2> footprint_points(const Element& e) {
  std::vector<Vec2> p;
  p.reserve(e.vertices.size());
  for (Vec3 v : e.vertices) p.push_back({v.x, v.y});
  return p;
}

/// Whether p lies in triangle abc (either orientation), its sides included.
bool in_triangle(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  return (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v[v.size() / 2];
}

/// A wall of the model, before it is put on the storeys it spans.
struct WallShape {
  size_t element;
  Rect rect;
  double z0, z1;
  bool hung = false;  ///< stands on no floor: a bulkhead, a wall over a window band (a gap beneath it)
};

/// A wall's rectangle as a closed footprint, for point tests.
bool in_rect(const Rect& r, Vec2 p, double grow) {
  const Vec2 n{-r.along.y, r.along.x};
  const Vec2 q = p - r.centre;
  return std::fabs(dot(q, r.along)) <= r.length / 2 + grow && std::fabs(dot(q, n)) <= r.width / 2 + grow;
}

/// Distance from p along unit direction d to the first side of r it meets (HUGE_VAL: none).
double ray_to_rect(const Rect& r, Vec2 p, Vec2 d) {
  const Vec2 n{-r.along.y, r.along.x};
  const Vec2 q = p - r.centre;
  double t0 = 0, t1 = HUGE_VAL;
  for (auto [axis, half] : {std::pair{r.along, r.length / 2}, std::pair{n, r.width / 2}}) {
    const double o = dot(q, axis), v = dot(d, axis);
    if (std::fabs(v) < 1e-12) {
      if (std::fabs(o) > half) return HUGE_VAL;
      continue;
    }
    double a = (-half - o) / v, b = (half - o) / v;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
    if (t0 > t1) return HUGE_VAL;
  }
  return t0;
}

/// The closed loops where the plane z = zc cuts a mesh whose triangles are counter-clockwise
/// seen from outside: counter-clockwise around the solid (holes clockwise). Each cut edge's
/// point is computed from its ends in one order, so that the two triangles sharing an edge
/// give the very same point; pieces of a mesh that is not closed, which close no loop,
/// are left out.
std::vector<std::vector<Vec2>> section_at(const std::vector<Vec3>& v, const std::vector<std::array<int, 3>>& tris,
                                          double zc) {
  auto cut = [&](Vec3 a, Vec3 b) {
    if (std::tie(b.x, b.y, b.z) < std::tie(a.x, a.y, a.z)) std::swap(a, b);
    const double t = (zc - a.z) / (b.z - a.z);
    return Vec2{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
  };
  using Key = std::pair<long long, long long>;
  auto key = [](Vec2 p) { return Key{std::llround(p.x * 1e6), std::llround(p.y * 1e6)}; };  // micrometres
  std::vector<std::pair<Vec2, Vec2>> segments;
  for (const auto& t : tris) {
    const Vec3 p[3] = {v[size_t(t[0])], v[size_t(t[1])], v[size_t(t[2])]};
    std::vector<Vec2> hits;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = p[k], b = p[(k + 1) % 3];
      if ((a.z >= zc) != (b.z >= zc)) hits.push_back(cut(a, b));
    }
    if (hits.size() != 2) continue;
    const Vec3 n = cross(p[1] - p[0], p[2] - p[0]);
    const Vec2 along{-n.y, n.x};  // the solid lies left of the section's direction
    if (dot(hits[1] - hits[0], along) < 0) std::swap(hits[0], hits[1]);
    if (key(hits[0]) != key(hits[1])) segments.push_back({hits[0], hits[1]});
  }
  std::multimap<Key, size_t> from;
  for (size_t i = 0; i < segments.size(); ++i) from.emplace(key(segments[i].first), i);
  std::vector<bool> used(segments.size(), false);
  std::vector<std::vector<Vec2>> loops;
  for (size_t s0 = 0; s0 < segments.size(); ++s0) {
    if (used[s0]) continue;
    std::vector<Vec2> loop;
    std::vector<size_t> taken;
    size_t s = s0;
    bool closed = false;
    while (taken.size() <= segments.size()) {
      used[s] = true;
      taken.push_back(s);
      loop.push_back(segments[s].first);
      const Key end = key(segments[s].second);
      if (end == key(segments[s0].first)) {
        closed = true;
        break;
      }
      auto [b, e] = from.equal_range(end);
      auto next = std::find_if(b, e, [&](const auto& kv) { return !used[kv.second]; });
      if (next == e) break;
      s = next->second;
    }
    if (closed && loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

/// The loop without its straight-through vertices and its edges shorter than `tol`.
std::vector<Vec2> simplified(std::vector<Vec2> p, double tol) {
  for (bool changed = true; changed && p.size() > 3;) {
    changed = false;
    for (size_t i = 0; i < p.size() && p.size() > 3; ++i) {
      const Vec2 a = p[(i + p.size() - 1) % p.size()], b = p[i], c = p[(i + 1) % p.size()];
      const double ac = length(c - a);
      if (length(b - a) < tol || (ac > 0 && std::fabs(cross(c - a, b - a)) / ac < tol)) {
        p.erase(p.begin() + std::ptrdiff_t(i));
        changed = true;
      }
    }
  }
  return p;
}

/// A simple counter-clockwise polygon as convex pieces: ear clipping, then Hertel and
/// Mehlhorn's merge of neighbouring pieces across every diagonal whose removal leaves
/// a convex piece. Empty when no ear is found (a polygon that is not simple).
std::vector<std::vector<Vec2>> convex_pieces(const std::vector<Vec2>& poly) {
  std::vector<std::vector<int>> pieces;
  std::vector<int> left(poly.size());
  for (size_t i = 0; i < poly.size(); ++i) left[i] = int(i);
  while (left.size() > 3) {
    bool clipped = false;
    for (size_t i = 0; i < left.size() && !clipped; ++i) {
      const int a = left[(i + left.size() - 1) % left.size()], b = left[i], c = left[(i + 1) % left.size()];
      const Vec2 pa = poly[size_t(a)], pb = poly[size_t(b)], pc = poly[size_t(c)];
      if (cross(pb - pa, pc - pb) <= 0) continue;  // a reflex corner is no ear
      bool empty = true;
      for (int q : left)
        if (q != a && q != b && q != c && in_triangle(poly[size_t(q)], pa, pb, pc)) empty = false;
      if (!empty) continue;
      pieces.push_back({a, b, c});
      left.erase(left.begin() + std::ptrdiff_t(i));
      clipped = true;
    }
    if (!clipped) return {};
  }
  pieces.push_back(left);
  auto as_points = [&](const std::vector<int>& ids) {
    std::vector<Vec2> out;
    for (int id : ids) out.push_back(poly[size_t(id)]);
    return out;
  };
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t i = 0; i < pieces.size() && !merged; ++i)
      for (size_t j = i + 1; j < pieces.size() && !merged; ++j) {
        const std::vector<int>&P = pieces[i], &Q = pieces[j];
        for (size_t k = 0; k < P.size() && !merged; ++k) {
          const int a = P[k], b = P[(k + 1) % P.size()];
          const auto m = std::find(Q.begin(), Q.end(), b);
          if (m == Q.end() || Q[size_t(m - Q.begin() + 1) % Q.size()] != a) continue;
          // P from b round to a, then Q after a up to before b.
          std::vector<int> R;
          for (size_t t = 1; t <= P.size(); ++t) R.push_back(P[(k + t) % P.size()]);
          const size_t mq = size_t(m - Q.begin());
          for (size_t t = 2; t < Q.size(); ++t) R.push_back(Q[(mq + t) % Q.size()]);
          if (!is_convex_ccw(as_points(R))) continue;
          pieces[i] = std::move(R);
          pieces.erase(pieces.begin() + std::ptrdiff_t(j));
          merged = true;
        }
      }
  }
  std::vector<std::vector<Vec2>> out;
  for (const auto& ids : pieces) out.push_back(as_points(ids));
  return out;
}

/// One straight piece a wall stands on: its rectangle, and its own footprint when that is
/// not the rectangle.
struct WallPiece {
  Rect rect;
  std::vector<Vec2> footprint;  ///< convex, counter-clockwise; empty: the rectangle
};

/// What a wall stands on. Its section is taken at five heights and the fullest kept (above
/// the doors and windows, below a gable's slope): a section that fills its rectangle is a
/// straight wall on that rectangle; any other (an L, a curve, a wall cut on the skew) is its
/// section's convex pieces, each with its own footprint. A mesh whose section does not close
/// keeps the rectangle when its points fill most of it; else there are no pieces.
std::vector<WallPiece> wall_pieces(const Element& e, const Rect& rect) {
  std::vector<std::vector<Vec2>> best;
  double best_area = 0;
  for (double f : {0.92, 0.75, 0.5, 0.25, 0.08}) {
    std::vector<std::vector<Vec2>> loops = section_at(e.vertices, e.triangles, e.box.lo.z + f * (e.box.hi.z - e.box.lo.z));
    double area = 0;
    for (const auto& l : loops) area += std::max(0.0, signed_area(l));
    if (area > best_area) best_area = area, best = std::move(loops);
  }
  const double rect_area = rect.length * rect.width;
  if (best.empty() || best_area >= 0.95 * rect_area) {
    if (best.empty() && rect.fill < kMinFill) return {};
    return {WallPiece{rect, {}}};
  }
  std::vector<WallPiece> out;
  for (const auto& loop : best) {
    if (signed_area(loop) <= 0) continue;  // a hole in the section: left filled
    const std::vector<Vec2> simple = simplified(loop, 1e-3);
    const std::vector<std::vector<Vec2>> convex = convex_pieces(simple);
    if (convex.empty()) return {};
    for (const auto& c : convex) {
      const std::optional<Rect> r = min_area_rect(c);
      if (!r || r->length < 1e-3 || r->width < 1e-3) continue;
      out.push_back({*r, c});
    }
  }
  return out;
}

/// A wall's top seen from its side: over each place along its rectangle (from the end at
/// centre − length/2 · along), the highest point of its mesh, as a polyline {along, z}
/// through its mesh's corners, simplified to kTopTolerance. Empty when the mesh is too
/// large to sweep (then its top is taken as level).
std::vector<Vec2> top_profile(const Element& e, const Rect& r) {
  constexpr double kTopTolerance = 0.01;  // [m]
  const Vec2 o = r.centre - (r.length / 2) * r.along;
  std::vector<Vec2> side(e.vertices.size());  // {along, z}
  for (size_t i = 0; i < e.vertices.size(); ++i)
    side[i] = {std::clamp(dot(Vec2{e.vertices[i].x, e.vertices[i].y} - o, r.along), 0.0, r.length), e.vertices[i].z};
  std::vector<double> at{0, r.length};
  for (Vec2 p : side) at.push_back(p.x);
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end(), [](double a, double b) { return b - a < 1e-4; }), at.end());
  at.back() = r.length;
  if (double(at.size()) * double(e.triangles.size()) > 4e6) return {};
  // Between two corners the top is straight unless two edges cross there: the midpoints
  // find such a crossing's hump.
  const size_t corners = at.size();
  for (size_t i = 0; i + 1 < corners; ++i) at.push_back(0.5 * (at[i] + at[i + 1]));
  std::sort(at.begin(), at.end());
  auto highest = [&](double s) {
    double z = e.box.lo.z;  // (a place no triangle spans, between two parts of a wall: its foot)
    for (const auto& t : e.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec2 a = side[size_t(t[size_t(k)])], b = side[size_t(t[size_t((k + 1) % 3)])];
        // (Within a micrometre: corners a rounding apart along the wall are one place.)
        const double lo = std::min(a.x, b.x), hi = std::max(a.x, b.x);
        if (s < lo - 1e-6 || s > hi + 1e-6) continue;
        const double c = std::clamp(s, lo, hi);
        z = std::max(z, hi - lo > 1e-6 ? a.y + (b.y - a.y) * (c - a.x) / (b.x - a.x) : std::max(a.y, b.y));
      }
    return z;
  };
  std::vector<Vec2> line;
  for (double s : at) line.push_back({s, highest(s)});
  // Douglas–Peucker, by height: the points whose height the straight between the kept ones
  // misses by more than the tolerance are kept.
  std::vector<bool> keep(line.size(), false);
  keep.front() = keep.back() = true;
  std::vector<std::pair<size_t, size_t>> todo{{0, line.size() - 1}};
  while (!todo.empty()) {
    const auto [i, j] = todo.back();
    todo.pop_back();
    double worst = kTopTolerance;
    size_t at_worst = 0;
    for (size_t k = i + 1; k < j; ++k) {
      const double z = line[i].y + (line[j].y - line[i].y) * (line[k].x - line[i].x) / (line[j].x - line[i].x);
      if (std::fabs(line[k].y - z) > worst) worst = std::fabs(line[k].y - z), at_worst = k;
    }
    if (at_worst == 0) continue;
    keep[at_worst] = true;
    todo.push_back({i, at_worst});
    todo.push_back({at_worst, j});
  }
  std::vector<Vec2> out;
  for (size_t k = 0; k < line.size(); ++k)
    if (keep[k]) out.push_back(line[k]);
  return out;
}

/// The point of the 0.1 mm grid a coordinate [m] lies within a single-precision rounding
/// of (as the nearest double to it), or none.
std::optional<double> on_grid(double v) {
  const double g = std::round(v * kSnapPerMetre) / kSnapPerMetre;
  if (std::fabs(v - g) <= std::max(2e-6, 2e-7 * std::fabs(v))) return g;
  return std::nullopt;
}

/// Whether a wall's top profile slopes: it falls more than kOnFloor below its highest point
/// somewhere, and climbs nowhere steeper than a step (a wall with a lower part, a notch,
/// stands level at its highest, as before).
bool slopes(const std::vector<Vec2>& profile) {
  if (profile.size() < 2) return false;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (Vec2 p : profile) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
  if (hi - lo <= kOnFloor) return false;
  for (size_t k = 0; k + 1 < profile.size(); ++k) {
    const double run = profile[k + 1].x - profile[k].x, rise = std::fabs(profile[k + 1].y - profile[k].y);
    if (rise > 10 * run) return false;  // steeper than 84°
  }
  return true;
}

class Builder {
 public:
  explicit Builder(const std::string& path) : path_(path) {}

  double import_seconds = 0;  ///< [s] Assimp's ReadFile

  Plan build() {
    read_step_file();
    read_in_child_first();
    ImportOptions options;
    options.ifc_spaces = true;
    options.contents = for_assimp_;
    ImportedScene scene;
    try {
      scene = import_scene(path_, options);
    } catch (const std::runtime_error& e) {
      // Where the rewrite left geometry out (NURBS boundaries, spheres), that is likely why
      // nothing was left to read: say so, naming the first few.
      std::string left_out;
      for (size_t k = 0; k < rewrite_left_out_.size() && k < 3; ++k) left_out += "\n  " + rewrite_left_out_[k];
      if (rewrite_left_out_count_ > 3) left_out += "\n  and " + std::to_string(rewrite_left_out_count_ - 3) + " more";
      if (!left_out.empty()) left_out = "\nits geometry Assimp has no form for was left out:" + left_out;
      throw PlanError({path_, 0, 0, ""}, std::string("Assimp cannot read this IFC model: ") + e.what() + left_out);
    }
    import_seconds = scene.import_seconds;
    gather(scene);
    plan_.name = std::filesystem::path(path_).stem().string();
    plan_.source = path_;
    plan_.lenient = true;
    make_storeys();
    make_walls();
    make_openings();
    make_stairwells();
    make_rooms();
    make_surfaces();
    make_objects();
    make_view();
    if (plan_.walls.empty()) {
      const std::string what = "the model has no walls or columns to walk between (" +
                               std::to_string(elements_.size()) + " elements, none a usable wall)";
      std::shared_ptr<const Mesh> faces;
      try {
        faces = std::make_shared<const Mesh>(faces_without_spaces(std::move(scene)));
      } catch (const std::runtime_error&) {  // mesh_of_scene: not one triangle
        throw PlanError({path_, 0, 0, ""}, what + ", and no faces but its spaces' to show as a scene");
      }
      throw IfcWithoutWalls({path_, 0, 0, ""}, what, std::move(faces));
    }
    if (dropped_.size() > kWarningsListed)
      plan_.warnings.push_back(std::to_string(dropped_.size() - kWarningsListed) + " more elements dropped");
    return std::move(plan_);
  }

 private:
  /// Every element's faces as one mesh (mesh_of_scene), in their colours, without the
  /// spaces' volumes (read here for the rooms, they are no surfaces).
  static Mesh faces_without_spaces(ImportedScene scene) {
    std::vector<uint8_t> in_space(scene.nodes.size(), 0);
    for (size_t i = 0; i < scene.nodes.size(); ++i) {  // parents come before their children
      ImportedNode& n = scene.nodes[i];
      in_space[i] = ifc_type(n.name) == "IfcSpace" || (n.parent >= 0 && in_space[size_t(n.parent)]);
      if (in_space[i]) n.triangles.clear(), n.triangle_material.clear();
    }
    return mesh_of_scene(scene);
  }

  /// A STEP physical file starts "ISO-10303-21;" and ends "END-ISO-10303-21;": a file cut
  /// short is an error rather than a building with its last storeys missing. The spaces'
  /// LongNames, which Assimp does not keep, are read from its text here.
  void read_step_file() {
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw PlanError({path_, 0, 0, ""}, "cannot open the file");
    std::string head(64, '\0');
    in.read(head.data(), std::streamsize(head.size()));
    head.resize(size_t(in.gcount()));
    if (head.find("ISO-10303-21") == std::string::npos)
      throw PlanError({path_, 1, 0, ""}, "not an IFC file: a STEP file (IFC) starts with 'ISO-10303-21;'");
    in.clear();
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    const std::streamoff tail_size = std::min<std::streamoff>(size, 4096);
    in.seekg(size - tail_size);
    std::string tail(size_t(tail_size), '\0');
    in.read(tail.data(), tail_size);
    if (tail.find("END-ISO-10303-21") == std::string::npos)
      throw PlanError({path_, 0, 0, ""}, "the file is cut short: it does not end with 'END-ISO-10303-21;'");
    std::string text(size_t(size), '\0');
    in.seekg(0);
    in.read(text.data(), size);
    text.resize(size_t(in.gcount()));
    // Assimp's STEP reader crashes on a dangling reference: refuse such a file first.
    if (const std::optional<StepProblem> p = step_data_problem(text)) {
      const int line = 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(p->offset), '\n'));
      throw PlanError({path_, line, 0, ""}, "not a well-formed STEP file: " + p->what);
    }
    names_ = ifc_root_names(text);
    // IFC4's face sets and styles, which Assimp 5.2 cannot read, as IFC2X3 writes them.
    if (std::optional<Ifc4Rewrite> r = ifc4_for_assimp(text)) {
      for (const std::string& w : r->warnings) plan_.warnings.push_back(path_ + ": " + w);
      rewrite_left_out_ = std::move(r->left_out);
      rewrite_left_out_count_ = r->left_out_count;
      for_assimp_ = std::move(r->text);
      ifc4_kinds_ = std::move(r->kinds);
    }
  }

  /// Assimp 5.2's STEP reader crashes on some malformed files the STEP check lets through
  /// (a record of an entity type it does not know, referenced where it expects a known
  /// one). So the model is read once in a child process first: a child that dies is an
  /// error naming the file, not the end of Avenues. A child that only failed (Assimp's own
  /// error) leaves the reading below to say why. Costs one more import.
  void read_in_child_first() const {
    std::fflush(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) return;  // no process to spare: read in this one, as before
    if (pid == 0) {
      // A crash ends the child by its signal, whatever handlers the parent set (a
      // sanitizer's, a fuzzer's): the parent reports it.
      for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(sig, SIG_DFL);
      int code = kChildRead;
      try {
        ImportOptions options;
        options.ifc_spaces = true;
        options.contents = for_assimp_;
        (void)import_scene(path_, options);
      } catch (...) {
        code = kChildFailed;
      }
      ::_exit(code);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0)
      if (errno != EINTR) return;
    if (WIFEXITED(status) && (WEXITSTATUS(status) == kChildRead || WEXITSTATUS(status) == kChildFailed)) return;
    const std::string how = WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                                : "exit status " + std::to_string(WEXITSTATUS(status));
    throw PlanError({path_, 0, 0, ""}, "Assimp cannot read this IFC model: its reader crashed (" + how +
                                           ") on it, a malformed or unsupported file");
  }

  /// The element's Name as the file writes it (with its spaces), else as Assimp's node has it.
  std::string name_of(const std::string& node, const std::string& type) const {
    const auto it = names_.find(ifc_guid(node));
    return it != names_.end() && !it->second.name.empty() ? it->second.name : ifc_name(node, type);
  }

  void drop(const Element& e, const std::string& why) {
    dropped_.push_back(e.label());
    if (dropped_.size() <= kWarningsListed) plan_.warnings.push_back(e.label() + " dropped: " + why);
  }

  /// Elements from nodes: a node of a placed IFC type starts an element, unless it lies
  /// inside one (a mapped item, the flights and railings of a stair, the plates of a
  /// curtain wall), whose triangles it then adds to.
  void gather(const ImportedScene& scene) {
    std::vector<int> owner(scene.nodes.size(), -1), storey_of(scene.nodes.size(), -1);
    for (size_t i = 0; i < scene.nodes.size(); ++i) {
      const ImportedNode& n = scene.nodes[i];
      const int p = n.parent;
      const int parent_owner = p >= 0 ? owner[size_t(p)] : -1;
      storey_of[i] = p >= 0 ? storey_of[size_t(p)] : -1;
      const std::string type = ifc_type(n.name);
      const Role role = role_of(type);
      const bool inside_part = parent_owner >= 0 && elements_[size_t(parent_owner)].role != Role::Space;
      if (role == Role::Storey) {
        storey_of[i] = int(storey_names_.size());
        std::string name = name_of(n.name, type);
        storey_names_.push_back(name.empty() ? "storey " + std::to_string(storey_names_.size() + 1) : name);
      }
      if (inside_part || (role == Role::None && parent_owner >= 0)) {
        owner[i] = parent_owner;
      } else if (role != Role::None && role != Role::Container && role != Role::Storey) {
        owner[i] = int(elements_.size());
        Element e;
        e.type = type, e.role = role, e.name = name_of(n.name, type), e.guid = ifc_guid(n.name);
        if (const auto kind = ifc4_kinds_.find(e.guid); kind != ifc4_kinds_.end()) e.kind = kind->second;
        e.storey = storey_of[i];
        elements_.push_back(std::move(e));
      }
      if (owner[i] < 0 || n.triangles.empty()) continue;
      Element& e = elements_[size_t(owner[i])];
      const int base = int(e.vertices.size());
      for (Vec3 v : n.vertices) e.vertices.push_back(v), e.box.add(v);
      for (const auto& t : n.triangles) e.triangles.push_back({base + t[0], base + t[1], base + t[2]});
      if (!e.coloured && n.coloured) e.colour = n.colour, e.coloured = true;
    }
    for (const std::string& w : scene.warnings) plan_.warnings.push_back(w);
  }

  /// Storey elevations from the floors their spaces stand on (else the bottoms of their
  /// walls, else of anything in them); heights up to the next storey, less the slab.
  void make_storeys() {
    const size_t n = std::max<size_t>(storey_names_.size(), 1);
    if (storey_names_.empty()) storey_names_.push_back("storey 1");  // a model without storeys: one for all
    for (Element& e : elements_)
      if (e.storey < 0) e.storey = 0;
    std::vector<std::vector<double>> space_floor(n), space_top(n), wall_floor(n), any_floor(n), tops(n);
    for (const Element& e : elements_) {
      if (e.triangles.empty()) continue;
      const size_t s = size_t(e.storey);
      if (e.role == Role::Space) space_floor[s].push_back(e.box.lo.z), space_top[s].push_back(e.box.hi.z);
      if (e.role == Role::Wall) wall_floor[s].push_back(e.box.lo.z);
      if (e.role != Role::Skip) any_floor[s].push_back(e.box.lo.z);
      if (e.role == Role::Wall || e.role == Role::Space) tops[s].push_back(e.box.hi.z);
    }
    struct Level {
      size_t node;
      double elevation, room_height;
    };
    std::vector<Level> levels;
    for (size_t s = 0; s < n; ++s) {
      const std::vector<double>& floors = !space_floor[s].empty() ? space_floor[s]
                                          : !wall_floor[s].empty() ? wall_floor[s]
                                                                   : any_floor[s];
      if (floors.empty()) {
        plan_.warnings.push_back("storey '" + storey_names_[s] + "' dropped: nothing in it has geometry");
        continue;
      }
      const double elevation = median(floors);
      double height = !space_top[s].empty() ? median(space_top[s]) - elevation
                                             : (tops[s].empty() ? 2.5 : median(tops[s]) - elevation);
      levels.push_back({s, elevation, std::clamp(height, 2.0, 12.0)});
    }
    if (levels.empty()) throw PlanError({path_, 0, 0, ""}, "the model has no geometry Avenues can use");
    std::sort(levels.begin(), levels.end(), [](const Level& a, const Level& b) { return a.elevation < b.elevation; });
    // Storeys closer than 1 m apart (two levels of one floor) are one storey: the plan's
    // storeys are bands one can stand in (a crawl space of 1.2 m still is one).
    std::vector<Level> kept;
    storey_index_.assign(n, -1);
    for (const Level& l : levels) {
      if (!kept.empty() && l.elevation - kept.back().elevation < 1.0) {
        plan_.warnings.push_back("storey '" + storey_names_[l.node] + "' joined to '" + storey_names_[kept.back().node] +
                                 "': its floor is " + format_number(l.elevation - kept.back().elevation) + " m above");
        storey_index_[l.node] = int(kept.size()) - 1;
        continue;
      }
      storey_index_[l.node] = int(kept.size());
      kept.push_back(l);
    }
    for (size_t i = 0; i < kept.size(); ++i) {
      Storey st;
      st.name = storey_names_[kept[i].node];
      st.where = {path_, 0, 0, "IfcBuildingStorey '" + st.name + "'"};
      st.elevation = kept[i].elevation;
      if (i + 1 < kept.size()) {
        const double gap = kept[i + 1].elevation - kept[i].elevation;
        st.slab = std::clamp(gap - kept[i].room_height, 0.05, std::min(0.6, 0.3 * gap));
        st.height = gap - st.slab;
      } else {
        st.height = kept[i].room_height;
        st.slab = 0.3;
      }
      plan_.storeys.push_back(st);
    }
    for (Element& e : elements_) e.storey = storey_index_[size_t(e.storey)];
  }

  /// The storey whose band holds z (its floor to the next storey's floor).
  int storey_at(double z) const {
    int best = 0;
    for (size_t i = 0; i < plan_.storeys.size(); ++i)
      if (z >= plan_.storeys[i].elevation - 0.05) best = int(i);
    return best;
  }

  MaterialId material_of(const Element& e) {
    if (!e.coloured) return -1;
    const std::array<int, 3> key{int(std::lround(e.colour[0] * 255)), int(std::lround(e.colour[1] * 255)),
                                 int(std::lround(e.colour[2] * 255))};
    auto [it, fresh] = materials_.emplace(key, MaterialId(plan_.materials.size()));
    if (fresh) {
      Material m;
      m.name = "IFC colour " + std::to_string(key[0]) + "," + std::to_string(key[1]) + "," + std::to_string(key[2]);
      m.colour = e.colour;
      m.where = {path_, 0, 0, e.label()};
      plan_.materials.push_back(m);
    }
    return it->second;
  }

  /// Walls and columns: the rectangle around the footprint, on each storey whose band it
  /// spans at least half of (or 1 m of), and on the storey whose floor it stands on however
  /// low it is (a parapet, a half wall). One that stands on no storey's floor but lies in
  /// one storey's band (a bulkhead hanging from a ceiling, a wall over a window band) is a
  /// wall of that storey with a gap beneath it along its whole length, from the floor to
  /// its foot: cut out of the free space, so that it hides what is behind it and a walker
  /// passes under it only where a person could. Any other is an object: drawn, opaque, not
  /// cut out of the free space.
  void make_walls() {
    on_grid_ = drawn_on_grid();
    for (size_t i = 0; i < elements_.size(); ++i) {
      Element& e = elements_[i];
      if (e.role != Role::Wall) continue;
      if (e.triangles.empty()) {
        drop(e, "no geometry");
        continue;
      }
      const std::optional<Rect> r = min_area_rect(convex_hull(footprint_points(e)));
      if (!r || r->length < kMinWall || r->width <= 1e-4) {
        e.as_object = true;  // a flat or tiny piece: drawn, nothing to walk around
        continue;
      }
      const std::vector<WallPiece> pieces = wall_pieces(e, *r);
      if (pieces.empty()) {
        plan_.warnings.push_back(e.label() + " drawn as an object: its footprint (" +
                                 format_number("%.0f", 100 * r->fill) +
                                 "% of its rectangle) is not a straight wall and its section does not close");
        e.as_object = true;
        continue;
      }
      // A single straight piece may slope on top (a gable wall under a pitched roof).
      std::vector<Vec2> profile;
      if (pieces.size() == 1 && pieces[0].footprint.empty()) profile = top_profile(e, pieces[0].rect);
      if (!slopes(profile)) profile.clear();
      bool placed = false;
      for (size_t s = 0; s < plan_.storeys.size(); ++s) {
        const Storey& st = plan_.storeys[s];
        const double z0 = e.box.lo.z, z1 = e.box.hi.z;
        const double lo = std::max(z0, st.elevation), hi = std::min(z1, st.elevation + st.height);
        const bool spans = hi - lo >= std::min(1.0, 0.5 * st.height);
        const bool stands = std::fabs(z0 - st.elevation) <= kOnFloor && hi - lo >= kMinWall;
        if (!spans && !stands) continue;
        for (size_t k = 0; k < pieces.size(); ++k) {
          wall_shape_.push_back({i, pieces[k].rect, z0, z1});
          plan_.walls.push_back(wall_of_piece(e, pieces, k, s, profile));
        }
        placed = true;
      }
      if (!placed && !hung_wall(i, pieces)) e.as_object = true;
    }
    // The top storey's top: where its walls slope up to its ceiling (gables under a pitched
    // roof, the storey as high as their ridge) and a roof covers it, the roof is its top,
    // not a flat slab. (A model without its roof, Office A's, keeps the slab.)
    if (!plan_.storeys.empty() && roof_over_top_storey()) {
      Storey& top = plan_.storeys.back();
      for (const Wall& w : plan_.walls)
        if (w.storey == StoreyId(plan_.storeys.size() - 1) && w.sloped() && highest_top(w) >= top.height - kOnFloor) {
          top.slab = 0;
          break;
        }
    }
    // What of the top storey's walls rises above its band (its ceiling and slab) stands no
    // storey's band: it is drawn as an object there, not lost.
    if (!plan_.storeys.empty()) {
      const Storey& top = plan_.storeys.back();
      const double band_top = top.elevation + top.height + top.slab;
      std::vector<uint8_t> on_top(elements_.size(), 0);
      for (size_t k = 0; k < plan_.walls.size(); ++k)
        if (size_t(plan_.walls[k].storey) + 1 == plan_.storeys.size()) on_top[wall_shape_[k].element] = 1;
      for (size_t i = 0; i < elements_.size(); ++i)
        if (on_top[i] && !elements_[i].as_object && elements_[i].box.hi.z > band_top + kOnFloor)
          elements_[i].above = band_top;
    }
  }

  /// Whether a roof covers the top storey: elements other than walls, spaces, doors and
  /// windows (an IfcRoof, roof slabs) standing in its band and reaching its ceiling, whose
  /// extents seen from above cover at least half of the walls'.
  bool roof_over_top_storey() const {
    const Storey& top = plan_.storeys.back();
    Box3 walls;
    for (const Element& e : elements_)
      if (e.role == Role::Wall && !e.triangles.empty()) walls.add(e.box.lo), walls.add(e.box.hi);
    const double ceiling = top.elevation + top.height;
    double covered = 0;
    for (const Element& e : elements_) {
      if (e.triangles.empty() || (e.role != Role::Surface && e.role != Role::Object)) continue;
      if (e.box.lo.z < top.elevation - kOnFloor || e.box.hi.z < ceiling - 3 * kOnFloor) continue;
      const double dx = std::min(e.box.hi.x, walls.hi.x) - std::max(e.box.lo.x, walls.lo.x);
      const double dy = std::min(e.box.hi.y, walls.hi.y) - std::max(e.box.lo.y, walls.lo.y);
      if (dx > 0 && dy > 0) covered += dx * dy;
    }
    return covered >= 0.5 * (walls.hi.x - walls.lo.x) * (walls.hi.y - walls.lo.y);
  }

  /// Whether the model's walls are drawn on a 0.1 mm grid (a metric model, as BIM tools
  /// draw them): three in four of their corners' coordinates lie within a single-precision
  /// rounding of it. A model drawn in feet and inches (an eighth of an inch is 3.175 mm)
  /// is not, and is read as it is.
  bool drawn_on_grid() const {
    size_t near = 0, all = 0;
    for (const Element& e : elements_) {
      if (e.role != Role::Wall) continue;
      for (Vec3 v : e.vertices)
        for (double c : {v.x, v.y}) {
          ++all;
          near += on_grid(c).has_value();
        }
    }
    return all > 0 && near >= 0.75 * double(all);
  }

  /// [m] above its floor: the highest point of a sloped wall's top.
  static double highest_top(const Wall& w) {
    double hi = std::max(w.height, w.height_at_end);
    for (Vec2 b : w.top_bends) hi = std::max(hi, b.y);
    return hi;
  }

  /// Piece k of element e's footprint as a wall of storey s, up to the ceiling when the
  /// element reaches it (within 5 cm), else to its top: level, or along `profile` (its top
  /// seen from the side, {along, z}; empty: level) where that falls below the ceiling.
  Wall wall_of_piece(const Element& e, const std::vector<WallPiece>& pieces, size_t k, size_t s,
                     const std::vector<Vec2>& profile = {}) {
    const WallPiece& piece = pieces[k];
    const Storey& st = plan_.storeys[s];
    Wall w;
    w.name = e.name.empty() ? e.guid : e.name;
    if (pieces.size() > 1) w.name += " (" + std::to_string(k + 1) + "/" + std::to_string(pieces.size()) + ")";
    w.storey = StoreyId(s);
    // A wall drawn on a millimetre grid, as BIM tools draw them, read back on it: its
    // coordinates come out of Assimp in single precision, a rounding off the grid, and
    // walls drawn to meet would miss each other by that in slivers of space. Only what lies
    // within such a rounding of a 0.1 mm grid point is moved, and only in a model drawn on
    // the grid (drawn_on_grid: one in feet keeps its own), so no wall's end moves away from
    // another.
    auto snap = [&](double v) { return on_grid_ ? on_grid(v).value_or(v) : v; };
    w.thickness = snap(piece.rect.width);
    const Vec2 half = (piece.rect.length / 2) * piece.rect.along;
    w.centre = {piece.rect.centre - half, piece.rect.centre + half};
    for (Vec2& p : w.centre) p = {snap(p.x), snap(p.y)};
    w.from_arc = {false};
    w.footprint = piece.footprint;
    w.height = e.box.hi.z >= st.elevation + st.height - 0.05 ? -1 : e.box.hi.z - st.elevation;
    double lowest = HUGE_VAL;
    for (Vec2 p : profile) lowest = std::min(lowest, p.y);
    if (!profile.empty() && lowest < st.elevation + st.height - 0.05) {
      auto above_floor = [&](double z) { return std::max(0.0, z - st.elevation); };
      w.height = above_floor(profile.front().y);
      w.height_at_end = above_floor(profile.back().y);
      for (size_t i = 1; i + 1 < profile.size(); ++i)
        if (profile[i].x > 1e-3 && profile[i].x < piece.rect.length - 1e-3)
          w.top_bends.push_back({snap(profile[i].x), above_floor(profile[i].y)});
      if (!w.sloped()) w.height_at_end = -1, w.top_bends.clear();
    }
    w.material = material_of(e);
    w.where = {path_, 0, 0, e.label()};
    return w;
  }

  /// A wall standing on no floor, as a wall of the storey whose band holds it with a gap
  /// beneath it (make_walls); false when no storey's band holds it, or the gap or the wall
  /// would be too low to be one.
  bool hung_wall(size_t i, const std::vector<WallPiece>& pieces) {
    const Element& e = elements_[i];
    const double z0 = e.box.lo.z, z1 = e.box.hi.z;
    const int s = storey_at(z0);
    const Storey& st = plan_.storeys[size_t(s)];
    const double ceiling = st.elevation + st.height;
    const double foot = z0 - st.elevation;
    if (foot < kMinOpening || z0 >= ceiling - kMinWall || z1 > ceiling + st.slab + kOnFloor) return false;
    for (size_t k = 0; k < pieces.size(); ++k) {
      const WallPiece& piece = pieces[k];
      Wall w = wall_of_piece(e, pieces, k, size_t(s));
      Opening gap;
      gap.name = "beneath " + w.name;
      gap.kind = OpeningKind::Gap;
      gap.at = 0;
      gap.width = w.length();
      gap.sill = 0;
      gap.head = foot;
      gap.where = w.where;
      w.openings.push_back(std::move(gap));
      wall_shape_.push_back({i, piece.rect, z0, z1, true});
      plan_.walls.push_back(std::move(w));
    }
    return !pieces.empty();
  }

  /// Doors and windows: an opening in the wall of their storey nearest their centre, as
  /// wide as their points reach along it; overlapping openings in one wall are merged.
  void make_openings() {
    for (const Element& e : elements_) {
      if (e.role != Role::Door && e.role != Role::Window) continue;
      if (e.triangles.empty()) {
        drop(e, "no geometry");
        continue;
      }
      const int s = storey_at(e.box.lo.z + 0.01);
      const Storey& st = plan_.storeys[size_t(s)];
      const std::vector<Vec2> pts = footprint_points(e);
      const Vec2 c{0.5 * (e.box.lo.x + e.box.hi.x), 0.5 * (e.box.lo.y + e.box.hi.y)};
      int best = -1;
      double best_d = HUGE_VAL;
      for (size_t w = 0; w < plan_.walls.size(); ++w) {
        const Wall& wall = plan_.walls[w];
        if (wall.storey != s || wall_shape_[w].hung) continue;  // a hung wall's gap is its own
        const double d = distance_to_segment(c, wall.centre[0], wall.centre[1]);
        if (d <= wall.thickness / 2 + kDoorReach && d < best_d) best = int(w), best_d = d;
      }
      if (best < 0) {
        drop(e, "it stands in no wall of storey '" + st.name + "'");
        continue;
      }
      Wall& wall = plan_.walls[size_t(best)];
      const Vec2 a = wall.centre[0], dir = wall.centre[1] - wall.centre[0];
      const double len = length(dir);
      double t0 = HUGE_VAL, t1 = -HUGE_VAL;
      for (Vec2 p : pts) {
        const double t = dot(p - a, dir) / len;
        t0 = std::min(t0, t), t1 = std::max(t1, t);
      }
      t0 = std::max(t0, 0.0), t1 = std::min(t1, len);
      const double top = wall.height < 0 ? st.height : std::min(st.height, wall.sloped() ? highest_top(wall) : wall.height);
      Opening o;
      o.name = e.name.empty() ? e.guid : e.name;
      o.kind = e.role == Role::Door ? OpeningKind::Door : OpeningKind::Window;
      o.at = t0;
      o.width = t1 - t0;
      o.sill = std::max(0.0, e.box.lo.z - st.elevation);
      o.head = std::min(top, e.box.hi.z - st.elevation);
      if (o.sill < 0.05) o.sill = 0;
      o.where = {path_, 0, 0, e.label()};
      if (o.width < kMinOpening || o.head - o.sill < kMinOpening) {
        drop(e, "it opens less than " + format_number(kMinOpening) + " m of wall '" + wall.name + "'");
        continue;
      }
      add_opening(wall, std::move(o));
    }
    for (Wall& w : plan_.walls)
      std::sort(w.openings.begin(), w.openings.end(), [](const Opening& a, const Opening& b) { return a.at < b.at; });
  }

  void add_opening(Wall& wall, Opening o) {
    for (Opening& m : wall.openings) {
      if (o.at >= m.at + m.width || m.at >= o.at + o.width) continue;
      plan_.warnings.push_back(o.where.element + ": overlaps " + m.where.element + " in wall '" + wall.name +
                               "': one opening");
      const double end = std::max(m.at + m.width, o.at + o.width);
      m.at = std::min(m.at, o.at);
      m.width = end - m.at;
      m.sill = std::min(m.sill, o.sill);
      m.head = std::max(m.head, o.head);
      if (o.kind == OpeningKind::Door) m.kind = OpeningKind::Door;
      return;
    }
    wall.openings.push_back(std::move(o));
  }

  /// Stairs and ramps: each cuts a stairwell (a floor opening) into the floor of every
  /// storey it climbs to, so that a walker standing on it climbs through; the stair itself
  /// stays an object, drawn. A stair climbs to a storey when its highest tread (the highest
  /// level holding at least kTread of upward faces: a handrail's top is narrower) lies at
  /// most a riser below that storey's floor. The opening is the convex hull of the stair's
  /// points up to that floor, seen from above.
  void make_stairwells() {
    constexpr double kTread = 0.15;   // [m²] of upward faces at one level: a tread, a landing
    constexpr double kRiser = 0.3;    // [m] the last tread may lie this far below the floor it reaches
    constexpr double kClimb = 1.0;    // [m] a stair climbs at least this (else it is a step)
    for (const Element& e : elements_) {
      const bool stair = e.type == "IfcStair" || e.type == "IfcStairFlight" || e.type == "IfcRamp" ||
                         e.type == "IfcRampFlight";
      if (!stair || e.triangles.empty()) continue;
      std::map<long, double> up;  // level [cm] -> area of upward faces there [m²]
      for (const auto& t : e.triangles) {
        const Vec3 p = e.vertices[size_t(t[0])], q = e.vertices[size_t(t[1])], r = e.vertices[size_t(t[2])];
        const Vec3 n = cross(q - p, r - p);
        const double a = 0.5 * length(n);
        if (a < 1e-9 || n.z < 0.98 * 2 * a) continue;
        up[std::lround((p.z + q.z + r.z) / 3 * 100)] += a;
      }
      double tread = -HUGE_VAL;  // the highest level a person stands on
      for (const auto& [level, area] : up)
        if (area >= kTread) tread = std::max(tread, level / 100.0);
      if (tread == -HUGE_VAL) tread = e.box.hi.z;  // no flat treads (a sloped flight): its top
      const double base = e.box.lo.z;
      bool climbs = false;
      for (size_t s = 1; s < plan_.storeys.size(); ++s) {
        const double floor = plan_.storeys[s].elevation;
        if (!(floor >= base + kClimb && floor <= tread + kRiser)) continue;
        std::vector<Vec2> pts;
        for (Vec3 v : e.vertices)
          if (v.z <= floor + 0.05) pts.push_back({v.x, v.y});
        std::vector<Vec2> hull = convex_hull(std::move(pts));  // counter-clockwise
        if (hull.size() < 3 || !(signed_area(hull) > 0.1)) continue;
        FloorOpening f;
        f.name = e.name.empty() ? e.guid : e.name;
        for (int k = 2; std::any_of(plan_.floor_openings.begin(), plan_.floor_openings.end(),
                                    [&](const FloorOpening& g) { return g.storey == StoreyId(s) && g.name == f.name; });
             ++k)
          f.name = (e.name.empty() ? e.guid : e.name) + " (" + std::to_string(k) + ")";
        f.storey = StoreyId(s);
        f.outline = std::move(hull);
        f.where = {path_, 0, 0, e.label()};
        plan_.floor_openings.push_back(std::move(f));
        climbs = true;
      }
      if (!climbs && tread - base >= kClimb)
        plan_.warnings.push_back(e.label() + " climbs " + format_number(tread - base) +
                                 " m but reaches no storey's floor: drawn, not climbable");
    }
  }

  /// Spaces: rooms named as the file names them, labelled at the centre of the largest of
  /// their floor's triangles that lies in no wall.
  void make_rooms() {
    std::map<std::pair<int, std::string>, int> seen;
    for (const Element& e : elements_) {
      if (e.role != Role::Space) continue;
      if (e.triangles.empty()) {
        drop(e, "no geometry");
        continue;
      }
      const int s = storey_at(e.box.lo.z + 0.01);
      // Floor triangles: facing down, at the space's bottom.
      std::vector<std::pair<double, Vec2>> floor;
      double area = 0;
      for (const auto& t : e.triangles) {
        const Vec3 p = e.vertices[size_t(t[0])], q = e.vertices[size_t(t[1])], r = e.vertices[size_t(t[2])];
        const Vec3 n = cross(q - p, r - p);
        const double a = 0.5 * length(n);
        if (a < 1e-6 || std::fabs(n.z) < 0.9 * 2 * a) continue;
        if (std::max({p.z, q.z, r.z}) > e.box.lo.z + 0.05) continue;
        area += a;
        floor.push_back({a, Vec2{(p.x + q.x + r.x) / 3, (p.y + q.y + r.y) / 3}});
      }
      std::sort(floor.begin(), floor.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
      std::optional<Vec2> label;
      for (const auto& [a, c] : floor) {
        bool in_wall = false;
        for (size_t w = 0; w < plan_.walls.size() && !in_wall; ++w)
          in_wall = plan_.walls[w].storey == s && in_rect(wall_shape_[w].rect, c, 0.02);
        if (!in_wall) {
          label = c;
          break;
        }
      }
      if (!label) {
        drop(e, "no point of its floor lies outside the walls");
        continue;
      }
      Room room;
      // Its LongName ("Foyer") where the model gives one, else its Name ("A101").
      const auto named = names_.find(e.guid);
      room.name = named != names_.end() && !named->second.long_name.empty() ? named->second.long_name
                  : e.name.empty()                                          ? e.guid
                                                                            : e.name;
      const int copies = seen[{s, room.name}]++;
      if (copies > 0) room.name += " (" + std::to_string(copies + 1) + ")";
      room.storey = s;
      room.label = label;
      room.where = {path_, 0, 0, e.label()};
      room_area_.push_back(area);
      plan_.rooms.push_back(std::move(room));
    }
  }

  /// Slabs and coverings: each room's floor takes the colour of the highest surface facing
  /// up under its label at its storey's floor (a finish floor over the structural slab),
  /// its ceiling that of the lowest facing down over it at its ceiling (a suspended
  /// ceiling under the slab above). A slab or covering that is no room's floor or ceiling
  /// (a roof slab, a landing, a terrace outside the walls) is an object.
  void make_surfaces() {
    struct Best {
      double z;
      size_t element;
    };
    std::vector<std::optional<Best>> floor(plan_.rooms.size()), ceiling(plan_.rooms.size());
    for (size_t i = 0; i < elements_.size(); ++i) {
      const Element& e = elements_[i];
      if (e.role != Role::Surface || e.triangles.empty()) continue;
      for (const auto& t : e.triangles) {
        const Vec3 p = e.vertices[size_t(t[0])], q = e.vertices[size_t(t[1])], r = e.vertices[size_t(t[2])];
        const Vec3 n = cross(q - p, r - p);
        const double a = length(n);
        if (a < 1e-9 || std::fabs(n.z) < 0.9 * a) continue;  // not flat
        const bool up = n.z > 0;
        const double z = (p.z + q.z + r.z) / 3;
        const Vec2 p2{p.x, p.y}, q2{q.x, q.y}, r2{r.x, r.y};
        for (size_t k = 0; k < plan_.rooms.size(); ++k) {
          const Room& room = plan_.rooms[k];
          const Storey& st = plan_.storeys[size_t(room.storey)];
          if (up ? std::fabs(z - st.elevation) > kOnFloor
                 : z < st.elevation + 0.5 * st.height || z > st.elevation + st.height + st.slab + kOnFloor)
            continue;
          if (!in_triangle(*room.label, p2, q2, r2)) continue;
          std::optional<Best>& best = up ? floor[k] : ceiling[k];
          if (!best || (up ? z > best->z : z < best->z)) best = Best{z, i};
        }
      }
    }
    std::vector<bool> used(elements_.size(), false);
    for (size_t k = 0; k < plan_.rooms.size(); ++k) {
      if (floor[k]) plan_.rooms[k].floor = material_of(elements_[floor[k]->element]), used[floor[k]->element] = true;
      if (ceiling[k])
        plan_.rooms[k].ceiling = material_of(elements_[ceiling[k]->element]), used[ceiling[k]->element] = true;
    }
    for (size_t i = 0; i < elements_.size(); ++i)
      if (elements_[i].role == Role::Surface && !used[i]) elements_[i].as_object = true;
  }

  /// Everything else with a surface: an object with its own mesh, standing on its storey.
  void make_objects() {
    for (const Element& e : elements_) {
      if (e.above < HUGE_VAL) add_part_above(e);
      if ((e.role != Role::Object && !e.as_object) || e.triangles.empty()) continue;
      std::vector<std::vector<int>> polygons;
      polygons.reserve(e.triangles.size());
      for (const auto& t : e.triangles) polygons.push_back({t[0], t[1], t[2]});
      add_object(e, "", storey_at(e.box.lo.z + 0.01), e.vertices, std::move(polygons));
    }
  }

  /// Element e's polygons over vertices v (world [m]) as an object of storey s, its name
  /// and mesh key marked with `part` ("" for the whole element).
  void add_object(const Element& e, const std::string& part, int s, std::vector<Vec3> v,
                  std::vector<std::vector<int>> polygons) {
    const double floor = plan_.storeys[size_t(s)].elevation;
    for (Vec3& p : v) p.z -= floor;
    Object o;
    o.name = (e.name.empty() ? e.guid : e.name) + (part.empty() ? "" : " (" + part + ")");
    o.mesh = path_ + ":" + e.guid + (part.empty() ? "" : ":" + part);
    o.storey = s;
    o.model = std::make_shared<const Mesh>(mesh_of_polygons(o.mesh, std::move(v), std::move(polygons)));
    o.material = material_of(e);
    o.where = {path_, 0, 0, e.label()};
    plan_.objects.push_back(std::move(o));
  }

  /// The part of wall e above e.above (the top storey's band), cut there, as an object of
  /// the top storey.
  void add_part_above(const Element& e) {
    const double cut = e.above;
    // Corners shared as the element shares them, and each cut edge's point made once (from
    // its ends in one order), so the part is as closed as the wall was.
    std::vector<Vec3> v;
    std::vector<int> kept(e.vertices.size(), -1);
    std::map<std::pair<int, int>, int> cut_at;
    auto corner = [&](int i) {
      if (kept[size_t(i)] < 0) kept[size_t(i)] = int(v.size()), v.push_back(e.vertices[size_t(i)]);
      return kept[size_t(i)];
    };
    auto crossing = [&](int i, int j) {
      if (i > j) std::swap(i, j);
      auto [it, fresh] = cut_at.try_emplace({i, j}, int(v.size()));
      if (fresh) {
        const Vec3 a = e.vertices[size_t(i)], b = e.vertices[size_t(j)];
        const double f = (cut - a.z) / (b.z - a.z);
        v.push_back({a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), cut});
      }
      return it->second;
    };
    std::vector<std::vector<int>> polygons;
    for (const auto& t : e.triangles) {
      std::vector<int> poly;
      for (int k = 0; k < 3; ++k) {
        const int i = t[size_t(k)], j = t[size_t((k + 1) % 3)];
        const double za = e.vertices[size_t(i)].z, zb = e.vertices[size_t(j)].z;
        if (za >= cut) poly.push_back(corner(i));
        if ((za < cut) != (zb < cut)) poly.push_back(crossing(i, j));
      }
      if (poly.size() >= 3) polygons.push_back(std::move(poly));
    }
    if (!polygons.empty())
      add_object(e, "above the top storey", int(plan_.storeys.size()) - 1, std::move(v), std::move(polygons));
  }

  /// The first view: at eye height in the largest named space of the entrance storey (the
  /// storey with rooms whose floor is nearest z = 0), looking the way the walls leave
  /// most room.
  void make_view() {
    int best = -1;
    for (size_t r = 0; r < plan_.rooms.size(); ++r) {
      if (best < 0) {
        best = int(r);
        continue;
      }
      const double ze = std::fabs(plan_.storeys[size_t(plan_.rooms[r].storey)].elevation);
      const double zb = std::fabs(plan_.storeys[size_t(plan_.rooms[size_t(best)].storey)].elevation);
      if (ze < zb - 0.5 || (ze < zb + 0.5 && plan_.rooms[r].storey == plan_.rooms[size_t(best)].storey &&
                            room_area_[r] > room_area_[size_t(best)]))
        best = int(r);
      else if (ze < zb + 0.5 && plan_.rooms[r].storey != plan_.rooms[size_t(best)].storey && ze < zb)
        best = int(r);
    }
    if (best < 0) {
      // No spaces: outside the building, south of it, looking at its middle.
      Box3 b;
      for (const WallShape& w : wall_shape_) b.add({w.rect.centre.x, w.rect.centre.y, w.z0}), b.add({w.rect.centre.x, w.rect.centre.y, w.z1});
      if (wall_shape_.empty()) return;
      const Vec3 mid{0.5 * (b.lo.x + b.hi.x), 0.5 * (b.lo.y + b.hi.y), plan_.storeys.front().elevation + kEyeHeight};
      const double reach = std::clamp(std::max(b.hi.x - b.lo.x, b.hi.y - b.lo.y), 5.0, 0.5 * plan_.far_margin);
      plan_.view = Viewpoint{{mid.x, b.lo.y - reach, mid.z}, mid, 60};
      return;
    }
    const Room& room = plan_.rooms[size_t(best)];
    const Storey& st = plan_.storeys[size_t(room.storey)];
    const Vec2 eye = *room.label;
    double longest = -1;
    Vec2 look = eye + Vec2{1, 0};
    for (int k = 0; k < 72; ++k) {
      const double a = 2 * std::numbers::pi * k / 72;
      const Vec2 d{std::cos(a), std::sin(a)};
      double free = 50;
      for (size_t w = 0; w < plan_.walls.size(); ++w)
        if (plan_.walls[w].storey == room.storey) free = std::min(free, ray_to_rect(wall_shape_[w].rect, eye, d));
      if (free > longest) longest = free, look = eye + free * d;
    }
    const double z = st.elevation + std::min(kEyeHeight, 0.7 * st.height);
    plan_.view = Viewpoint{{eye.x, eye.y, z}, {look.x, look.y, z}, 60};
  }

  std::string path_;
  Plan plan_;
  std::vector<Element> elements_;
  std::vector<std::string> storey_names_;  ///< per IfcBuildingStorey node, in file order
  std::vector<int> storey_index_;          ///< per node storey: its Plan storey
  bool on_grid_ = false;                   ///< the walls are drawn on a 0.1 mm grid (drawn_on_grid)
  std::vector<WallShape> wall_shape_;      ///< per Plan wall
  std::vector<double> room_area_;          ///< per Plan room [m²]
  std::vector<std::string> dropped_;
  std::map<std::string, IfcRootNames> names_;  ///< GlobalId -> the file's own names (spaces kept)
  std::string for_assimp_;  ///< the STEP text Assimp reads instead of the file, where it differs (ifc4_for_assimp.h)
  std::map<std::string, std::string> ifc4_kinds_;  ///< GlobalId -> IFC4 kind, for products Assimp read as another
  std::vector<std::string> rewrite_left_out_;  ///< what ifc4_for_assimp left out whole, as it said it (the first few)
  size_t rewrite_left_out_count_ = 0;         ///< and how many records in all
  std::map<std::array<int, 3>, MaterialId> materials_;
};

}  // namespace

Plan read_ifc_building(const std::string& path, std::vector<StageTime>* stages) {
  const auto t0 = std::chrono::steady_clock::now();
  Builder b(path);
  Plan plan = b.build();
  if (stages) {
    const double total = seconds_since(t0);
    stages->push_back({"assimp import", b.import_seconds});
    stages->push_back({"IFC to plan", total - b.import_seconds});
  }
  return plan;
}

}  // namespace avenues
