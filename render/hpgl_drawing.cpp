// Avenues — a drawing as HPGL for pen plotters (see drawing.h).
//
// Plotter units are 0.025 mm (40 to the millimetre), integers, origin at the page's
// lower-left corner, y up. Pen 1 draws outlines and pen 2 creases (load the heavier pen in
// stall 1); pen 3, the heaviest, an architect's cut outlines, and labels (LB, ASCII) follow.
// Fills are not plotted: the cut outlines close them. The strokes are rounded to plotter units first, then ordered (pen_order.h), so
// the pen-up travel reported is exactly the travel of the file: from (0, 0) after IN
// through every PU move, not counting the return home.
#include <cmath>
#include <string>

#include "render/drawing_formats.h"
#include "render/pen_order.h"

namespace avenues::detail {

namespace {

constexpr double kUnitsPerMm = 40;  // 1 plotter unit = 0.025 mm

int pen_of(Weight w) { return w == Weight::Outline ? 1 : w == Weight::Cut ? 3 : 2; }

void put_point(std::string& out, Vec2 p) {
  out += std::to_string(static_cast<long>(p.x));
  out += ',';
  out += std::to_string(static_cast<long>(p.y));
}

}  // namespace

std::string hpgl_bytes(const Drawing& d, const Page& page, DrawingStats& stats) {
  std::vector<std::array<Vec2, 2>> segments;
  std::vector<int> pens;
  segments.reserve(d.strokes.size());
  pens.reserve(d.strokes.size());
  auto units = [&](Vec2 px) {
    const Vec2 mm = page.from_raster_y_up(px);
    return Vec2{std::round(mm.x * kUnitsPerMm), std::round(mm.y * kUnitsPerMm)};
  };
  for (const Stroke& s : d.strokes) {
    segments.push_back({units(s.a), units(s.b)});
    pens.push_back(pen_of(s.weight));
  }
  const PenPlan plan = plan_pen_paths(segments, pens, {0, 0});
  stats.penup_mm_before = plan.travel_before / kUnitsPerMm;
  stats.penup_mm_after = plan.travel_after / kUnitsPerMm;

  std::string out = "IN;PA;\n";
  out.reserve(out.size() + d.strokes.size() * 24);
  int pen = 0;
  for (const PenPath& path : plan.paths) {
    if (path.pen != pen) {
      pen = path.pen;
      out += "SP" + std::to_string(pen) + ";\n";
    }
    out += "PU";
    put_point(out, path.points[0]);
    out += ";PD";
    for (size_t k = 1; k < path.points.size(); ++k) {
      if (k > 1) out += ',';
      put_point(out, path.points[k]);
    }
    out += ";\n";
  }
  if (!d.labels.empty()) out += "SP2;DT\x03;\n";
  for (const Label& l : d.labels) {
    std::string text;
    for (unsigned char ch : l.text) text += ch >= 32 && ch < 127 && ch != ';' ? char(ch) : '?';
    const double h_cm = page.mm(l.height) / 10, w_cm = h_cm * 0.7;  // SI: character size in cm
    const Vec2 at = units(l.at);
    out += "PU" + std::to_string(long(at.x - text.size() * w_cm * kUnitsPerMm * 10 * 0.75 / 2)) + "," +
           std::to_string(long(at.y - h_cm * kUnitsPerMm * 10 / 2)) + ";SI" + std::to_string(w_cm) + "," +
           std::to_string(h_cm) + ";LB" + text + "\x03\n";
  }
  out += "PU;SP0;\n";
  return out;
}

}  // namespace avenues::detail
