// Avenues — reading Crow's tables 1a and 1b (see crow.h); the scene of one is crow_scene.cpp.
#include "cells/crow.h"
#include "plans/polygon_triangulation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace avenues {

namespace {

/// One line of the file that says something: its number and its words.
struct Line {
  int number = 0;  ///< 1-based
  std::vector<std::string> words;
};

/// The lines with words, comments ("(...)" and "# ...") taken out.
std::vector<Line> significant_lines(const std::string& text, const std::string& name) {
  std::vector<Line> out;
  std::istringstream in(text);
  std::string raw;
  for (int number = 1; std::getline(in, raw); ++number) {
    std::string kept;
    int depth = 0;
    for (char ch : raw) {
      if (ch == '#' && depth == 0) break;
      if (ch == '(') ++depth;
      else if (ch == ')') {
        if (depth == 0) throw PlanError({name, number, 0, ""}, "')' without '('");
        --depth;
      } else if (depth == 0) kept += ch;
    }
    if (depth != 0) throw PlanError({name, number, 0, ""}, "'(' without ')'");
    Line l{number, {}};
    std::istringstream words(kept);
    for (std::string w; words >> w;) l.words.push_back(w);
    if (!l.words.empty()) out.push_back(std::move(l));
  }
  return out;
}

bool parse_number(const std::string& w, double& x) {
  const char* s = w.c_str();
  char* end = nullptr;
  x = std::strtod(s, &end);
  return end != s && *end == '\0' && std::isfinite(x);
}

bool parse_count(const std::string& w, long& n) {
  if (w.empty() || w.size() > 9 || w.find_first_not_of("0123456789") != std::string::npos) return false;
  n = std::strtol(w.c_str(), nullptr, 10);
  return true;
}

bool is_command(const std::string& w) { return w == "m" || w == "M" || w == "d" || w == "D"; }

/// "x y z" from words[first..first+2] of a line.
Vec3 coordinates(const Line& l, size_t first, const std::string& name, const std::string& element) {
  double xyz[3];
  for (size_t k = 0; k < 3; ++k)
    if (!parse_number(l.words[first + k], xyz[k]))
      throw PlanError({name, l.number, 0, element}, "'" + l.words[first + k] + "' is not a number");
  return {xyz[0], xyz[1], xyz[2]};
}

/// Table 1a, from `start` (the line after a count, or the first line).
void read_lines(const std::vector<Line>& lines, size_t start, long count, int count_line, const std::string& name,
                CrowObject& o) {
  std::map<std::tuple<double, double, double>, int> index;
  for (size_t i = start; i < lines.size(); ++i) {
    const Line& l = lines[i];
    const std::string element = "point " + std::to_string(i - start + 1);
    if (l.words.size() != 4 || !is_command(l.words[0]))
      throw PlanError({name, l.number, 0, element}, "expected 'm x y z' (move to) or 'd x y z' (draw to)");
    const Vec3 p = coordinates(l, 1, name, element);
    auto [it, fresh] = index.try_emplace({p.x, p.y, p.z}, int(o.points.size()));
    if (fresh) o.points.push_back(p);
    const bool move = l.words[0] == "m" || l.words[0] == "M";
    if (move) {
      o.polylines.push_back({it->second});
    } else {
      if (o.polylines.empty()) throw PlanError({name, l.number, 0, element}, "draws before any move: where from?");
      o.polylines.back().push_back(it->second);
    }
  }
  const long found = long(lines.size() - start);
  if (count >= 0 && found != count)
    throw PlanError({name, count_line, 0, ""}, "says " + std::to_string(count) + " points but " + std::to_string(found) +
                                                   " follow");
  if (found == 0) throw PlanError({name, count_line, 0, ""}, "has no points");
  std::erase_if(o.polylines, [](const std::vector<int>& p) { return p.size() < 2; });  // a move alone draws nothing
}

/// Table 1b: the header, the numbered points, the polygons.
void read_polygons(const std::vector<Line>& lines, const std::string& name, CrowObject& o) {
  const Line& head = lines[0];
  long npts = 0, npolys = 0;
  if (head.words.size() != 2 || !parse_count(head.words[0], npts) || !parse_count(head.words[1], npolys) || npts < 3 ||
      npolys < 1)
    throw PlanError({name, head.number, 0, ""}, "expected 'NumPts NumPolys' (at least 3 points and 1 polygon)");
  const int last = lines.back().number;
  if (lines.size() < size_t(1 + npts + npolys)) {
    const long have = long(lines.size()) - 1;
    const std::string what = have < npts ? std::to_string(have) + " of " + std::to_string(npts) + " points"
                                         : std::to_string(have - npts) + " of " + std::to_string(npolys) + " polygons";
    throw PlanError({name, last, 0, ""}, "ends after " + what);
  }
  for (long j = 1; j <= npts; ++j) {
    const Line& l = lines[size_t(j)];
    const std::string element = "point " + std::to_string(j);
    long number = 0;
    if (l.words.size() != 4) throw PlanError({name, l.number, 0, element}, "expected 'J X Y Z'");
    if (!parse_count(l.words[0], number) || number != j)
      throw PlanError({name, l.number, 0, element}, "numbered '" + l.words[0] + "' where " + std::to_string(j) + " was expected");
    o.points.push_back(coordinates(l, 1, name, element));
  }
  for (long k = 1; k <= npolys; ++k) {
    const Line& l = lines[size_t(npts + k)];
    const std::string element = "polygon " + std::to_string(k);
    long n = 0;
    if (!parse_count(l.words[0], n) || n < 3)
      throw PlanError({name, l.number, 0, element}, "expected a vertex count of at least 3, found '" + l.words[0] + "'");
    if (long(l.words.size()) != n + 1)
      throw PlanError({name, l.number, 0, element},
                      "says " + std::to_string(n) + " vertices but lists " + std::to_string(l.words.size() - 1));
    std::vector<int> poly;
    for (long i = 1; i <= n; ++i) {
      long p = 0;
      if (!parse_count(l.words[size_t(i)], p) || p < 1 || p > npts)
        throw PlanError({name, l.number, 0, element},
                        "'" + l.words[size_t(i)] + "' is not a point number from 1 to " + std::to_string(npts));
      if (std::find(poly.begin(), poly.end(), int(p - 1)) != poly.end())
        throw PlanError({name, l.number, 0, element}, "uses point " + std::to_string(p) + " twice");
      poly.push_back(int(p - 1));
    }
    o.polygons.push_back(std::move(poly));
  }
  if (lines.size() > size_t(1 + npts + npolys))
    throw PlanError({name, lines[size_t(1 + npts + npolys)].number, 0, ""},
                    "more lines than the header's " + std::to_string(npts) + " points and " + std::to_string(npolys) +
                        " polygons");
}

}  // namespace

CrowObject parse_crow(const std::string& text, const std::string& name) {
  const std::vector<Line> lines = significant_lines(text, name);
  if (lines.empty()) throw PlanError({name, 0, 0, ""}, "is empty: neither Crow's table 1a nor 1b");
  CrowObject o;
  o.path = name;
  const Line& first = lines[0];
  long count = 0;
  if (is_command(first.words[0])) {
    o.table = CrowObject::Table::Lines;
    read_lines(lines, 0, -1, first.number, name, o);
  } else if (first.words.size() == 1 && parse_count(first.words[0], count)) {
    o.table = CrowObject::Table::Lines;  // listing 1's count of points, then the commands
    read_lines(lines, 1, count, first.number, name, o);
  } else if (first.words.size() == 2) {
    o.table = CrowObject::Table::Polygons;
    read_polygons(lines, name, o);
  } else {
    throw PlanError({name, first.number, 0, ""},
                    "neither a move/draw command (table 1a), a count of points, nor 'NumPts NumPolys' (table 1b)");
  }
  return o;
}

CrowObject read_crow(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || !std::filesystem::is_regular_file(path)) throw std::runtime_error("cannot read Crow object " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return parse_crow(text.str(), path);
}

Mesh crow_mesh(const CrowObject& o) {
  if (o.polygons.empty())
    throw PlanError({o.path, 0, 0, ""}, "has no polygons (a line list, table 1a, has no surfaces)");
  Mesh m;
  m.path = o.path;
  m.vertices = o.points;
  for (size_t k = 0; k < o.polygons.size(); ++k) {
    // Crow lists polygons clockwise seen from outside; a Mesh wants counter-clockwise.
    std::vector<int> poly(o.polygons[k].rbegin(), o.polygons[k].rend());
    std::vector<std::array<int, 3>> cut = triangulate_polygon(m.vertices, poly);
    if (cut.empty())  // no area: a fan keeps every vertex (its triangles are dropped later, with a warning)
      for (size_t i = 1; i + 1 < poly.size(); ++i) cut.push_back({poly[0], poly[i], poly[i + 1]});
    for (const auto& t : cut) {
      m.triangles.push_back(t);
      m.polygon_of.push_back(int(k));
    }
  }
  smooth_corner_normals(m);
  m.boundary_edges = boundary_edges(o.polygons);
  m.closed = m.boundary_edges == 0;
  return m;
}

std::vector<RealLine> crow_lines(const CrowObject& o) {
  std::vector<RealLine> out;
  auto add = [&](int a, int b) {
    if (o.points[size_t(a)] == o.points[size_t(b)]) return;
    out.push_back({o.points[size_t(a)], o.points[size_t(b)], LineKind::Convex});
  };
  for (const auto& pl : o.polylines)
    for (size_t i = 0; i + 1 < pl.size(); ++i) add(pl[i], pl[i + 1]);
  std::map<std::pair<int, int>, bool> done;
  for (const auto& poly : o.polygons)
    for (size_t i = 0; i < poly.size(); ++i) {
      const int a = poly[i], b = poly[(i + 1) % poly.size()];
      if (!done.try_emplace({std::min(a, b), std::max(a, b)}, true).second) continue;
      add(a, b);
    }
  return out;
}

}  // namespace avenues
