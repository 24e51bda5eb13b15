// Avenues — bilevel half-tones for print: ordered and error-diffusion dithering (see
// raster.h).
//
// Both work on the linear grey level g in [0, 1] (the picture decoded from sRGB), so that
// the fraction of white dots over an area equals the area's mean linear grey: what a
// printed page reflects. A dot is white (255) or black (0).
//  - Bayer: white where g exceeds the threshold (B(x mod 8, y mod 8) + ½) / 64 of the
//    recursive 8×8 Bayer matrix; each sample on its own, so rows are independent.
//  - Floyd–Steinberg: white where g plus the diffused error is at least ½; the error
//    (value − dot) goes 7/16 ahead, 3/16, 5/16 and 1/16 to the row below, in a serpentine
//    order (rows alternate direction) to avoid the drift of one-way scanning.
#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "render/raster.h"
#include "render/raster_srgb.h"

namespace avenues {

namespace {

/// The 8×8 Bayer index matrix, built by the recursion M(2n) = [4M, 4M+2; 4M+3, 4M+1].
std::array<std::array<int, 8>, 8> bayer8() {
  std::array<std::array<int, 8>, 8> m{};
  for (int size = 1; size < 8; size *= 2)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const int v = 4 * m[size_t(y)][size_t(x)];
        m[size_t(y)][size_t(x)] = v;
        m[size_t(y)][size_t(x + size)] = v + 2;
        m[size_t(y + size)][size_t(x)] = v + 3;
        m[size_t(y + size)][size_t(x + size)] = v + 1;
      }
  return m;
}

}  // namespace

const char* to_string(Dither d) {
  switch (d) {
    case Dither::None: return "none";
    case Dither::Bayer: return "bayer";
    case Dither::FloydSteinberg: return "fs";
  }
  return "?";
}

bool parse_dither(const std::string& s, Dither& out) {
  if (s == "none") out = Dither::None;
  else if (s == "bayer") out = Dither::Bayer;
  else if (s == "fs" || s == "floyd-steinberg") out = Dither::FloydSteinberg;
  else return false;
  return true;
}

Image dither(const Image& picture, Dither how) {
  if (how == Dither::None) return picture;
  const Image grey = grey_of(picture);
  const SrgbDecoder& lin = srgb_decoder();
  const int w = grey.width, h = grey.height;
  Image out;
  out.resize(w, h, 1);
  out.bilevel = true;
  if (how == Dither::Bayer) {
    static const auto m = bayer8();
    for (int y = 0; y < h; ++y) {
      const uint8_t* src = grey.row(y);
      uint8_t* dst = out.row(y);
      for (int x = 0; x < w; ++x) {
        const float threshold = (float(m[size_t(y % 8)][size_t(x % 8)]) + 0.5f) / 64;
        dst[x] = lin(src[x]) > threshold ? 255 : 0;
      }
    }
    return out;
  }
  // Floyd–Steinberg: `here` holds this row's values plus the error pushed into it,
  // `below` gathers the error for the next row. One sample of margin on either side.
  std::vector<float> here(size_t(w) + 2), below(size_t(w) + 2);
  for (int x = 0; x < w; ++x) here[size_t(x) + 1] = lin(grey.row(0)[x]);
  for (int y = 0; y < h; ++y) {
    std::fill(below.begin(), below.end(), 0.0f);
    if (y + 1 < h)
      for (int x = 0; x < w; ++x) below[size_t(x) + 1] = lin(grey.row(y + 1)[x]);
    const bool forward = y % 2 == 0;
    const int dir = forward ? 1 : -1;
    uint8_t* dst = out.row(y);
    for (int k = 0; k < w; ++k) {
      const int x = forward ? k : w - 1 - k;
      const size_t i = size_t(x) + 1;
      const float v = here[i];
      const float dot = v >= 0.5f ? 1.0f : 0.0f;
      dst[x] = dot > 0 ? 255 : 0;
      const float e = v - dot;
      here[size_t(int(i) + dir)] += e * (7.0f / 16);
      below[size_t(int(i) - dir)] += e * (3.0f / 16);
      below[i] += e * (5.0f / 16);
      below[size_t(int(i) + dir)] += e * (1.0f / 16);
    }
    std::swap(here, below);
  }
  return out;
}

}  // namespace avenues
