// Avenues tests — what a rendered picture shows: a surface's colour under some light.
#pragma once

#include <algorithm>
#include <array>
#include <string>

#include <gtest/gtest.h>

#include "core/srgb.h"
#include "render/raster.h"

namespace avenues::testing {

/// An 8-bit sRGB code as linear light.
inline double linear8(int v) { return linear_from_srgb(v / 255.0); }

/// The linear colour of the picture's pixel (x, y) (its middle by default) over the colour
/// it should show, channel by channel: one factor (the light on it) when it shows that
/// colour, within the 8-bit rounding.
inline void expect_pixel_shows(const Image& pic, const std::array<double, 3>& colour, const std::string& what,
                               int x = -1, int y = -1) {
  ASSERT_EQ(pic.channels, 3);
  if (x < 0) x = pic.width / 2;
  if (y < 0) y = pic.height / 2;
  const uint8_t* px = pic.row(size_t(y)) + size_t(x) * 3;
  // The light, from the colour's strongest channel (the one 8-bit rounding disturbs least).
  auto step = [&](size_t k) { return linear8(std::min(255, px[k] + 1)) - linear8(std::max(0, px[k] - 1)); };
  const size_t strong = size_t(std::max_element(colour.begin(), colour.end()) - colour.begin());
  ASSERT_GT(colour[strong], 0) << what;
  const double light = linear8(px[strong]) / colour[strong];
  ASSERT_GT(light, 0.05) << what << " is lit";
  for (size_t k = 0; k < 3; ++k) {
    // Its own rounding, and the strongest channel's carried over by the light.
    const double tolerance = step(k) + colour[k] / colour[strong] * step(strong);
    EXPECT_NEAR(linear8(px[k]), colour[k] * light, tolerance) << what << ", channel " << k << ": " << int(px[k]);
  }
}

/// How two pictures of one size differ: in how many pixels, and in how many of those away
/// from every edge (no pixel of another colour beside it, in either picture).
struct PictureDifference {
  long pixels = 0, differ = 0, off_edges = 0;
  long edges = 0;  ///< pixels beside a pixel of another colour, in either picture
};

/// Two pictures of one view made two ways that should agree up to the renderer's edge
/// error (docs/ACCURACY.md §2): a sample centred on an edge may go either way, so a pixel
/// may differ only beside a pixel of another colour, in either picture.
inline PictureDifference compare_off_edges(const Image& a, const Image& b) {
  PictureDifference d;
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.channels, 3);
  EXPECT_EQ(b.channels, 3);
  if (a.width != b.width || a.height != b.height || a.channels != 3 || b.channels != 3) return d;
  const int w = a.width, h = a.height;
  auto pixel = [&](const Image& im, int x, int y) {
    const size_t i = 3 * (size_t(y) * size_t(w) + size_t(x));
    return std::array<uint8_t, 3>{im.data[i], im.data[i + 1], im.data[i + 2]};
  };
  auto on_edge = [&](const Image& im, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx >= 0 && ny >= 0 && nx < w && ny < h && pixel(im, nx, ny) != pixel(im, x, y)) return true;
      }
    return false;
  };
  d.pixels = long(w) * h;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool edge = on_edge(a, x, y) || on_edge(b, x, y);
      d.edges += edge;
      if (pixel(a, x, y) == pixel(b, x, y)) continue;
      ++d.differ;
      d.off_edges += !edge;
    }
  return d;
}

}  // namespace avenues::testing
