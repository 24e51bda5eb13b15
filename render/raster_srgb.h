// Avenues — linear light to 8-bit sRGB and back by table (IEC 61966-2-1; the transfer
// functions are in core/srgb.h).
//
// Shading and filtering happen in linear light (Material::colour is linear RGB); a
// sample is encoded to 8-bit sRGB once, at the very end, through a table. The table has
// 2^13 entries indexed by the rounded linear value, fine enough that every one of the
// 256 codes is reachable and no code is off by more than one from the exact transfer
// function (the first step, 1/8191, encodes to 0.4 of a code).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "core/srgb.h"  // srgb_from_linear, linear_from_srgb

namespace avenues {

/// 8-bit sRGB code → linear value, by table.
class SrgbDecoder {
 public:
  SrgbDecoder() {
    for (int c = 0; c < 256; ++c) table_[size_t(c)] = float(linear_from_srgb(c / 255.0));
  }
  float operator()(uint8_t code) const { return table_[code]; }

 private:
  std::array<float, 256> table_{};
};

/// Linear value → 8-bit sRGB code, by table; values outside [0, 1] are clamped.
class SrgbEncoder {
 public:
  static constexpr int kSteps = 8191;  ///< table entries - 1
  SrgbEncoder() {
    for (int i = 0; i <= kSteps; ++i)
      table_[size_t(i)] = uint8_t(std::lround(255 * srgb_from_linear(double(i) / kSteps)));
  }
  uint8_t operator()(float linear) const {
    const float v = linear * float(kSteps) + 0.5f;
    // Written so that NaN lands on 0, like a negative value.
    const int i = v >= float(kSteps) ? kSteps : (v > 0 ? int(v) : 0);
    return table_[size_t(i)];
  }

 private:
  std::array<uint8_t, kSteps + 1> table_{};
};

/// Rec. 709 luminance of a linear RGB colour.
inline float luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

/// The tables, built once per process.
const SrgbEncoder& srgb_encoder();
const SrgbDecoder& srgb_decoder();

}  // namespace avenues
