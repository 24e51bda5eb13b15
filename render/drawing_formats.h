// Avenues — internal to render/: the page a drawing is put on, and one encoder per file format
// (svg_drawing.cpp, cairo_drawing.cpp, dxf_drawing.cpp, hpgl_drawing.cpp). drawing.cpp picks
// one by the file's extension.
#pragma once

#include <string>

#include "render/drawing.h"

namespace avenues::detail {

/// Raster pixels to paper millimetres: x_mm = margin + x_px·scale.
struct Page {
  double scale = 1;               ///< [mm/px] > 0
  double margin = 0;              ///< [mm]
  double width = 0, height = 0;   ///< [mm] the whole page, margins included
  double outline = 0.5, crease = 0.25, cut = 0.7;  ///< [mm] pen widths

  /// Page coordinates with y down from the top edge (SVG, Cairo).
  Vec2 from_raster_y_down(Vec2 px) const { return {margin + px.x * scale, margin + px.y * scale}; }
  /// Page coordinates with y up from the bottom edge (DXF, HPGL).
  Vec2 from_raster_y_up(Vec2 px) const { return {margin + px.x * scale, height - margin - px.y * scale}; }
  double pen(Weight w) const { return w == Weight::Outline ? outline : w == Weight::Cut ? cut : crease; }
  double mm(double px) const { return px * scale; }
};

/// The page for `drawing`; throws std::runtime_error naming `path` if the options or the
/// drawing's size are not usable.
Page page_for(const Drawing& drawing, const PageOptions& options, const std::string& path);

std::string svg_bytes(const Drawing& drawing, const Page& page);
/// PDF, or EPS when `eps`; throws std::runtime_error naming `path` if Cairo fails.
std::string cairo_bytes(const Drawing& drawing, const Page& page, bool eps, const std::string& path);
std::string dxf_bytes(const Drawing& drawing, const Page& page);
/// Fills stats.penup_mm_before / after.
std::string hpgl_bytes(const Drawing& drawing, const Page& page, DrawingStats& stats);

}  // namespace avenues::detail
