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

}  // namespace avenues::testing
