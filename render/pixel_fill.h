// Avenues — a run of pixels filled with one colour: the half-tone renderer's innermost loop
// (a flat frame is mostly this), and the part of a frame that writing the frame buffer once
// with memset is the peer of.
//
// A grey pixel is one byte, so a run is a memset. An RGB pixel is three bytes, which no
// machine word holds a whole number of: the colour repeats every three 16-byte vectors.
// The run is written as its first vector (unaligned), then whole vectors on the 16-byte
// grid, three registers taking turns, then its last vector flush with its end. So no
// store but the first and the last crosses a cache line: one that does costs two, and
// 16-byte stores at the pixels' own 3-byte steps make one in four such.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace avenues {

/// Writes n pixels of `channels` bytes (1 or 3) at dst, each `colour` (its first
/// `channels` bytes). Touches no byte outside [dst, dst + n·channels).
void fill_pixels(uint8_t* dst, size_t n, const std::array<uint8_t, 3>& colour, int channels);

}  // namespace avenues
