// Avenues — a drawing as SVG (see drawing.h). Hand-written XML: user units are paper
// millimetres (viewBox = page size in mm), one group per layer (an Inkscape layer too),
// inside it one group per weight carrying the stroke width in mm.
#include <algorithm>
#include <charconv>
#include <string>

#include "render/drawing_formats.h"
#include "render/xml_text.h"

namespace avenues::detail {

namespace {

/// v with 4 decimals (0.1 µm on paper), without going through a locale.
std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 4);
  return std::string(buf, r.ptr);
}

}  // namespace

std::string svg_bytes(const Drawing& d, const Page& page) {
  std::string o;
  o.reserve(512 + d.strokes.size() * 72);
  o += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\"";
  o += " width=\"" + num(page.width) + "mm\" height=\"" + num(page.height) + "mm\"";
  o += " viewBox=\"0 0 " + num(page.width) + " " + num(page.height) + "\">\n";
  if (!d.title.empty()) o += "<title>" + xml_escape(d.title) + "</title>\n";
  for (Layer layer : layers_drawn(d)) {
    const std::string name = to_string(layer);
    o += "<g id=\"" + name + "\" inkscape:groupmode=\"layer\" inkscape:label=\"" + name +
         "\" fill=\"none\" stroke=\"#000\" stroke-linecap=\"round\">\n";
    if (layer == Layer::Cut && !d.fill.empty()) {  // the poché, under its outlines
      o += "<path class=\"fill\" fill=\"#888\" fill-rule=\"evenodd\" stroke=\"none\" d=\"";
      for (const auto& ring : d.fill)
        for (size_t k = 0; k < ring.size(); ++k) {
          const Vec2 p = page.from_raster_y_down(ring[k]);
          o += k == 0 ? 'M' : 'L';
          o += num(p.x);
          o += ' ';
          o += num(p.y);
          o += k + 1 == ring.size() ? 'Z' : ' ';
        }
      o += "\"/>\n";
    }
    if (layer == Layer::Annotation) {
      for (const Label& l : d.labels) {
        const Vec2 p = page.from_raster_y_down(l.at);
        o += "<text x=\"" + num(p.x) + "\" y=\"" + num(p.y + page.mm(l.height) / 2) + "\" font-size=\"" +
             num(page.mm(l.height) * 1.4) + "\" font-family=\"sans-serif\" text-anchor=\"middle\" fill=\"#000\" "
             "stroke=\"none\">" + xml_escape(l.text) + "</text>\n";
      }
    }
    for (Weight weight : {Weight::Cut, Weight::Outline, Weight::Crease}) {
      if (weight == Weight::Cut && layer != Layer::Cut) continue;
      o += "<g class=\"" + std::string(to_string(weight)) + "\" stroke-width=\"" + num(page.pen(weight)) + "\">\n";
      for (const Stroke& s : d.strokes) {
        if (s.layer != layer || s.weight != weight) continue;
        const Vec2 a = page.from_raster_y_down(s.a), b = page.from_raster_y_down(s.b);
        o += "<line x1=\"" + num(a.x) + "\" y1=\"" + num(a.y) + "\" x2=\"" + num(b.x) + "\" y2=\"" + num(b.y) + "\"/>\n";
      }
      o += "</g>\n";
    }
    o += "</g>\n";
  }
  o += "</svg>\n";
  return o;
}

}  // namespace avenues::detail
