// Avenues — the small out-of-line pieces of plan.h: how a source location prints, the
// names of opening kinds, the rule of a wall's centre line (find_self_crossing) and a plan
// moved. The reader itself is plan_reader.cpp.
#include "plans/plan.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace avenues {

namespace {

/// Sign of the turn a→b→c: > 0 left (counter-clockwise), < 0 right, 0 collinear.
double orient(Vec2 a, Vec2 b, Vec2 c) { return cross(b - a, c - a); }

/// Is c, known collinear with a–b, within the segment's bounding box?
bool within(Vec2 a, Vec2 b, Vec2 c) {
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}

/// Do closed segments p1–p2 and q1–q2 share any point (touching counts)?
bool segments_meet(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2) {
  const double d1 = orient(q1, q2, p1), d2 = orient(q1, q2, p2);
  const double d3 = orient(p1, p2, q1), d4 = orient(p1, p2, q2);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  return (d1 == 0 && within(q1, q2, p1)) || (d2 == 0 && within(q1, q2, p2)) ||
         (d3 == 0 && within(p1, p2, q1)) || (d4 == 0 && within(p1, p2, q2));
}

}  // namespace

// (find_self_crossing: plan.h.) A sweep over x keeps it near n log n for long tessellated walls.
std::pair<int, int> find_self_crossing(const std::vector<Vec2>& pts, bool closed) {
  const int n = static_cast<int>(pts.size()) - 1;  // segments i: pts[i] → pts[i+1]
  auto neighbours = [&](int i, int j) {  // i < j
    return j == i + 1 || (closed && i == 0 && j == n - 1);
  };
  // Neighbours share a vertex; they only "cross" if they fold back onto each other.
  for (int i = 0; i < n; ++i) {
    const int j = i + 1 < n ? i + 1 : (closed ? 0 : -1);
    if (j < 0 || j == i) continue;
    const Vec2 a = pts[i + 1] - pts[i], b = pts[j + 1] - pts[j];
    if (std::fabs(cross(a, b)) <= 1e-12 * length(a) * length(b) && dot(a, b) < 0)
      return {std::min(i, j), std::max(i, j)};
  }
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  auto xlo = [&](int i) { return std::min(pts[i].x, pts[i + 1].x); };
  auto xhi = [&](int i) { return std::max(pts[i].x, pts[i + 1].x); };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return xlo(a) < xlo(b); });
  for (int oi = 0; oi < n; ++oi) {
    const int i = order[oi];
    for (int oj = oi + 1; oj < n && xlo(order[oj]) <= xhi(i); ++oj) {
      const int j = order[oj];
      const int a = std::min(i, j), b = std::max(i, j);
      if (neighbours(a, b)) continue;
      if (segments_meet(pts[a], pts[a + 1], pts[b], pts[b + 1])) return {a, b};
    }
  }
  return {-1, -1};
}

// "house.toml:12:3 (wall 'north')", leaving out whatever is unknown: a generated plan
// has no file and no line, so its elements print as just "(wall 'north')" → "wall 'north'".
std::string SourceLoc::str() const {
  std::string s = file;
  if (line > 0) {
    if (!s.empty()) s += ':';
    s += std::to_string(line);
    if (column > 0) s += ':' + std::to_string(column);
  }
  if (!element.empty()) s += s.empty() ? element : " (" + element + ")";
  return s;
}

// The spelling used in plan files (`kind = "door"`), so messages can quote it back.
const char* to_string(OpeningKind k) {
  switch (k) {
    case OpeningKind::Door: return "door";
    case OpeningKind::Window: return "window";
    case OpeningKind::Hatch: return "hatch";
    case OpeningKind::Gap: return "gap";
  }
  return "?";
}

double Wall::length() const {
  double total = 0;
  for (size_t i = 0; i + 1 < centre.size(); ++i) total += avenues::length(centre[i + 1] - centre[i]);
  return total;
}

bool Wall::sloped() const {
  if (height < 0 || height_at_end < 0) return false;
  double last = height;
  for (Vec2 b : top_bends) {
    if (b.y != last) return true;
    last = b.y;
  }
  return height_at_end != last;
}

double Wall::top_at(double along) const {
  if (height < 0 || height_at_end < 0) return height;
  double s0 = 0, z0 = height;
  auto between = [&](double s1, double z1) { return s1 > s0 ? z0 + (z1 - z0) * (along - s0) / (s1 - s0) : z1; };
  for (Vec2 b : top_bends) {
    if (along <= b.x) return between(b.x, b.y);
    s0 = b.x, z0 = b.y;
  }
  return between(length(), height_at_end);
}

Plan moved(Plan p, Vec2 by) {
  for (Wall& w : p.walls)
    for (Vec2& v : w.centre) v = v + by;
  for (FloorOpening& f : p.floor_openings)
    for (Vec2& v : f.outline) v = v + by;
  for (Room& r : p.rooms)
    if (r.label) r.label = *r.label + by;
  for (Object& o : p.objects) o.position = o.position + Vec3{by.x, by.y, 0};
  for (Light& l : p.lights) l.position = l.position + Vec3{by.x, by.y, 0};
  if (p.view) {
    p.view->eye = p.view->eye + Vec3{by.x, by.y, 0};
    p.view->look = p.view->look + Vec3{by.x, by.y, 0};
  }
  p.name += " (far from the origin)";
  return p;
}

double fov_deg_of_vertical(double vertical_rad) {
  return std::clamp(2 * std::atan(std::tan(vertical_rad / 2) * 16 / 9) * 180 / std::numbers::pi, 40.0, 120.0);
}

}  // namespace avenues
