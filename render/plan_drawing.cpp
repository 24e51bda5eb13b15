// Avenues — the plan drawing (see plan_drawing.h).
//
// Hand-written SVG. Every length is computed in metres; sizes meant for the page
// (line widths, text, dashes) are given in paper millimetres and converted with the
// drawing's scale, so the picture reads the same at 1:50 as at 1:1000.
#include "render/plan_drawing.h"
#include "render/xml_text.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.h"

namespace avenues {
namespace {

constexpr double kEps = 1e-6;  // [m] coordinates are rounded once from exact values

// --- text helpers ----------------------------------------------------------

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  std::string s = buf;
  if (s.find('.') != std::string::npos) {
    while (!s.empty() && s.back() == '0') s.pop_back();
    if (!s.empty() && s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

std::string hex_colour(double r, double g, double b) {
  auto c = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); };
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c(r), c(g), c(b));
  return buf;
}

/// HSL (h in degrees, s and l in [0,1]) to "#rrggbb".
std::string hsl(double h, double s, double l) {
  double c = (1 - std::fabs(2 * l - 1)) * s;
  double hp = std::fmod(h, 360.0) / 60.0;
  double x = c * (1 - std::fabs(std::fmod(hp, 2.0) - 1));
  double r = 0, g = 0, b = 0;
  if (hp < 1) { r = c; g = x; }
  else if (hp < 2) { r = x; g = c; }
  else if (hp < 3) { g = c; b = x; }
  else if (hp < 4) { g = x; b = c; }
  else if (hp < 5) { r = x; b = c; }
  else { r = c; b = x; }
  double m = l - c / 2;
  return hex_colour(r + m, g + m, b + m);
}

/// A pale colour per room, the same on every run: the golden-ratio sequence of hues
/// keeps rooms with neighbouring ids far apart on the colour wheel.
std::string room_colour(RoomId id, bool named) {
  if (!named) return "#e4e4e4";
  double h = std::fmod(0.13 + 0.618033988749895 * static_cast<double>(id), 1.0) * 360.0;
  return hsl(h, 0.62, 0.86);
}

const char* kDoorwayFill = "#f1e6cf";
const char* kOutsideFill = "#eaf3e6";
const char* kLowFill = "#d4d4d4";
const char* kSolidFill = "#a9a9a9";
const char* kCutStroke = "#1b1b1b";
const char* kEdgeStroke = "#555555";
const char* kOutline = "#9a9a9a";
const char* kDrawingStroke = "#8fb8e0";  // the drawing's own lines, under the plan

struct PortalStyle {
  const char* colour;
  double width_mm;
  double dash_mm, gap_mm;
};
PortalStyle portal_style(PortalKind k) {
  switch (k) {
    case PortalKind::Door: return {"#c0392b", 0.45, 1.6, 0.8};
    case PortalKind::Window: return {"#1f77b4", 0.45, 1.6, 0.8};
    case PortalKind::Hatch: return {"#8e44ad", 0.45, 1.6, 0.8};
    case PortalKind::Gap: return {"#d68910", 0.4, 1.2, 0.8};
    case PortalKind::Stairwell: return {"#2c3e50", 0.3, 1.0, 0.6};
    case PortalKind::Open: return {"#6aa35a", 0.15, 0.6, 0.6};
    case PortalKind::Transparent: default: return {"#7f8c8d", 0.15, 0.6, 0.6};
  }
}

// --- geometry helpers ------------------------------------------------------

struct Seg {
  Vec2 a, b;
};

/// The extent, seen from above, of points lying in one vertical plane with outward
/// normal n: the two extreme points along the plane's horizontal direction.
std::optional<Seg> extent(const std::vector<Vec3>& pts, Vec3 n) {
  if (pts.empty()) return std::nullopt;
  Vec2 d{-n.y, n.x};
  double len = length(d);
  if (len < 1e-9) return std::nullopt;
  d = (1 / len) * d;
  size_t lo = 0, hi = 0;
  double tlo = HUGE_VAL, thi = -HUGE_VAL;
  for (size_t i = 0; i < pts.size(); ++i) {
    double t = dot(Vec2{pts[i].x, pts[i].y}, d);
    if (t < tlo) { tlo = t; lo = i; }
    if (t > thi) { thi = t; hi = i; }
  }
  if (thi - tlo < kEps) return std::nullopt;
  return Seg{{pts[lo].x, pts[lo].y}, {pts[hi].x, pts[hi].y}};
}

/// Where a vertical convex polygon crosses the horizontal plane z = zc.
std::optional<Seg> cut(const std::vector<Vec3>& poly, Vec3 n, double zc) {
  std::vector<Vec3> hits;
  for (size_t i = 0, m = poly.size(); i < m; ++i) {
    Vec3 a = poly[i], b = poly[(i + 1) % m];
    if ((a.z - zc) * (b.z - zc) <= 0 && std::fabs(a.z - b.z) > 1e-12) {
      double t = (zc - a.z) / (b.z - a.z);
      hits.push_back(a + t * (b - a));
    } else if (std::fabs(a.z - zc) < 1e-12) {
      hits.push_back(a);
    }
  }
  return extent(hits, n);
}

/// The bottom edge of a vertical convex polygon, if it lies at height z0.
std::optional<Seg> bottom_edge(const std::vector<Vec3>& poly, Vec3 n, double z0) {
  std::vector<Vec3> low;
  for (Vec3 p : poly)
    if (p.z <= z0 + kEps) low.push_back(p);
  return extent(low, n);
}

bool vertical(const Plane& p) { return std::fabs(p.n.z) < 0.5; }

// --- the drawing -----------------------------------------------------------

struct Frame {        // one storey's panel on the page
  double px = 0, py = 0;     ///< [m] page position of the panel's top-left corner
  double bx0 = 0, by0 = 0;   ///< [m] plan coordinates of the panel's bottom-left corner
  double w = 0, h = 0;       ///< [m]
  double X(double x) const { return px + (x - bx0); }
  double Y(double y) const { return py + (by0 + h - y); }  // y up in the plan, down on the page
};

class Svg {
 public:
  std::string out;
  double k = 0.1;  ///< [m of plan per mm of paper]

  double mm(double v) const { return v * k; }
  void raw(const std::string& s) { out += s; }

  void polygon(const Frame& f, const std::vector<Vec2>& p, const std::string& attrs) {
    out += "<polygon points=\"";
    for (size_t i = 0; i < p.size(); ++i) {
      if (i) out += ' ';
      out += num(f.X(p[i].x));
      out += ',';
      out += num(f.Y(p[i].y));
    }
    out += "\" " + attrs + "/>\n";
  }
  void line(const Frame& f, Seg s, const std::string& attrs) {
    out += "<line x1=\"" + num(f.X(s.a.x)) + "\" y1=\"" + num(f.Y(s.a.y)) + "\" x2=\"" +
           num(f.X(s.b.x)) + "\" y2=\"" + num(f.Y(s.b.y)) + "\" " + attrs + "/>\n";
  }
  void text(double x, double y, double size_mm, const std::string& s, const std::string& attrs = "") {
    out += "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" font-size=\"" + num(mm(size_mm)) + "\"" +
           (attrs.empty() ? "" : " " + attrs) + ">" + xml_escape(s) + "</text>\n";
  }
  void rect(double x, double y, double w, double h, const std::string& attrs) {
    out += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" +
           num(h) + "\" " + attrs + "/>\n";
  }
  /// Stroke attributes; `fill_none` adds fill="none" (not for filled shapes).
  std::string stroke(const char* colour, double width_mm, bool fill_none = true) const {
    std::string a = fill_none ? "fill=\"none\" " : "";
    a += "stroke=\"";
    a += colour;
    a += "\" stroke-width=\"" + num(mm(width_mm)) + "\" stroke-linecap=\"round\"";
    return a;
  }
  std::string dashed(const PortalStyle& s, bool fill_none = true) const {
    return stroke(s.colour, s.width_mm, fill_none) + " stroke-dasharray=\"" + num(mm(s.dash_mm)) + " " +
           num(mm(s.gap_mm)) + "\"";
  }
};

/// A round number of metres for the scale bar, about a quarter of `span`.
double nice_length(double span) {
  double target = std::max(span / 4, 0.5);
  double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= target) return m * p;
  return p;
}

struct StoreyView {
  double floor = 0, ceiling = 0, cut = 0;  ///< [m] absolute heights
  std::vector<CellId> fill;                ///< cells in the storey's floor-to-ceiling band
  std::vector<CellId> raised;              ///< room cells starting above the floor (over low walls)
};

}  // namespace

std::string plan_svg(const CellComplex& c, const DrawingLines& underlay) {
  const size_t nstoreys = std::max<size_t>(c.storeys.size(), 1);

  // Which cells each storey's plan shows.
  std::vector<StoreyView> views(nstoreys);
  for (size_t s = 0; s < nstoreys; ++s) {
    StoreyView& v = views[s];
    if (s < c.storeys.size()) {
      v.floor = c.storeys[s].elevation;
      v.ceiling = v.floor + c.storeys[s].height;
    } else {
      v.floor = 0;
      v.ceiling = 2.5;
    }
    v.cut = v.floor + std::min(1.2, 0.5 * (v.ceiling - v.floor));
  }
  for (size_t i = 0; i < c.cells.size(); ++i) {
    const Cell& cell = c.cells[i];
    auto id = static_cast<CellId>(i);
    // A tall outside cell (the outside around several storeys is one cell where its outline
    // does not change) belongs on the plan of every storey whose whole height it spans.
    if (cell.kind == CellKind::Outside) {
      for (StoreyView& v : views)
        if (cell.z0 <= v.floor + kEps && cell.z1 >= v.ceiling - kEps) v.fill.push_back(id);
      continue;
    }
    if (cell.storey < 0 || static_cast<size_t>(cell.storey) >= nstoreys) continue;
    StoreyView& v = views[static_cast<size_t>(cell.storey)];
    if (cell.kind == CellKind::Doorway) {
      v.fill.push_back(id);
    } else if (cell.kind == CellKind::Room) {
      if (cell.z0 <= v.floor + kEps) v.fill.push_back(id);
      else if (cell.kind == CellKind::Room && cell.z0 < v.ceiling - kEps) v.raised.push_back(id);
    }
  }
  // Outside first, then rooms, then doorways on top.
  auto order = [&](CellId a, CellId b) {
    auto rank = [&](CellId id) {
      switch (c.cells[static_cast<size_t>(id)].kind) {
        case CellKind::Outside: return 0;
        case CellKind::Room: return 1;
        default: return 2;
      }
    };
    return std::pair(rank(a), a) < std::pair(rank(b), b);
  };
  for (StoreyView& v : views) std::sort(v.fill.begin(), v.fill.end(), order);

  // The building's extent (the outside reaches the far box: leave most of it out).
  Box3 building;
  for (const Cell& cell : c.cells)
    if (cell.kind == CellKind::Room || cell.kind == CellKind::Doorway || cell.kind == CellKind::Stairwell)
      for (Vec2 p : cell.footprint) building.add({p.x, p.y, 0});
  if (building.lo.x > building.hi.x)
    for (const Cell& cell : c.cells)
      if (cell.kind != CellKind::Sky)
        for (Vec2 p : cell.footprint) building.add({p.x, p.y, 0});
  if (building.lo.x > building.hi.x) building = Box3{{0, 0, 0}, {10, 10, 0}};
  double bw = building.hi.x - building.lo.x, bh = building.hi.y - building.lo.y;
  double margin = 1.0 + 0.05 * std::max(bw, bh);
  double W = bw + 2 * margin, H = bh + 2 * margin;

  // Panels side by side, or stacked when the building is wide.
  const bool stacked = nstoreys > 1 && W > 1.3 * H;
  double gap_m = 0.06 * std::max(W, H);
  double span_w = stacked ? W : nstoreys * W + (nstoreys - 1) * gap_m;
  double span_h = stacked ? nstoreys * H + (nstoreys - 1) * gap_m : H;

  // A standard scale that keeps the drawing within about 380 mm.
  double scale = 20;
  for (double s : {20.0, 50.0, 100.0, 200.0, 250.0, 500.0, 1000.0, 2000.0, 2500.0, 5000.0, 10000.0,
                   20000.0, 50000.0, 100000.0}) {
    scale = s;
    if (std::max(span_w, span_h) * 1000.0 / s <= 380.0) break;
  }
  Svg svg;
  svg.k = scale / 1000.0;
  const double k = svg.k;

  const double page_margin = 10 * k, title_h = 14 * k, panel_title_h = 9 * k;
  gap_m = std::max(gap_m, 8 * k);
  // Legend entries: swatch kind, label.
  enum class Sw { Fill, Line, Dash, Hatch };
  struct Entry {
    Sw sw;
    std::string colour;
    std::string label;
    PortalStyle style{};
    double width_mm = 0;
  };
  std::vector<Entry> legend;
  legend.push_back({Sw::Fill, room_colour(0, true), "room (one colour per room)"});
  legend.push_back({Sw::Fill, kDoorwayFill, "doorway (opening in a wall)"});
  legend.push_back({Sw::Fill, kOutsideFill, "outside"});
  legend.push_back({Sw::Fill, kSolidFill, "wall or other solid"});
  bool any_raised = false;
  for (const StoreyView& v : views) any_raised |= !v.raised.empty();
  if (any_raised) legend.push_back({Sw::Fill, kLowFill, "space above a low wall"});
  legend.push_back({Sw::Line, kCutStroke, "wall cut at 1.2 m", {}, 0.6});
  legend.push_back({Sw::Line, kEdgeStroke, "edge below the cut (sill, low wall)", {}, 0.25});
  for (PortalKind pk : {PortalKind::Door, PortalKind::Window, PortalKind::Hatch, PortalKind::Gap,
                        PortalKind::Transparent, PortalKind::Open}) {
    std::string label = std::string(to_string(pk)) + " portal";
    if (pk == PortalKind::Transparent) label = "transparent portal (between cells)";
    if (pk == PortalKind::Open) label = "open portal (outside)";
    legend.push_back({Sw::Dash, portal_style(pk).colour, label, portal_style(pk)});
  }
  legend.push_back({Sw::Hatch, "url(#hatch-down)", "floor opening (stair down)"});
  legend.push_back({Sw::Hatch, "url(#hatch-up)", "ceiling opening (stair up)"});

  const double entry_w = 72 * k, entry_h = 6.5 * k;
  double page_w = std::max(span_w + 2 * page_margin, 200 * k);
  int per_row = std::max(1, static_cast<int>((page_w - 2 * page_margin) / entry_w));
  int legend_rows = (static_cast<int>(legend.size()) + per_row - 1) / per_row;
  const double legend_top_gap = 8 * k, scalebar_h = 16 * k;
  double panels_h = span_h + (stacked ? static_cast<double>(nstoreys) : 1.0) * panel_title_h;
  if (stacked) panels_h += 0;  // gaps already in span_h
  double page_h = page_margin + title_h + panels_h + legend_top_gap + legend_rows * entry_h +
                  scalebar_h + page_margin;

  // Panel frames.
  std::vector<Frame> frames(nstoreys);
  for (size_t s = 0; s < nstoreys; ++s) {
    Frame& f = frames[s];
    f.bx0 = building.lo.x - margin;
    f.by0 = building.lo.y - margin;
    f.w = W;
    f.h = H;
    double top = page_margin + title_h;
    if (stacked) {
      f.px = page_margin;
      f.py = top + static_cast<double>(s) * (H + gap_m + panel_title_h) + panel_title_h;
    } else {
      f.px = page_margin + static_cast<double>(s) * (W + gap_m);
      f.py = top + panel_title_h;
    }
  }

  std::string& o = svg.out;
  o.reserve(c.cells.size() * 600 + 8192);
  o += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  o += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + num(page_w / k) +
       "mm\" height=\"" + num(page_h / k) + "mm\" viewBox=\"0 0 " + num(page_w) + " " + num(page_h) +
       "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
  o += "<title>" + xml_escape("Avenues plan: " + c.plan_name) + "</title>\n";
  o += "<desc>Cells, portals and walls of each storey; viewBox in metres, 1:" + num(scale) +
       " on the page.</desc>\n";
  o += "<defs>\n";
  auto hatch = [&](const char* id, double angle, const char* colour) {
    o += std::string("<pattern id=\"") + id + "\" patternUnits=\"userSpaceOnUse\" width=\"" + num(1.6 * k) +
         "\" height=\"" + num(1.6 * k) + "\" patternTransform=\"rotate(" + num(angle) + ")\">" +
         "<rect width=\"" + num(1.6 * k) + "\" height=\"" + num(1.6 * k) + "\" fill=\"#ffffff\" fill-opacity=\"0.6\"/>" +
         "<line x1=\"0\" y1=\"0\" x2=\"0\" y2=\"" + num(1.6 * k) + "\" stroke=\"" + colour +
         "\" stroke-width=\"" + num(0.3 * k) + "\"/></pattern>\n";
  };
  hatch("hatch-down", 45, "#2c3e50");
  hatch("hatch-up", -45, "#7f8c8d");
  for (size_t s = 0; s < nstoreys; ++s)
    o += "<clipPath id=\"storey" + std::to_string(s) + "\"><rect x=\"" + num(frames[s].px) + "\" y=\"" +
         num(frames[s].py) + "\" width=\"" + num(W) + "\" height=\"" + num(H) + "\"/></clipPath>\n";
  o += "</defs>\n";
  svg.rect(0, 0, page_w, page_h, "fill=\"#ffffff\"");
  svg.text(page_margin, page_margin + 7 * k, 6.5, c.plan_name.empty() ? "Avenues plan" : c.plan_name,
           "font-weight=\"bold\"");
  svg.text(page_margin, page_margin + 12.5 * k, 3.6,
           std::to_string(c.storeys.size()) + (c.storeys.size() == 1 ? " storey, " : " storeys, ") +
               std::to_string(c.rooms.size()) + " rooms, " + std::to_string(c.cells.size()) + " cells, " +
               std::to_string(c.portals.size()) + " portals — scale 1:" + num(scale),
           "fill=\"#444444\"");

  for (size_t s = 0; s < nstoreys; ++s) {
    const Frame& f = frames[s];
    const StoreyView& v = views[s];
    std::string title = s < c.storeys.size() ? c.storeys[s].name : std::string("storey");
    if (title.empty()) title = "storey " + std::to_string(s);
    title += "  (floor " + num(v.floor) + " m, ceiling " + num(v.ceiling) + " m)";
    svg.text(f.px, f.py - 2.5 * k, 4.5, title, "font-weight=\"bold\"");
    o += "<g id=\"storey-" + std::to_string(s) + "\" clip-path=\"url(#storey" + std::to_string(s) + ")\">\n";
    svg.rect(f.px, f.py, W, H, "fill=\"#ffffff\"");

    // Solids (walls) as poché, then cells over them.
    o += "<g class=\"solids\" fill=\"" + std::string(kSolidFill) + "\" stroke=\"none\">\n";
    for (const CellComplex::SolidBox& sb : c.solids)
      if (sb.quad.size() >= 3 && sb.z0 < v.ceiling - kEps && sb.z1 > v.floor + kEps)
        svg.polygon(f, sb.quad, "");
    o += "</g>\n";
    std::string outline = "stroke=\"" + std::string(kOutline) + "\" stroke-width=\"" + num(svg.mm(0.08)) + "\"";
    o += "<g class=\"cells\">\n";
    for (CellId id : v.raised)
      svg.polygon(f, c.cells[static_cast<size_t>(id)].footprint,
                  "fill=\"" + std::string(kLowFill) + "\" " + outline);
    for (CellId id : v.fill) {
      const Cell& cell = c.cells[static_cast<size_t>(id)];
      std::string fill;
      if (cell.kind == CellKind::Doorway) fill = kDoorwayFill;
      else if (cell.kind == CellKind::Outside) fill = kOutsideFill;
      else if (cell.room >= 0 && static_cast<size_t>(cell.room) < c.rooms.size())
        fill = room_colour(cell.room, c.rooms[static_cast<size_t>(cell.room)].named);
      else fill = room_colour(cell.room, false);
      svg.polygon(f, cell.footprint, "fill=\"" + fill + "\" " + outline);
    }
    o += "</g>\n";

    // The drawing's own lines, over the cells' fills and under what was understood; only
    // those near the building (a drawing's title block or site plan lies far off).
    if (!underlay.empty()) {
      o += "<g class=\"drawing\" " + svg.stroke(kDrawingStroke, 0.13) + ">\n";
      const double x0 = f.bx0, y0 = f.by0, x1 = f.bx0 + f.w, y1 = f.by0 + f.h;
      for (const auto& [a, b] : underlay) {
        if (std::max(a.x, b.x) < x0 || std::min(a.x, b.x) > x1 || std::max(a.y, b.y) < y0 || std::min(a.y, b.y) > y1)
          continue;
        svg.line(f, {a, b}, "");
      }
      o += "</g>\n";
    }

    // Floor and ceiling openings (horizontal stairwell portals).
    o += "<g class=\"stairwells\">\n";
    for (const Portal& p : c.portals) {
      if (p.kind != PortalKind::Stairwell || vertical(p.plane) || p.poly.size() < 3) continue;
      double z = p.poly[0].z;
      const char* pattern = nullptr;
      if (std::fabs(z - v.floor) < 1e-3) pattern = "url(#hatch-down)";
      else if (std::fabs(z - v.ceiling) < 1e-3) pattern = "url(#hatch-up)";
      if (!pattern) continue;
      std::vector<Vec2> fp;
      for (Vec3 q : p.poly) fp.push_back({q.x, q.y});
      svg.polygon(f, fp, std::string("fill=\"") + pattern + "\" " + svg.dashed(portal_style(PortalKind::Stairwell), false));
    }
    o += "</g>\n";

    // Edges below the cut: the bottom edge of every opaque side face.
    o += "<g class=\"edges\" " + svg.stroke(kEdgeStroke, 0.25) + ">\n";
    for (CellId id : v.fill) {
      const Cell& cell = c.cells[static_cast<size_t>(id)];
      for (const Face& face : cell.faces) {
        if (!vertical(face.plane)) continue;
        for (const OpaquePoly& op : face.opaque)
          if (auto sg = bottom_edge(op.poly, face.plane.n, cell.z0)) svg.line(f, *sg, "");
      }
    }
    o += "</g>\n";

    // Vertical portals in the storey's band, artificial ones first.
    o += "<g class=\"portals\">\n";
    for (int pass = 0; pass < 2; ++pass) {
      for (const Portal& p : c.portals) {
        if (!vertical(p.plane) || p.poly.empty()) continue;
        bool artificial = p.kind == PortalKind::Transparent || p.kind == PortalKind::Open;
        if (artificial != (pass == 0)) continue;
        double zmin = HUGE_VAL;
        for (Vec3 q : p.poly) zmin = std::min(zmin, q.z);
        if (zmin < v.floor - kEps || zmin >= v.ceiling - kEps) continue;
        if (auto sg = extent(p.poly, p.plane.n)) svg.line(f, *sg, svg.dashed(portal_style(p.kind)));
      }
    }
    o += "</g>\n";

    // Walls cut at sill height.
    o += "<g class=\"cut\" " + svg.stroke(kCutStroke, 0.6) + ">\n";
    for (const Cell& cell : c.cells) {
      if (cell.kind == CellKind::Sky || !(cell.z0 < v.cut && cell.z1 > v.cut)) continue;
      if (cell.kind != CellKind::Outside && cell.storey != static_cast<StoreyId>(s)) continue;
      for (const Face& face : cell.faces) {
        if (!vertical(face.plane)) continue;
        for (const OpaquePoly& op : face.opaque)
          if (auto sg = cut(op.poly, face.plane.n, v.cut)) svg.line(f, *sg, "");
      }
    }
    o += "</g>\n";

    // Cell ids, then room names at each room's largest cell on this storey.
    auto inside = [&](Vec2 q) {
      return q.x > f.bx0 && q.x < f.bx0 + W && q.y > f.by0 && q.y < f.by0 + H;
    };
    o += "<g class=\"cell-ids\" fill=\"#666666\" text-anchor=\"middle\">\n";
    std::map<RoomId, std::pair<double, Vec2>> label_at;
    for (CellId id : v.fill) {
      const Cell& cell = c.cells[static_cast<size_t>(id)];
      Vec2 m = centroid(cell.footprint);
      if (inside(m)) svg.text(f.X(m.x), f.Y(m.y) - svg.mm(2.2), 1.8, std::to_string(id));
      if (cell.kind == CellKind::Room && cell.room >= 0) {
        double a = std::fabs(signed_area(cell.footprint));
        auto it = label_at.find(cell.room);
        if (it == label_at.end() || a > it->second.first) label_at[cell.room] = {a, m};
      }
    }
    o += "</g>\n";
    o += "<g class=\"room-names\" fill=\"#1b1b1b\" text-anchor=\"middle\">\n";
    for (const auto& [room, at] : label_at) {
      Vec2 m = at.second;
      std::string name;
      double room_area = 0;
      bool named = true;
      if (static_cast<size_t>(room) < c.rooms.size()) {
        name = c.rooms[static_cast<size_t>(room)].name;
        room_area = c.rooms[static_cast<size_t>(room)].area;
        named = c.rooms[static_cast<size_t>(room)].named;
      }
      if (name.empty() || !named) name = name.empty() ? "(unnamed)" : "(" + name + ")";
      svg.text(f.X(m.x), f.Y(m.y) + svg.mm(1.4), 4, name,
               named ? "font-weight=\"bold\"" : "font-style=\"italic\"");
      if (room_area > 0) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.1f m\xc2\xb2", room_area);
        svg.text(f.X(m.x), f.Y(m.y) + svg.mm(5.2), 2.8, buf, "fill=\"#444444\"");
      }
    }
    o += "</g>\n";
    o += "</g>\n";
    svg.rect(f.px, f.py, W, H, svg.stroke("#888888", 0.2));
  }

  // Legend.
  double ly = page_margin + title_h + panels_h + legend_top_gap;
  o += "<g class=\"legend\">\n";
  for (size_t i = 0; i < legend.size(); ++i) {
    const Entry& e = legend[i];
    double x = page_margin + static_cast<double>(static_cast<int>(i) % per_row) * entry_w;
    double y = ly + static_cast<double>(static_cast<int>(i) / per_row) * entry_h;
    double sw = 9 * k, sh = 3.6 * k;
    switch (e.sw) {
      case Sw::Fill:
      case Sw::Hatch:
        svg.rect(x, y, sw, sh, "fill=\"" + e.colour + "\" stroke=\"" + std::string(kOutline) +
                                   "\" stroke-width=\"" + num(svg.mm(0.1)) + "\"");
        break;
      case Sw::Line:
        o += "<line x1=\"" + num(x) + "\" y1=\"" + num(y + sh / 2) + "\" x2=\"" + num(x + sw) + "\" y2=\"" +
             num(y + sh / 2) + "\" " + svg.stroke(e.colour.c_str(), e.width_mm) + "/>\n";
        break;
      case Sw::Dash:
        o += "<line x1=\"" + num(x) + "\" y1=\"" + num(y + sh / 2) + "\" x2=\"" + num(x + sw) + "\" y2=\"" +
             num(y + sh / 2) + "\" " + svg.dashed(e.style) + "/>\n";
        break;
    }
    svg.text(x + sw + 2 * k, y + sh * 0.9, 3.2, e.label);
  }
  o += "</g>\n";

  // Scale bar: four blocks, alternately dark and light.
  double L = nice_length(W);
  double sy = ly + legend_rows * entry_h + 4 * k, sx = page_margin;
  o += "<g class=\"scale-bar\">\n";
  for (int i = 0; i < 4; ++i)
    svg.rect(sx + i * L / 4, sy, L / 4, 2 * k,
             std::string("fill=\"") + (i % 2 ? "#ffffff" : "#1b1b1b") + "\" stroke=\"#1b1b1b\" stroke-width=\"" +
                 num(svg.mm(0.15)) + "\"");
  svg.text(sx, sy + 6 * k, 2.4, "0", "text-anchor=\"middle\"");
  svg.text(sx + L / 2, sy + 6 * k, 2.4, num(L / 2), "text-anchor=\"middle\"");
  svg.text(sx + L, sy + 6 * k, 2.4, num(L) + " m", "text-anchor=\"middle\"");
  svg.text(sx + L + 8 * k, sy + 2 * k, 2.4, "scale 1:" + num(scale) + " (y up, metres)");
  o += "</g>\n";
  o += "</svg>\n";
  return std::move(svg.out);
}

void write_plan_svg(const CellComplex& complex, const std::string& path, const DrawingLines& underlay) {
  write_file_atomically(path, plan_svg(complex, underlay));
}

}  // namespace avenues
