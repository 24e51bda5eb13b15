// Avenues — the mean colour of an image (a Sweet Home texture), in linear light.
//
// Avenues paints each surface one colour: a textured surface takes its image's mean.
// The image is told by its content (PNG by libpng, JPEG by libjpeg, and what else
// stb_image reads: TGA, which older models' textures often are, BMP, GIF, PSD, PNM),
// decoded from memory,
// every pixel's sRGB components made linear (core/srgb.h) before they are averaged, each
// weighted by its alpha (a transparent pixel shows no colour).
#pragma once

#include <array>
#include <span>
#include <string>
#include <string_view>

namespace avenues {

/// Images larger than this many pixels are refused (a hostile header must not make the
/// reader allocate or loop without end).
constexpr long long kMaxImagePixels = 1LL << 25;

/// The image's mean colour in linear RGB, each [0, 1]. Throws std::runtime_error naming
/// `name` when the bytes are not an image of those formats it can decode, when the image is
/// larger than kMaxImagePixels, or wholly transparent.
std::array<double, 3> mean_image_colour(std::string_view bytes, const std::string& name);

/// The same for pixels already decoded: `rgba` holds 4 bytes a pixel (sRGB, alpha). Throws
/// std::runtime_error naming `name` when they are wholly transparent (or there are none).
std::array<double, 3> mean_pixels_colour(std::span<const unsigned char> rgba, const std::string& name);

}  // namespace avenues
