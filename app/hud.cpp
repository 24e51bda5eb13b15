// Avenues — the walkthrough's head-up display (see hud.h).
#include "app/hud.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace avenues::app {

namespace {

/// Where a panel's text goes: its size [px], the margin around the text and the lines' pitch.
struct PanelLayout {
  int w = 1, h = 1;
  double pad = 0, line_h = 0, ascent = 0;
};

/// Measures the lines at this size of type on a scratch surface.
PanelLayout measure(const std::vector<std::string>& lines, double font_px) {
  cairo_surface_t* scratch = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
  cairo_t* m = cairo_create(scratch);
  cairo_select_font_face(m, "monospace", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(m, font_px);
  cairo_font_extents_t fe;
  cairo_font_extents(m, &fe);
  double text_w = 0;
  for (const std::string& l : lines) {
    cairo_text_extents_t te;
    cairo_text_extents(m, l.c_str(), &te);
    text_w = std::max(text_w, te.x_advance);
  }
  cairo_destroy(m);
  cairo_surface_destroy(scratch);
  PanelLayout out;
  out.pad = std::round(font_px * 0.6);
  out.line_h = std::ceil(fe.height);
  out.ascent = fe.ascent;
  out.w = std::max(1, int(std::ceil(text_w + 2 * out.pad)));
  out.h = std::max(1, int(std::ceil(out.line_h * double(lines.size()) + 2 * out.pad)));
  return out;
}

void draw_panel(OverlayPanel& panel, const std::vector<std::string>& lines, double font_px, int x, int y,
                bool centred_in, int win_w, int win_h) {
  const PanelLayout layout = measure(lines, font_px);
  const int w = layout.w, h = layout.h;
  const double pad = layout.pad, line_h = layout.line_h;
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  cairo_t* cr = cairo_create(s);
  cairo_set_source_rgba(cr, 0.05, 0.05, 0.08, 0.72);
  cairo_paint(cr);
  cairo_select_font_face(cr, "monospace", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, font_px);
  cairo_set_source_rgb(cr, 0.95, 0.95, 0.9);
  for (size_t i = 0; i < lines.size(); ++i) {
    cairo_move_to(cr, pad, pad + layout.ascent + line_h * double(i));
    cairo_show_text(cr, lines[i].c_str());
  }
  cairo_destroy(cr);
  cairo_surface_flush(s);
  // Cairo's ARGB32 is premultiplied, native-endian 32-bit: B, G, R, A bytes on little-endian.
  panel.width = w;
  panel.height = h;
  panel.bgra.resize(size_t(w) * size_t(h) * 4);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  for (int r = 0; r < h; ++r) std::memcpy(panel.bgra.data() + size_t(r) * size_t(w) * 4, data + size_t(r) * size_t(stride), size_t(w) * 4);
  cairo_surface_destroy(s);
  panel.x = centred_in ? std::max(0, (win_w - w) / 2) : x;
  panel.y = centred_in ? std::max(0, (win_h - h) / 2) : y;
  ++panel.version;
}

std::string joined(const std::vector<std::string>& lines, double font_px) {
  std::string s = std::to_string(font_px);
  for (const std::string& l : lines) s += "\n" + l;
  return s;
}

}  // namespace

void set_text_panel(OverlayPanel& panel, const std::vector<std::string>& lines, int x, int y, double font_px) {
  const std::string src = joined(lines, font_px);
  if (src == panel.source && panel.width > 0) {
    panel.x = x, panel.y = y;
    return;
  }
  panel.source = src;
  draw_panel(panel, lines, font_px, x, y, false, 0, 0);
}

void set_centred_text_panel(OverlayPanel& panel, const std::vector<std::string>& lines, int width, int height,
                            double font_px) {
  // Fitted and drawn again only when the text or the window changes.
  const std::string src = std::to_string(width) + "x" + std::to_string(height) + " " + joined(lines, font_px);
  if (src == panel.source && panel.width > 0) {
    panel.x = std::max(0, (width - panel.width) / 2);
    panel.y = std::max(0, (height - panel.height) / 2);
    return;
  }
  panel.source = src;
  // Smaller type in a small window, so that every line fits, wide and high (down to 7 px).
  for (; font_px > 7; font_px -= 0.5) {
    const PanelLayout layout = measure(lines, font_px);
    if (layout.w <= width - 8 && layout.h <= height - 8) break;
  }
  draw_panel(panel, lines, font_px, 0, 0, true, width, height);
}

}  // namespace avenues::app
