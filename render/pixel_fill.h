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
//
// The vectors of a colour, from each of a pixel's three bytes on, are made once
// (FillColour) and kept for the colour's next runs (FillColours): made afresh for every
// run, they cost as much as a short run's stores.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace avenues {

/// One colour ready to fill runs with: 16 pixels (48 bytes) of it from each byte of a
/// pixel on.
class FillColour {
 public:
  FillColour() = default;
  explicit FillColour(const std::array<uint8_t, 3>& colour);
  const std::array<uint8_t, 3>& colour() const { return colour_; }
  /// Writes n pixels of `channels` bytes (1: colour()[0]; or 3) at dst. Touches no byte
  /// outside [dst, dst + n·channels).
  void fill(uint8_t* dst, size_t n, int channels) const;

 private:
  std::array<uint8_t, 3> colour_{};
  alignas(16) uint64_t phases_[3][6] = {};  ///< bytes from byte k of a pixel on, per k
};

/// The colours last filled with, kept (64 of them, by a hash of the colour): most
/// pictures have few colours, and a flat frame the same ones from row to row.
class FillColours {
 public:
  FillColours();
  const FillColour& of(const std::array<uint8_t, 3>& colour) {
    FillColour& slot = slots_[(colour[0] * 7u + colour[1] * 131u + colour[2] * 31u) % kSlots];
    if (slot.colour() != colour) slot = FillColour(colour);
    return slot;
  }

 private:
  static constexpr size_t kSlots = 64;
  std::array<FillColour, kSlots> slots_;
};

}  // namespace avenues
