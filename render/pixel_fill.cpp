// Avenues — a run of pixels filled with one colour (see pixel_fill.h).
#include "render/pixel_fill.h"

#include <bit>
#include <cstring>

namespace avenues {

namespace {

typedef uint64_t Vector __attribute__((vector_size(16)));  // 16 bytes: two words

}  // namespace

FillColour::FillColour(const std::array<uint8_t, 3>& colour) : colour_(colour) {
  for (size_t phase = 0; phase < 3; ++phase) {
    const uint64_t px = uint64_t(colour[phase]) | uint64_t(colour[(phase + 1) % 3]) << 8 |
                        uint64_t(colour[(phase + 2) % 3]) << 16;
    // Bytes 0–7, 8–15 and 16–23 of the repeated pixel: 24 bytes, a period of the pattern.
    uint64_t w[3] = {px | px << 24 | px << 48, px >> 16 | px << 8 | px << 32 | px << 56, px >> 8 | px << 16 | px << 40};
    if constexpr (std::endian::native == std::endian::big)
      for (uint64_t& x : w) x = __builtin_bswap64(x);  // the same bytes in memory
    for (size_t i = 0; i < 6; ++i) phases_[phase][i] = w[i % 3];
  }
}

FillColours::FillColours() {
  // Each slot holds a colour that does not hash to it, so that its first use makes it.
  for (size_t i = 0; i < kSlots; ++i) {
    std::array<uint8_t, 3> c{0, 0, 0};
    while ((c[0] * 7u + c[1] * 131u + c[2] * 31u) % kSlots == i) ++c[2];
    slots_[i] = FillColour(c);
  }
}

void FillColour::fill(uint8_t* dst, size_t n, int channels) const {
  if (channels == 1) {
    std::memset(dst, colour_[0], n);
    return;
  }
  constexpr size_t V = sizeof(Vector);
  const size_t bytes = 3 * n;
  if (bytes < 2 * V) {
    for (size_t i = 0; i < n; ++i) std::memcpy(dst + 3 * i, colour_.data(), 3);
    return;
  }
  std::memcpy(dst, phases_[0], V);  // the first vector, wherever the run begins
  uint8_t* p = reinterpret_cast<uint8_t*>((reinterpret_cast<uintptr_t>(dst) + V) & ~uintptr_t(V - 1));
  const uint64_t* words = phases_[size_t(p - dst) % 3];
  Vector v0, v1, v2;
  std::memcpy(&v0, words, V);
  std::memcpy(&v1, words + 2, V);
  std::memcpy(&v2, words + 4, V);
  uint8_t* const end = dst + bytes;
  for (; p + 3 * V <= end; p += 3 * V) {
    std::memcpy(p, &v0, V);
    std::memcpy(p + V, &v1, V);
    std::memcpy(p + 2 * V, &v2, V);
  }
  if (p + V <= end) {
    std::memcpy(p, &v0, V);
    p += V;
    if (p + V <= end) {
      std::memcpy(p, &v1, V);
      p += V;
    }
  }
  if (p < end) std::memcpy(end - V, phases_[(bytes - V) % 3], V);  // the last vector, flush with the end
}

}  // namespace avenues
