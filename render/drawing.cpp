// Avenues — a drawing's export, chosen by the file's extension (see drawing.h).
#include "render/drawing.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/file_name.h"
#include "render/drawing_formats.h"

namespace avenues {

const char* to_string(Weight w) { return w == Weight::Outline ? "outline" : w == Weight::Cut ? "cut" : "crease"; }
const char* to_string(Layer l) {
  switch (l) {
    case Layer::Architecture: return "architecture";
    case Layer::Furniture: return "furniture";
    case Layer::Shadows: return "shadows";
    case Layer::Cut: return "cut";
    case Layer::Beyond: return "beyond";
    case Layer::Annotation: return "annotation";
  }
  return "?";
}

std::vector<Layer> layers_drawn(const Drawing& d) {
  std::vector<Layer> out{Layer::Architecture, Layer::Furniture};
  for (Layer l : {Layer::Shadows, Layer::Cut, Layer::Beyond, Layer::Annotation}) {
    bool used = std::any_of(d.strokes.begin(), d.strokes.end(), [&](const Stroke& s) { return s.layer == l; });
    used |= l == Layer::Cut && !d.fill.empty();
    used |= l == Layer::Annotation && !d.labels.empty();
    if (used) out.push_back(l);
  }
  return out;
}

namespace {

enum class Format { Svg, Pdf, Eps, Dxf, Hpgl };

struct Extension {
  const char* ext;
  Format format;
};
constexpr Extension kExtensions[] = {{".svg", Format::Svg}, {".pdf", Format::Pdf},   {".eps", Format::Eps},
                                     {".dxf", Format::Dxf}, {".hpgl", Format::Hpgl}, {".plt", Format::Hpgl}};

Format format_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  for (const Extension& e : kExtensions)
    if (ext == e.ext) return e.format;
  throw std::runtime_error("cannot write drawing " + path + ": unknown extension '" + ext + "' (use " +
                           drawing_extensions() + ")");
}

}  // namespace

bool is_drawing_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return std::any_of(std::begin(kExtensions), std::end(kExtensions), [&](const Extension& e) { return ext == e.ext; });
}

std::string drawing_extensions() {
  std::string s;
  for (const Extension& e : kExtensions) s += (s.empty() ? "" : ", ") + std::string(e.ext);
  return s;
}

namespace detail {

Page page_for(const Drawing& d, const PageOptions& o, const std::string& path) {
  auto fail = [&](const std::string& why) { throw std::runtime_error("cannot write drawing " + path + ": " + why); };
  if (!(d.width > 0 && d.height > 0)) fail("the drawing has no size");
  if (!(o.margin_mm >= 0 && std::isfinite(o.margin_mm))) fail("the margin must be >= 0 mm");
  if (!(o.width_mm > 2 * o.margin_mm && std::isfinite(o.width_mm))) fail("the page must be wider than its two margins");
  if (!(o.outline_mm > 0 && o.crease_mm > 0 && o.cut_mm > 0)) fail("pen widths must be > 0 mm");
  Page p;
  p.margin = o.margin_mm;
  p.scale = (o.width_mm - 2 * o.margin_mm) / d.width;
  p.width = o.width_mm;
  p.height = d.height * p.scale + 2 * o.margin_mm;
  p.outline = o.outline_mm;
  p.crease = o.crease_mm;
  p.cut = o.cut_mm;
  return p;
}

}  // namespace detail

EncodedDrawing encode_drawing(const Drawing& d, const std::string& path, const PageOptions& options) {
  const Format f = format_of(path);
  const detail::Page page = detail::page_for(d, options, path);
  EncodedDrawing out;
  out.stats.lines = d.strokes.size();
  switch (f) {
    case Format::Svg: out.bytes = detail::svg_bytes(d, page); break;
    case Format::Pdf: out.bytes = detail::cairo_bytes(d, page, false, path); break;
    case Format::Eps: out.bytes = detail::cairo_bytes(d, page, true, path); break;
    case Format::Dxf: out.bytes = detail::dxf_bytes(d, page); break;
    case Format::Hpgl: out.bytes = detail::hpgl_bytes(d, page, out.stats); break;
  }
  return out;
}

DrawingStats write_drawing(const Drawing& d, const std::string& path, const PageOptions& options) {
  EncodedDrawing e = encode_drawing(d, path, options);
  write_file_atomically(path, e.bytes);
  return e.stats;
}

}  // namespace avenues
