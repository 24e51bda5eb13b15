// Avenues — the walkthrough's head-up display: the status line and the help, as panels.
//
// Text is set by Cairo (its toy text API, over fontconfig's monospace face) on a
// translucent dark box, into a premultiplied BGRA panel the window blends over the frame.
// A panel is redrawn only when its text changes; the status line's figures are smoothed
// and refreshed a few times a second, so the HUD costs nothing most frames.
#pragma once

#include <string>
#include <vector>

#include "app/viewer.h"

namespace avenues::app {

/// Lines of monospace text on a translucent box at (x, y) [px]; the panel's version is bumped
/// when the lines differ from what it shows.
void set_text_panel(OverlayPanel& panel, const std::vector<std::string>& lines, int x, int y, double font_px = 14);

/// The same box centred in a window of width × height pixels.
void set_centred_text_panel(OverlayPanel& panel, const std::vector<std::string>& lines, int width, int height,
                            double font_px = 15);

}  // namespace avenues::app
