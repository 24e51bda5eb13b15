// Avenues — a hidden-line drawing as a picture, for the walkthrough window.
//
// The exporters put drawings on paper (SVG, PDF, DXF, HPGL); the window wants pixels. Cairo draws
// the strokes, antialiased, in black on white at the drawing's own raster coordinates (one
// unit a pixel), outlines 2 px and creases 1 px wide, furniture a little lighter — the same
// look as the SVG page at screen size.
#pragma once

#include "render/drawing.h"
#include "render/raster.h"

namespace avenues {

/// The drawing as an RGB picture of drawing.width × drawing.height pixels, into `out`
/// (its storage reused).
void raster_of_drawing(const Drawing& drawing, Image& out);
/// The same drawn over `under`, a picture of the drawing's size and view (an architect's
/// drawing over its half-tone): the drawing's fills and lines on top of it, not on white.
/// Throws std::invalid_argument when the sizes differ.
void raster_of_drawing(const Drawing& drawing, const Image& under, Image& out);

}  // namespace avenues
