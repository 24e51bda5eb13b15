// Avenues — a hidden-line drawing as a picture (see line_raster.h).
#include "render/line_raster.h"

#include <cairo.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

namespace avenues {

namespace {

void draw(const Drawing& drawing, const Image* under, Image& out) {
  const int w = drawing.width, h = drawing.height;
  if (under && (under->width != w || under->height != h))
    throw std::invalid_argument("raster_of_drawing: the picture under the drawing is " + std::to_string(under->width) +
                                "x" + std::to_string(under->height) + ", the drawing " + std::to_string(w) + "x" +
                                std::to_string(h));
  out.resize(w, h, 3);
  if (w <= 0 || h <= 0) return;
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_t* cr = cairo_create(s);
  if (under) {
    // RGB24: native-endian 32-bit xRGB (see below); a grey picture's one sample is all three.
    cairo_surface_flush(s);
    unsigned char* data = cairo_image_surface_get_data(s);
    const int stride = cairo_image_surface_get_stride(s);
    const int c = under->channels;
    for (int y = 0; y < h; ++y) {
      uint32_t* dst = reinterpret_cast<uint32_t*>(data + size_t(y) * size_t(stride));
      const uint8_t* src = under->data.data() + size_t(y) * size_t(w) * size_t(c);
      for (int x = 0; x < w; ++x) {
        const uint8_t* p = src + size_t(x) * size_t(c);
        const uint32_t r = p[0], g = c == 3 ? p[1] : p[0], b = c == 3 ? p[2] : p[0];
        dst[x] = (r << 16) | (g << 8) | b;
      }
    }
    cairo_surface_mark_dirty(s);
  } else {
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
  }
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  if (!drawing.fill.empty()) {  // an architect's cut: grey, even-odd, under the lines
    cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
    for (const auto& ring : drawing.fill) {
      for (size_t k = 0; k < ring.size(); ++k)
        (k == 0 ? cairo_move_to : cairo_line_to)(cr, ring[k].x, ring[k].y);
      cairo_close_path(cr);
    }
    cairo_set_source_rgb(cr, 0.55, 0.55, 0.55);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  for (const Label& l : drawing.labels) {
    cairo_set_font_size(cr, l.height * 1.4);
    cairo_text_extents_t e;
    cairo_text_extents(cr, l.text.c_str(), &e);
    cairo_move_to(cr, l.at.x - e.width / 2 - e.x_bearing, l.at.y + l.height / 2);
    cairo_show_text(cr, l.text.c_str());
  }
  // One path per (layer, weight), stroked once: far fewer calls than a stroke per line.
  for (const Layer layer : layers_drawn(drawing))
    for (const Weight weight : {Weight::Crease, Weight::Outline, Weight::Cut}) {
      if (layer == Layer::Shadows) continue;  // the window never showed them
      bool any = false;
      for (const Stroke& st : drawing.strokes) {
        if (st.layer != layer || st.weight != weight) continue;
        cairo_move_to(cr, st.a.x, st.a.y);
        cairo_line_to(cr, st.b.x, st.b.y);
        any = true;
      }
      if (!any) continue;
      const double ink = layer == Layer::Furniture ? 0.3 : 0;
      cairo_set_source_rgb(cr, ink, ink, ink);
      cairo_set_line_width(cr, weight == Weight::Cut ? 3 : weight == Weight::Outline ? 2 : 1);
      cairo_stroke(cr);
    }
  cairo_destroy(cr);
  cairo_surface_flush(s);
  // RGB24: native-endian 32-bit xRGB, i.e. bytes B, G, R, x on little-endian machines.
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  for (int y = 0; y < h; ++y) {
    const uint32_t* src = reinterpret_cast<const uint32_t*>(data + size_t(y) * size_t(stride));
    uint8_t* dst = out.row(y);
    for (int x = 0; x < w; ++x) {
      const uint32_t p = src[x];
      dst[3 * x] = uint8_t(p >> 16);
      dst[3 * x + 1] = uint8_t(p >> 8);
      dst[3 * x + 2] = uint8_t(p);
    }
  }
  cairo_surface_destroy(s);
}

}  // namespace

void raster_of_drawing(const Drawing& drawing, Image& out) { draw(drawing, nullptr, out); }

void raster_of_drawing(const Drawing& drawing, const Image& under, Image& out) { draw(drawing, &under, out); }

}  // namespace avenues
