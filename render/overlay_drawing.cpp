// Avenues — the avenue overlay (see overlay_drawing.h). Hand-written SVG, units in
// pixels of the picture (panel 1), metres (panel 2, y flipped) and layout units (panel 3).
#include "render/overlay_drawing.h"
#include "render/xml_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/atomic_file.h"

namespace avenues {

namespace {

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3f", v);
  return b;
}

/// A colour per avenue depth, dark to light along a hue wheel.
std::string depth_colour(int depth) {
  static const char* palette[] = {"#1b4f72", "#b03a2e", "#1e8449", "#7d3c98", "#b9770e", "#117a65", "#884ea0", "#2e4053"};
  return palette[depth % 8];
}

std::string cell_label(const CellComplex& c, CellId id) {
  const Cell& cell = c.cells[size_t(id)];
  std::string s = "cell " + std::to_string(id);
  if (cell.room >= 0) s += " (" + c.rooms[size_t(cell.room)].name + ")";
  else s += std::string(" (") + to_string(cell.kind) + ")";
  return s;
}

}  // namespace

std::string overlay_svg(const CellComplex& c, const Camera& cam, const VisibleSet& vs) {
  const double W = cam.width, H = cam.height;
  // Panel 2: the plan of the storey the eye is on (cells at the eye's height).
  Box3 seen;
  for (CellId id : vs.cells)
    if (c.cells[size_t(id)].kind != CellKind::Sky && c.cells[size_t(id)].kind != CellKind::Outside)
      seen.add(c.cells[size_t(id)].bounds().lo), seen.add(c.cells[size_t(id)].bounds().hi);
  seen.add(cam.eye);
  const double pad = 1.0;
  const double px0 = seen.lo.x - pad, py0 = seen.lo.y - pad, pw = seen.hi.x - seen.lo.x + 2 * pad,
               ph = seen.hi.y - seen.lo.y + 2 * pad;
  const double plan_scale = H / std::max(ph, pw * H / W);  // px per metre
  const double PW = pw * plan_scale, PH = ph * plan_scale;
  // Panel 3: the avenue tree.
  const double row = 16, col = 120;
  const size_t tree_rows = std::min(vs.avenues.size(), kOverlayTreeRows);
  int max_depth = 0;
  for (size_t i = 0; i < tree_rows; ++i) max_depth = std::max(max_depth, vs.avenues[i].depth);
  const double TW = (max_depth + 1) * col + 160, TH = double(tree_rows) * row + 40;
  // The masks outlined: every one, or the shallowest kOverlayMasks (ties in search order).
  std::vector<size_t> outlined(vs.avenues.size());
  for (size_t i = 0; i < outlined.size(); ++i) outlined[i] = i;
  if (outlined.size() > kOverlayMasks) {
    std::stable_sort(outlined.begin(), outlined.end(),
                     [&](size_t a, size_t b) { return vs.avenues[a].depth < vs.avenues[b].depth; });
    outlined.resize(kOverlayMasks);
    std::sort(outlined.begin(), outlined.end());
  }
  auto of_all = [](size_t shown, size_t all, const char* what) {
    return shown == all ? std::to_string(all) + " " + what
                        : std::to_string(shown) + " of " + std::to_string(all) + " " + what;
  };
  const double gap = 30, total_w = W + gap + PW + gap + TW, total_h = std::max({H, PH, TH}) + 40;

  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << fmt(total_w) << "\" height=\"" << fmt(total_h)
    << "\" viewBox=\"0 0 " << fmt(total_w) << " " << fmt(total_h) << "\" font-family=\"sans-serif\">\n"
    << "<title>Avenues of sight: " << xml_escape(c.plan_name) << "</title>\n";

  // --- panel 1: picture plane with masks.
  o << "<g id=\"picture-plane\" transform=\"translate(0,30)\">\n"
    << "<text x=\"0\" y=\"-10\" font-size=\"14\">Picture plane: masks of "
    << of_all(outlined.size(), vs.avenues.size(), outlined.size() < vs.avenues.size() ? "avenues (the shallowest)" : "avenues")
    << ", " << vs.cells.size() << " cells</text>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << fmt(W) << "\" height=\"" << fmt(H)
    << "\" fill=\"#fbfbf8\" stroke=\"#000\" stroke-width=\"1\"/>\n";
  for (size_t i : outlined) {
    const Avenue& a = vs.avenues[i];
    std::string pts;
    double cx = 0, cy = 0;
    for (Vec2 m : a.mask) {
      Vec2 r = cam.raster_from_image(m);
      pts += fmt(r.x) + "," + fmt(r.y) + " ";
      cx += r.x / double(a.mask.size());
      cy += r.y / double(a.mask.size());
    }
    o << "<polygon points=\"" << pts << "\" fill=\"none\" stroke=\"" << depth_colour(a.depth)
      << "\" stroke-width=\"" << (a.depth == 0 ? 2 : 1.2) << "\"><title>avenue " << i << ": "
      << xml_escape(cell_label(c, a.cell)) << ", depth " << a.depth << "</title></polygon>\n";
    if (a.depth > 0)
      o << "<text x=\"" << fmt(cx) << "\" y=\"" << fmt(cy) << "\" font-size=\"9\" text-anchor=\"middle\" fill=\""
        << depth_colour(a.depth) << "\">" << xml_escape(cell_label(c, a.cell)) << "</text>\n";
  }
  o << "</g>\n";

  // --- panel 2: plan with the eye and the cells seen.
  auto X = [&](double x) { return (x - px0) * plan_scale; };
  auto Y = [&](double y) { return (py0 + ph - y) * plan_scale; };
  o << "<g id=\"plan\" transform=\"translate(" << fmt(W + gap) << ",30)\">\n"
    << "<text x=\"0\" y=\"-10\" font-size=\"14\">Plan at eye height: cells seen (shaded)</text>\n"
    << "<clipPath id=\"plan-clip\"><rect x=\"0\" y=\"0\" width=\"" << fmt(PW) << "\" height=\"" << fmt(PH)
    << "\"/></clipPath>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << fmt(PW) << "\" height=\"" << fmt(PH) << "\" fill=\"#fff\" stroke=\"#888\"/>\n"
    << "<g clip-path=\"url(#plan-clip)\">\n";
  std::vector<uint8_t> visible(c.cells.size(), 0);
  for (CellId id : vs.cells) visible[size_t(id)] = 1;
  for (size_t id = 0; id < c.cells.size(); ++id) {
    const Cell& cell = c.cells[id];
    if (!(cell.z0 <= cam.eye.z && cam.eye.z <= cell.z1)) continue;
    std::string pts;
    for (Vec2 p : cell.footprint) pts += fmt(X(p.x)) + "," + fmt(Y(p.y)) + " ";
    const bool inside = cell.kind == CellKind::Room || cell.kind == CellKind::Doorway || cell.kind == CellKind::Stairwell;
    o << "<polygon points=\"" << pts << "\" fill=\"" << (visible[id] ? (inside ? "#f5d76e" : "#d6eaf8") : "none")
      << "\" fill-opacity=\"0.6\" stroke=\"#999\" stroke-width=\"0.5\"><title>"
      << xml_escape(cell_label(c, CellId(id))) << "</title></polygon>\n";
  }
  // The view: two rays along the window's sides in plan.
  const double hw = cam.half_width(), reach = std::max(pw, ph);
  for (double sx : {cam.shift_x - hw, cam.shift_x + hw}) {
    Vec3 d = sx * cam.right + cam.forward;
    double l = std::hypot(d.x, d.y);
    if (l == 0) continue;
    o << "<line x1=\"" << fmt(X(cam.eye.x)) << "\" y1=\"" << fmt(Y(cam.eye.y)) << "\" x2=\""
      << fmt(X(cam.eye.x + d.x / l * reach)) << "\" y2=\"" << fmt(Y(cam.eye.y + d.y / l * reach))
      << "\" stroke=\"#c0392b\" stroke-width=\"1\" stroke-dasharray=\"4 3\"/>\n";
  }
  // Room names at their cells' centres (the first cell of each room at eye height).
  std::vector<uint8_t> named(c.rooms.size(), 0);
  for (const Cell& cell : c.cells) {
    if (cell.room < 0 || named[size_t(cell.room)] || !(cell.z0 <= cam.eye.z && cam.eye.z <= cell.z1)) continue;
    named[size_t(cell.room)] = 1;
    Vec2 m{0, 0};
    for (Vec2 p : cell.footprint) m = m + (1.0 / double(cell.footprint.size())) * p;
    o << "<text x=\"" << fmt(X(m.x)) << "\" y=\"" << fmt(Y(m.y)) << "\" font-size=\"11\" text-anchor=\"middle\">"
      << xml_escape(c.rooms[size_t(cell.room)].name) << "</text>\n";
  }
  o << "<circle cx=\"" << fmt(X(cam.eye.x)) << "\" cy=\"" << fmt(Y(cam.eye.y))
    << "\" r=\"4\" fill=\"#c0392b\"><title>eye</title></circle>\n</g>\n</g>\n";

  // --- panel 3: the avenue tree (depth across, depth-first order down).
  o << "<g id=\"avenue-tree\" transform=\"translate(" << fmt(W + gap + PW + gap) << ",30)\">\n"
    << "<text x=\"0\" y=\"-10\" font-size=\"14\">Avenue tree (Jones's Fig. 5)"
    << (tree_rows < vs.avenues.size() ? ": the first " + of_all(tree_rows, vs.avenues.size(), "avenues") : std::string())
    << "</text>\n";
  for (size_t i = 0; i < tree_rows; ++i) {
    const Avenue& a = vs.avenues[i];
    double x = a.depth * col + 6, y = i * row + 10;
    if (a.parent >= 0) {
      const Avenue& p = vs.avenues[size_t(a.parent)];
      double px = p.depth * col + 6, py = a.parent * row + 10;
      o << "<path d=\"M" << fmt(px) << "," << fmt(py) << " V" << fmt(y) << " H" << fmt(x)
        << "\" fill=\"none\" stroke=\"#777\" stroke-width=\"0.8\"/>\n";
      o << "<text x=\"" << fmt(px + 4) << "\" y=\"" << fmt(y - 3) << "\" font-size=\"7\" fill=\"#777\">"
        << to_string(c.portals[size_t(a.portal)].kind) << " " << a.portal << "</text>\n";
    }
    o << "<circle cx=\"" << fmt(x) << "\" cy=\"" << fmt(y) << "\" r=\"3\" fill=\"" << depth_colour(a.depth)
      << "\"/>\n<text x=\"" << fmt(x + 6) << "\" y=\"" << fmt(y + 3) << "\" font-size=\"9\">"
      << xml_escape(cell_label(c, a.cell)) << "</text>\n";
  }
  o << "</g>\n</svg>\n";
  return o.str();
}

void write_overlay_svg(const CellComplex& c, const Camera& cam, const VisibleSet& vs, const std::string& path) {
  write_file_atomically(path, overlay_svg(c, cam, vs));
}

}  // namespace avenues
