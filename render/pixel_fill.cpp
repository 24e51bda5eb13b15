// Avenues — a run of pixels filled with one colour (see pixel_fill.h).
#include "render/pixel_fill.h"

#include <bit>
#include <cstring>

namespace avenues {

namespace {

typedef uint64_t Vector __attribute__((vector_size(16)));  // 16 bytes: two words

/// The 48 bytes of 16 pixels of `colour` from byte `phase` (0, 1 or 2) of a pixel on, as
/// three vectors made in registers: a vector loaded from words just stored would wait for
/// the stores (a load spanning two stores is not forwarded from them).
struct Pattern {
  Vector v[3];
  Pattern(const std::array<uint8_t, 3>& colour, size_t phase) {
    const uint8_t c0 = colour[phase % 3], c1 = colour[(phase + 1) % 3], c2 = colour[(phase + 2) % 3];
    const uint64_t px = uint64_t(c0) | uint64_t(c1) << 8 | uint64_t(c2) << 16;
    // Bytes 0–7, 8–15 and 16–23 of the repeated pixel: 24 bytes, a period of the pattern.
    uint64_t w0 = px | px << 24 | px << 48, w1 = px >> 16 | px << 8 | px << 32 | px << 56, w2 = px >> 8 | px << 16 | px << 40;
    if constexpr (std::endian::native == std::endian::big) {
      w0 = __builtin_bswap64(w0), w1 = __builtin_bswap64(w1), w2 = __builtin_bswap64(w2);  // the same bytes in memory
    }
    v[0] = Vector{w0, w1};
    v[1] = Vector{w2, w0};
    v[2] = Vector{w1, w2};
  }
};

}  // namespace

void fill_pixels(uint8_t* dst, size_t n, const std::array<uint8_t, 3>& colour, int channels) {
  if (channels == 1) {
    std::memset(dst, colour[0], n);
    return;
  }
  constexpr size_t V = sizeof(Vector);
  const size_t bytes = 3 * n;
  if (bytes < 2 * V) {
    for (size_t i = 0; i < n; ++i) std::memcpy(dst + 3 * i, colour.data(), 3);
    return;
  }
  const Pattern first(colour, 0);
  std::memcpy(dst, &first.v[0], V);  // the first vector, wherever the run begins
  uint8_t* p = reinterpret_cast<uint8_t*>((reinterpret_cast<uintptr_t>(dst) + V) & ~uintptr_t(V - 1));
  const Pattern on_grid(colour, size_t(p - dst) % 3);
  uint8_t* const end = dst + bytes;
  for (; p + 3 * V <= end; p += 3 * V) {
    std::memcpy(p, &on_grid.v[0], V);
    std::memcpy(p + V, &on_grid.v[1], V);
    std::memcpy(p + 2 * V, &on_grid.v[2], V);
  }
  if (p + V <= end) {
    std::memcpy(p, &on_grid.v[0], V);
    p += V;
    if (p + V <= end) {
      std::memcpy(p, &on_grid.v[1], V);
      p += V;
    }
  }
  if (p < end) {  // the last vector, flush with the end
    const Pattern last(colour, (bytes - V) % 3);
    std::memcpy(end - V, &last.v[0], V);
  }
}

}  // namespace avenues
