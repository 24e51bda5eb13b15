// Avenues — raster pictures: the half-tone image, its files, its 1-bit print form and
// its stereo pairs.
//
// A picture leaves the renderer as 8-bit sRGB (grey or RGB), already gamma-encoded: the
// renderer works in linear light and encodes once at the end (raster_srgb.h). From
// there it can be
//   - written as PNG (8-bit grey or RGB; 1-bit grey for a bilevel picture, via libpng),
//     PGM, PPM or PBM (binary Netpbm), by the file's extension (raster_io.cpp);
//   - made bilevel for print — Wylie's and Bouknight's "half-tone" in the printer's
//     sense — by ordered (Bayer 8×8) or error-diffusion (Floyd–Steinberg) dithering,
//     in linear light, so that the mean grey level is kept (raster_dither.cpp);
//   - combined with its partner from a second eye into a red–cyan anaglyph (Dubois's
//     least-squares matrices) or a side-by-side pair (raster_stereo.cpp). Wylie 1967:
//     "the technique may be easily extended to stereo representation of half-tone
//     images."
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace avenues {

struct Image {
  int width = 0, height = 0;   ///< [px] >= 0
  int channels = 3;            ///< 1: grey, 3: RGB; each sample sRGB-encoded, 0..255
  bool bilevel = false;        ///< every sample is 0 (ink) or 255 (paper): a dithered half-tone
  std::vector<uint8_t> data;   ///< rows from the top, pixels left to right, `channels` bytes each

  /// Sets the size, keeping the storage when it is large enough (the samples are left
  /// as they were: a renderer writes every one of them).
  void resize(int w, int h, int c) {
    width = w;
    height = h;
    channels = c;
    bilevel = false;
    data.resize(size_t(w) * size_t(h) * size_t(c));
  }
  uint8_t* row(int y) { return data.data() + size_t(y) * size_t(width) * size_t(channels); }
  const uint8_t* row(int y) const { return data.data() + size_t(y) * size_t(width) * size_t(channels); }
};

/// How a picture is made bilevel for print.
enum class Dither : uint8_t {
  None,            ///< keep the grey levels
  Bayer,           ///< ordered dither with the 8×8 Bayer matrix: a regular screen, parallel
  FloydSteinberg,  ///< error diffusion (Floyd and Steinberg 1976): finer, row after row
};
const char* to_string(Dither d);
/// Parses "none", "bayer" or "fs" (also "floyd-steinberg"); false if it is none of them.
bool parse_dither(const std::string& s, Dither& out);

/// The picture made bilevel: grey (the luminance of an RGB picture), every sample 0 or
/// 255, the mean linear grey level kept. Dither::None returns the picture unchanged.
Image dither(const Image& picture, Dither how);

/// The picture as grey (Rec. 709 luminance, computed in linear light) or as RGB.
Image grey_of(const Image& picture);
Image rgb_of(const Image& picture);

struct ImageOptions {
  int png_level = 6;                         ///< zlib compression for PNG, 0..9
  Dither pbm_dither = Dither::FloydSteinberg;  ///< how a PBM file makes a grey picture bilevel
};

/// The extensions write_image understands, for messages: ".png, .pgm, .ppm, .pbm".
std::string raster_extensions();
/// True if the path's extension (any case) is one write_image understands.
bool is_raster_path(const std::string& path);

/// Writes the picture by the file's extension, all at once or not at all
/// (write_file_atomically): .png (8-bit grey or RGB, 1-bit for a bilevel picture),
/// .pgm (grey), .ppm (RGB), .pbm (1-bit; a picture not yet bilevel is dithered with
/// options.pbm_dither). Throws std::runtime_error naming the file for an unknown
/// extension or a failed write.
void write_image(const Image& picture, const std::string& path, const ImageOptions& options = {});

/// The bytes write_image() would write to `path`, without the write: for callers that must
/// have several files ready before writing any (write_files_atomically). Throws as it does.
std::string encode_image(const Image& picture, const std::string& path, const ImageOptions& options = {});

/// Reads a PNG (any bit depth and colour type libpng reads, without alpha) or a binary
/// Netpbm file (P4, P5, P6 of depth 255). A 1-bit file comes back bilevel. Throws
/// std::runtime_error naming the file otherwise.
Image read_image(const std::string& path);

/// How a stereo pair of pictures becomes one picture (for drawings, and for two separate
/// files, see StereoLayout in visibility/stereo.h).
enum class StereoComposite : uint8_t {
  Anaglyph,  ///< one red–cyan picture (left eye red), Dubois's least-squares projection
  Parallel,  ///< side by side, left eye's picture on the left (for parallel viewing)
  Cross,     ///< side by side, left eye's picture on the right (for cross-eyed viewing)
};
const char* to_string(StereoComposite l);
/// Parses "anaglyph", "parallel" or "cross"; false if it is none of them.
bool parse_stereo_composite(const std::string& s, StereoComposite& out);

/// Dubois 2001, "A projection method to generate anaglyph stereo images": the red–cyan
/// picture whose colours, seen through the filters, best match (in least squares) what
/// each eye should see. Computed in linear light; grey inputs are taken as RGB. The two
/// pictures must have the same size.
Image anaglyph(const Image& left, const Image& right);
/// The two pictures next to each other, `first` on the left; both become RGB if either is.
Image side_by_side(const Image& first, const Image& second);
/// The pair as `layout` asks (throws std::invalid_argument when the sizes differ).
Image stereo_composite(const Image& left, const Image& right, StereoComposite layout);

}  // namespace avenues
