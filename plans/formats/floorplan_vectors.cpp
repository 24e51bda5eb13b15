// Avenues — Raster-to-Vector floor-plan annotations as a Plan (see floorplan_vectors.h).
#include "plans/formats/floorplan_vectors.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace avenues {
namespace {

struct Segment {
  Vec2 a, b;  ///< [m]
  int line;   ///< 1-based line of the file
};

bool parse_number(const std::string& s, double& out) {
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end != s.c_str() && *end == '\0' && std::isfinite(out);
}

/// The room types of the dataset and the height of each kind of fixture [m].
bool is_room_type(const std::string& c) {
  static const char* const kRooms[] = {"living_room", "kitchen", "bedroom", "bathroom", "restroom",
                                       "washing_room", "closet", "corridor", "balcony", "PS", "office",
                                       "dining_room", "room", "storage", "hall", "toilet_room"};
  for (const char* r : kRooms)
    if (c == r) return true;
  return false;
}
double fixture_height(const std::string& c) {
  static const std::map<std::string, double> kFixtures = {{"bathtub", 0.55},       {"toilet", 0.4},
                                                          {"washing_basin", 0.85}, {"cooking_counter", 0.9},
                                                          {"special", 1.0},        {"stairs", 0.2}};
  auto it = kFixtures.find(c);
  return it == kFixtures.end() ? -1 : it->second;
}

std::string spaced(std::string s) {
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

/// Parameter along `w` (0 at w.a, in metres) of where segment `v` meets it, if it does
/// (crossing, or an end of either within `tol` of the other); parallel segments do not.
bool meets_at(const Segment& w, const Segment& v, double tol, double& s) {
  const Vec2 d = w.b - w.a, e = v.b - v.a;
  const double den = cross(d, e), len = length(d);
  if (std::fabs(den) <= 1e-9 * len * length(e)) return false;
  const double t = cross(v.a - w.a, e) / den;  // on w, in [0, 1]
  const double u = cross(v.a - w.a, d) / den;  // on v
  const double tol_w = tol / len, tol_v = tol / length(e);
  if (t < -tol_w || t > 1 + tol_w || u < -tol_v || u > 1 + tol_v) return false;
  s = t * len;
  return true;
}

}  // namespace

bool looks_like_floorplan_vectors(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string t; ls >> t;) tok.push_back(t);
    if (tok.empty()) continue;
    double v = 0;
    if (tok.size() < 5) return false;
    for (int i = 0; i < 4; ++i)
      if (!parse_number(tok[size_t(i)], v)) return false;
    return std::isalpha(static_cast<unsigned char>(tok[4][0])) != 0;
  }
  return false;
}

Plan read_floorplan_vectors(const std::string& path, const FloorplanVectorOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PlanError({path, 0, 0, ""}, "cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_floorplan_vectors(text.str(), path, options);
}

Plan parse_floorplan_vectors(const std::string& text, const std::string& name, const FloorplanVectorOptions& opt) {
  if (!(opt.metres_per_pixel > 0) || !std::isfinite(opt.metres_per_pixel))
    throw PlanError({name, 0, 0, ""}, "--scale must be a positive number of metres per pixel");
  if (!(opt.storey_height > 0)) throw PlanError({name, 0, 0, ""}, "--storey-height must be positive");
  const double s = opt.metres_per_pixel, t = opt.wall_thickness;
  auto where = [&](int line, const std::string& element) { return SourceLoc{name, line, 0, element}; };

  Plan plan;
  const size_t slash = name.find_last_of('/');
  plan.name = name.substr(slash == std::string::npos ? 0 : slash + 1);
  plan.source = name;
  plan.lenient = true;
  Storey storey;
  storey.name = "ground";
  storey.height = opt.storey_height;
  storey.where = where(0, "storey");
  plan.storeys.push_back(storey);

  std::vector<Segment> walls, doors;
  std::map<std::string, int> named;  // room type -> labels seen
  std::istringstream in(text);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream ls(line);
    std::vector<std::string> tok;
    for (std::string tk; ls >> tk;) tok.push_back(tk);
    if (tok.empty()) continue;
    double x[4];
    if (tok.size() < 5) throw PlanError(where(n, ""), "expected 'x1 y1 x2 y2 category ...', got " +
                                                          std::to_string(tok.size()) + " fields");
    for (int i = 0; i < 4; ++i)
      if (!parse_number(tok[size_t(i)], x[i]))
        throw PlanError(where(n, ""), "field " + std::to_string(i + 1) + " '" + tok[size_t(i)] + "' is not a number");
    const Vec2 a{x[0] * s, -x[1] * s}, b{x[2] * s, -x[3] * s};
    const std::string& cat = tok[4];
    if (cat == "wall" || cat == "door") {
      if (length(b - a) <= 0) {
        plan.warnings.push_back(where(n, cat).str() + ": a " + cat + " of no length: dropped");
        continue;
      }
      (cat == "wall" ? walls : doors).push_back({a, b, n});
    } else if (is_room_type(cat)) {
      Room r;
      const int k = ++named[cat];
      r.name = spaced(cat) + (k > 1 ? " " + std::to_string(k) : "");
      r.label = Vec2{(a.x + b.x) / 2, (a.y + b.y) / 2};
      r.where = where(n, "room '" + r.name + "'");
      plan.rooms.push_back(r);
    } else if (const double h = fixture_height(cat); h > 0) {
      Object o;
      o.name = spaced(cat) + " " + std::to_string(plan.objects.size() + 1);
      o.position = {(a.x + b.x) / 2, (a.y + b.y) / 2, 0};
      o.box = {std::max(std::fabs(b.x - a.x), 0.05), std::max(std::fabs(b.y - a.y), 0.05), h};
      o.where = where(n, "object '" + o.name + "'");
      plan.objects.push_back(o);
    } else if (cat != "entrance") {
      plan.warnings.push_back(where(n, "'" + cat + "'").str() + ": unknown category: dropped");
    }
  }
  if (walls.empty()) throw PlanError(where(0, ""), "no wall lines ('x1 y1 x2 y2 wall'): not a floor plan");

  // Walls: lengthened by half their thickness at an end that meets another wall, so
  // that two walls meeting at a corner close it.
  const double tol = 1.5 * s;  // annotations are whole pixels
  std::vector<Segment> centre = walls;
  for (size_t i = 0; i < walls.size(); ++i) {
    const Vec2 u = (1 / length(walls[i].b - walls[i].a)) * (walls[i].b - walls[i].a);
    for (int end = 0; end < 2; ++end) {
      const Vec2 p = end == 0 ? walls[i].a : walls[i].b;
      bool meets = false;
      for (size_t j = 0; j < walls.size() && !meets; ++j)
        meets = j != i && distance_to_segment(p, walls[j].a, walls[j].b) <= tol;
      if (meets) (end == 0 ? centre[i].a : centre[i].b) = p + (end == 0 ? -t / 2 : t / 2) * u;
    }
  }
  for (const Segment& c : centre) {
    Wall w;
    w.name = "wall " + std::to_string(plan.walls.size() + 1);
    w.thickness = t;
    w.centre = {c.a, c.b};
    w.from_arc = {false};
    w.where = where(c.line, "wall '" + w.name + "'");
    plan.walls.push_back(w);
  }

  // Doors: the opening of the wall they lie along, clear of the walls that meet it.
  for (const Segment& d : doors) {
    const SourceLoc at = where(d.line, "door");
    int best = -1;
    double best_off = tol;
    for (size_t i = 0; i < centre.size(); ++i) {
      const double off = std::max(distance_to_segment(d.a, walls[i].a, walls[i].b),
                                  distance_to_segment(d.b, walls[i].a, walls[i].b));
      if (off <= best_off) best = int(i), best_off = off;
    }
    if (best < 0) {
      plan.warnings.push_back(at.str() + ": lies on no wall: dropped");
      continue;
    }
    const Segment& c = centre[size_t(best)];
    const double len = length(c.b - c.a);
    const Vec2 u = (1 / len) * (c.b - c.a);
    double lo = std::clamp(std::min(dot(d.a - c.a, u), dot(d.b - c.a, u)), 0.0, len);
    double hi = std::clamp(std::max(dot(d.a - c.a, u), dot(d.b - c.a, u)), 0.0, len);
    // The free pieces of [lo, hi] between the walls that cross or abut this one.
    std::vector<std::pair<double, double>> blocked;
    for (size_t j = 0; j < walls.size(); ++j) {
      double at_s = 0;
      if (int(j) != best && meets_at(c, walls[j], tol, at_s))
        blocked.push_back({at_s - t / 2 - 0.01, at_s + t / 2 + 0.01});
    }
    std::sort(blocked.begin(), blocked.end());
    double piece_lo = lo, best_lo = 0, best_hi = 0;
    for (const auto& [b0, b1] : blocked) {
      if (b0 > piece_lo && std::min(b0, hi) - piece_lo > best_hi - best_lo) best_lo = piece_lo, best_hi = std::min(b0, hi);
      piece_lo = std::max(piece_lo, b1);
    }
    if (hi - piece_lo > best_hi - best_lo) best_lo = piece_lo, best_hi = hi;
    if (best_hi - best_lo < 0.3) {
      plan.warnings.push_back(at.str() + ": no room for it in wall '" + plan.walls[size_t(best)].name +
                              "' between the walls that meet it: dropped");
      continue;
    }
    if (best_hi - best_lo < hi - lo - t - 0.03)  // more than the jambs' half walls
      plan.warnings.push_back(at.str() + ": narrowed to keep clear of a wall that meets wall '" +
                              plan.walls[size_t(best)].name + "'");
    Opening o;
    o.kind = OpeningKind::Door;
    o.at = best_lo;
    o.width = best_hi - best_lo;
    o.head = std::min(2.1, opt.storey_height);
    o.where = at;
    std::vector<Opening>& os = plan.walls[size_t(best)].openings;
    bool overlaps = false;
    for (const Opening& e : os) overlaps = overlaps || (o.at < e.at + e.width && e.at < o.at + o.width);
    if (overlaps) {
      plan.warnings.push_back(at.str() + ": overlaps another door of wall '" + plan.walls[size_t(best)].name +
                              "': dropped");
      continue;
    }
    o.name = "door " + std::to_string(d.line);
    os.push_back(o);
  }
  return plan;
}

}  // namespace avenues
