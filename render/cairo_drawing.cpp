// Avenues — a drawing as PDF or EPS, through Cairo (see drawing.h). Cairo writes into a
// string (its stream surfaces), so the file itself is written at once by write_drawing().
// User space is scaled to paper millimetres; each weight is one path, stroked once.
#include <cairo-pdf.h>
#include <cairo-ps.h>
#include <cairo.h>

#include <memory>
#include <stdexcept>

#include "render/drawing_formats.h"

namespace avenues::detail {

namespace {

constexpr double kPointsPerMm = 72 / 25.4;

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

std::string cairo_bytes(const Drawing& d, const Page& page, bool eps, const std::string& path) {
  std::string bytes;
  const double w = page.width * kPointsPerMm, h = page.height * kPointsPerMm;
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      eps ? cairo_ps_surface_create_for_stream(append, &bytes, w, h)
          : cairo_pdf_surface_create_for_stream(append, &bytes, w, h),
      cairo_surface_destroy);
  if (eps) {
    cairo_ps_surface_set_eps(surface.get(), 1);
    if (!d.title.empty()) cairo_ps_surface_dsc_comment(surface.get(), ("%%Title: " + d.title).c_str());
  } else {
    if (!d.title.empty()) cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, d.title.c_str());
    // No creation date: the same drawing is the same bytes from run to run (as its SVG and
    // DXF are), so that a drawing kept under version control or compared changes only when
    // what it shows does. An empty date leaves Cairo's /CreationDate out.
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "");
  }
  {
    std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), cairo_destroy);
    cairo_scale(cr.get(), kPointsPerMm, kPointsPerMm);
    cairo_set_source_rgb(cr.get(), 0, 0, 0);
    cairo_set_line_cap(cr.get(), CAIRO_LINE_CAP_ROUND);
    if (!d.fill.empty()) {  // the poché, under every stroke
      cairo_set_fill_rule(cr.get(), CAIRO_FILL_RULE_EVEN_ODD);
      for (const auto& ring : d.fill) {
        for (size_t k = 0; k < ring.size(); ++k) {
          const Vec2 p = page.from_raster_y_down(ring[k]);
          if (k == 0) cairo_move_to(cr.get(), p.x, p.y);
          else cairo_line_to(cr.get(), p.x, p.y);
        }
        cairo_close_path(cr.get());
      }
      cairo_set_source_rgb(cr.get(), 0.55, 0.55, 0.55);
      cairo_fill(cr.get());
      cairo_set_source_rgb(cr.get(), 0, 0, 0);
    }
    cairo_select_font_face(cr.get(), "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    for (const Label& l : d.labels) {
      cairo_set_font_size(cr.get(), page.mm(l.height) * 1.4);
      cairo_text_extents_t e;
      cairo_text_extents(cr.get(), l.text.c_str(), &e);
      const Vec2 p = page.from_raster_y_down(l.at);
      cairo_move_to(cr.get(), p.x - e.width / 2 - e.x_bearing, p.y + page.mm(l.height) / 2);
      cairo_show_text(cr.get(), l.text.c_str());
    }
    for (Weight weight : {Weight::Cut, Weight::Outline, Weight::Crease}) {
      cairo_set_line_width(cr.get(), page.pen(weight));
      for (const Stroke& s : d.strokes) {
        if (s.weight != weight) continue;
        const Vec2 a = page.from_raster_y_down(s.a), b = page.from_raster_y_down(s.b);
        cairo_move_to(cr.get(), a.x, a.y);
        cairo_line_to(cr.get(), b.x, b.y);
      }
      cairo_stroke(cr.get());
    }
    if (cairo_status(cr.get()) != CAIRO_STATUS_SUCCESS)
      throw std::runtime_error("cannot write drawing " + path + ": " + cairo_status_to_string(cairo_status(cr.get())));
  }
  cairo_surface_finish(surface.get());
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error("cannot write drawing " + path + ": " +
                             cairo_status_to_string(cairo_surface_status(surface.get())));
  // Cairo 1.16 dates every PostScript header and has no setting to leave it out: the
  // header's %%CreationDate comment (optional in DSC) is dropped, for the reason above.
  if (eps) {
    const size_t end = bytes.find("%%EndComments");
    const size_t at = bytes.find("%%CreationDate:");
    if (at != std::string::npos && at < end) {
      const size_t eol = bytes.find('\n', at);
      bytes.erase(at, eol == std::string::npos ? std::string::npos : eol + 1 - at);
    }
  }
  return bytes;
}

}  // namespace avenues::detail
