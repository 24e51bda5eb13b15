// Avenues — a hidden-line drawing: strokes on the picture, and its export to paper.
//
// Jones 1971 drew "perspective line drawings ... suited to output on a standard digital
// CRT display"; Avenues draws the same lines for paper. A Drawing is what the eye sees as
// straight strokes in raster coordinates (the view's pixels, x to the right, rows from the
// top), each with a weight — outlines heavier than creases, as a draughtsman draws them —
// and a layer. write_drawing() puts it on a page, the format chosen by the file's
// extension:
//   .svg         hand-written SVG, page in millimetres, one group per layer, widths in mm;
//   .pdf, .eps   Cairo;
//   .dxf         dxflib: named layers, standard DXF lineweights, millimetres, y up;
//   .hpgl, .plt  HPGL for pen plotters: one pen per weight, strokes chained and ordered
//                nearest-end-first to cut the pen's travel in the air (pen_order.h).
// Every file is written at once or not at all (core/atomic_file.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/geometry.h"

namespace avenues {

/// How heavy a stroke is drawn.
enum class Weight : uint8_t {
  Outline,  ///< the eye sees past the line: silhouettes, edges of openings (line_weight.h)
  Crease,   ///< surfaces meet at the line on both sides of it: wall–floor, a table's edge seen from above
  Cut,      ///< where a cut plane passes through solid (a plan's or section's walls): the heaviest pen
};
const char* to_string(Weight w);

/// What a stroke is a line of; each layer is a group (SVG) or a named layer (DXF).
enum class Layer : uint8_t {
  Architecture,  ///< real lines of the cell complex (walls, floors, openings)
  Furniture,     ///< edges of the plan's objects
  Shadows,       ///< outlines of the shadows the plan's point lights cast (optional: LineOptions::shadows)
  Cut,           ///< an architect's drawing: outlines of what the cut plane passes through, and their fill
  Beyond,        ///< an architect's drawing: real lines seen beyond the cut
  Annotation,    ///< an architect's drawing: room names and areas
};
/// The layers a drawing shows, in drawing order: architecture and furniture always, the
/// others when something is drawn on them.
std::vector<Layer> layers_drawn(const struct Drawing& drawing);
const char* to_string(Layer l);

struct Stroke {
  Vec2 a, b;  ///< [px] raster coordinates of the ends: x to the right, y down from the top edge
  Weight weight = Weight::Crease;
  Layer layer = Layer::Architecture;
};

/// Text on the drawing (Layer::Annotation), centred on `at`.
struct Label {
  Vec2 at;             ///< [px] raster coordinates of the text's centre
  std::string text;    ///< UTF-8, one line
  double height = 10;  ///< [px] > 0: the height of its capitals
};

struct Drawing {
  int width = 0, height = 0;     ///< [px] > 0: the page in raster units (the camera's image size)
  std::vector<Stroke> strokes;   ///< each visible piece of line once; none overlaps another
  /// The cut's fill ("poché", Layer::Cut): closed rings [px], filled by the even-odd rule, so a
  /// ring inside another is a hole (the picture's window, then the free space the cut crosses).
  std::vector<std::vector<Vec2>> fill;
  std::vector<Label> labels;     ///< Layer::Annotation
  std::string title;             ///< for the file's metadata; may be empty
};

/// How a drawing is put on paper. The picture is scaled to fill the page's width inside the
/// margins; the page's height follows the picture's aspect ratio.
struct PageOptions {
  double width_mm = 297;    ///< [mm] > 2·margin_mm: the page's width (A4 landscape)
  double margin_mm = 10;    ///< [mm] >= 0: blank border on every side
  double outline_mm = 0.5;  ///< [mm] > 0: pen width of outlines (ISO 128 pairs 0.5 with 0.25)
  double crease_mm = 0.25;  ///< [mm] > 0: pen width of creases
  double cut_mm = 0.7;      ///< [mm] > 0: pen width of cut outlines (ISO 128: 0.7, 0.5, 0.25)
};

struct DrawingStats {
  size_t lines = 0;            ///< strokes written
  double penup_mm_before = 0;  ///< [mm] HPGL only: pen-up travel in the drawing's own order, pen by pen; else 0
  double penup_mm_after = 0;   ///< [mm] HPGL only: pen-up travel as written (chained, nearest end first), <= before; else 0
};

/// The extensions write_drawing() understands, for messages: ".svg, .pdf, .eps, .dxf, .hpgl, .plt".
std::string drawing_extensions();
/// True if the path's extension (any case) is one write_drawing() understands.
bool is_drawing_path(const std::string& path);

/// Writes the drawing to `path` in the format its extension names (case-insensitive), at once
/// or not at all. Throws std::runtime_error naming the file: for an unknown extension (listing
/// drawing_extensions()), invalid page options, or when it cannot be written.
DrawingStats write_drawing(const Drawing& drawing, const std::string& path, const PageOptions& page = {});

/// The file's bytes and what writing them would report; write_drawing() without the write, for
/// callers that must have several files ready before writing any (a stereo pair).
struct EncodedDrawing {
  std::string bytes;
  DrawingStats stats;
};
EncodedDrawing encode_drawing(const Drawing& drawing, const std::string& path, const PageOptions& page = {});

}  // namespace avenues
