// Avenues — stereo pairs as one picture: anaglyph and side by side (see raster.h).
//
// Jones 1971 already drew stereo pairs of his cell views; Wylie 1967 expected half-tones
// to follow. The two pictures come from two cameras (visibility/stereo.h makes the pair);
// here they are only combined.
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "render/raster.h"
#include "render/raster_srgb.h"

namespace avenues {

namespace {

/// Dubois's least-squares red–cyan projection (E. Dubois, "A projection method to generate
/// anaglyph stereo images", ICASSP 2001; the red–cyan matrices as he published them for
/// typical display primaries and filters): the anaglyph's linear RGB is L·left + R·right,
/// clamped to [0, 1].
constexpr float kLeft[3][3] = {{0.437f, 0.449f, 0.164f}, {-0.062f, -0.062f, -0.024f}, {-0.048f, -0.050f, -0.017f}};
constexpr float kRight[3][3] = {{-0.011f, -0.032f, -0.007f}, {0.377f, 0.761f, 0.009f}, {-0.026f, -0.093f, 1.234f}};

void require_same_size(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("a stereo pair needs two pictures of one size, not " + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                                std::to_string(b.height));
}

}  // namespace

const char* to_string(StereoComposite l) {
  switch (l) {
    case StereoComposite::Anaglyph: return "anaglyph";
    case StereoComposite::Parallel: return "parallel";
    case StereoComposite::Cross: return "cross";
  }
  return "?";
}

bool parse_stereo_composite(const std::string& s, StereoComposite& out) {
  if (s == "anaglyph") out = StereoComposite::Anaglyph;
  else if (s == "parallel") out = StereoComposite::Parallel;
  else if (s == "cross") out = StereoComposite::Cross;
  else return false;
  return true;
}

Image anaglyph(const Image& left, const Image& right) {
  require_same_size(left, right);
  const Image l = rgb_of(left), r = rgb_of(right);
  const SrgbDecoder& lin = srgb_decoder();
  const SrgbEncoder& enc = srgb_encoder();
  Image out;
  out.resize(l.width, l.height, 3);
  const size_t n = size_t(l.width) * size_t(l.height);
  for (size_t i = 0; i < n; ++i) {
    const float a[3] = {lin(l.data[3 * i]), lin(l.data[3 * i + 1]), lin(l.data[3 * i + 2])};
    const float b[3] = {lin(r.data[3 * i]), lin(r.data[3 * i + 1]), lin(r.data[3 * i + 2])};
    for (int c = 0; c < 3; ++c) {
      float v = 0;
      for (int k = 0; k < 3; ++k) v += kLeft[c][k] * a[k] + kRight[c][k] * b[k];
      out.data[3 * i + size_t(c)] = enc(std::clamp(v, 0.0f, 1.0f));
    }
  }
  return out;
}

Image side_by_side(const Image& first, const Image& second) {
  require_same_size(first, second);
  const bool colour = first.channels == 3 || second.channels == 3;
  const Image a = colour ? rgb_of(first) : first, b = colour ? rgb_of(second) : second;
  Image out;
  out.resize(2 * a.width, a.height, a.channels);
  out.bilevel = a.bilevel && b.bilevel;
  const size_t row = size_t(a.width) * size_t(a.channels);
  for (int y = 0; y < a.height; ++y) {
    std::memcpy(out.row(y), a.row(y), row);
    std::memcpy(out.row(y) + row, b.row(y), row);
  }
  return out;
}

Image stereo_composite(const Image& left, const Image& right, StereoComposite layout) {
  switch (layout) {
    case StereoComposite::Anaglyph: return anaglyph(left, right);
    case StereoComposite::Parallel: return side_by_side(left, right);
    case StereoComposite::Cross: return side_by_side(right, left);
  }
  throw std::invalid_argument("unknown stereo layout");
}

}  // namespace avenues
