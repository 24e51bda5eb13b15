// Avenues — picture files: PNG through libpng, binary Netpbm by hand (see raster.h).
//
// Every file is produced in memory first and written with write_file_atomically(), so a
// failure never leaves a partial picture behind.
#include <png.h>

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/atomic_file.h"
#include "core/file_name.h"
#include "render/raster.h"

namespace avenues {

namespace {

enum class Format { Png, Pgm, Ppm, Pbm, Unknown };

Format format_of(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".png") return Format::Png;
  if (ext == ".pgm") return Format::Pgm;
  if (ext == ".ppm") return Format::Ppm;
  if (ext == ".pbm") return Format::Pbm;
  return Format::Unknown;
}

// --- PNG -----------------------------------------------------------------------------

/// libpng reports errors through longjmp; the message is kept for the exception.
struct PngError {
  std::string message;
};

void on_png_error(png_structp png, png_const_charp message) {
  static_cast<PngError*>(png_get_error_ptr(png))->message = message;
  png_longjmp(png, 1);
}
void on_png_warning(png_structp, png_const_charp) {}

void append_bytes(png_structp png, png_bytep data, png_size_t n) {
  static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), n);
}
void no_flush(png_structp) {}

/// The picture's rows packed as PNG wants them: 1 bit per pixel for a bilevel grey
/// picture (most significant bit first, 1 = white), 8 bits per sample otherwise.
std::vector<std::vector<uint8_t>> png_rows(const Image& im, bool one_bit) {
  std::vector<std::vector<uint8_t>> rows(size_t(im.height));
  for (int y = 0; y < im.height; ++y) {
    const uint8_t* src = im.row(y);
    if (one_bit) {
      rows[size_t(y)].assign((size_t(im.width) + 7) / 8, 0);
      for (int x = 0; x < im.width; ++x)
        if (src[x] >= 128) rows[size_t(y)][size_t(x) / 8] |= uint8_t(0x80u >> (x % 8));
    } else {
      rows[size_t(y)].assign(src, src + size_t(im.width) * size_t(im.channels));
    }
  }
  return rows;
}

std::string encode_png(const Image& im, int level) {
  const bool one_bit = im.bilevel && im.channels == 1;
  std::vector<std::vector<uint8_t>> rows = png_rows(im, one_bit);
  std::vector<png_bytep> pointers;
  for (auto& r : rows) pointers.push_back(r.data());
  std::string bytes;
  PngError err;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &err, on_png_error, on_png_warning);
  if (!png) throw std::runtime_error("libpng: cannot create a writer");
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    throw std::runtime_error("libpng: " + (err.message.empty() ? std::string("out of memory") : err.message));
  }
  png_set_write_fn(png, &bytes, append_bytes, no_flush);
  png_set_compression_level(png, std::clamp(level, 0, 9));
  png_set_IHDR(png, info, png_uint_32(im.width), png_uint_32(im.height), one_bit ? 1 : 8,
               im.channels == 3 ? PNG_COLOR_TYPE_RGB : PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  png_write_image(png, pointers.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return bytes;
}

/// Reads a PNG held in memory.
struct PngSource {
  const std::string* bytes;
  size_t at = 0;
};
void read_bytes(png_structp png, png_bytep out, png_size_t n) {
  auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
  if (src->at + n > src->bytes->size()) png_error(png, "file is truncated");
  std::memcpy(out, src->bytes->data() + src->at, n);
  src->at += n;
}

Image decode_png(const std::string& bytes) {
  PngError err;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &err, on_png_error, on_png_warning);
  if (!png) throw std::runtime_error("libpng: cannot create a reader");
  png_infop info = png_create_info_struct(png);
  Image im;
  std::vector<png_bytep> pointers;
  PngSource src{&bytes};
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw std::runtime_error(err.message.empty() ? std::string("out of memory") : err.message);
  }
  png_set_read_fn(png, &src, read_bytes);
  png_read_info(png, info);
  const int depth = png_get_bit_depth(png, info);
  const int type = png_get_color_type(png, info);
  if (type & PNG_COLOR_MASK_ALPHA) png_error(png, "pictures with alpha are not read");
  const bool one_bit = depth == 1 && type == PNG_COLOR_TYPE_GRAY;
  // Everything to 8 bits per sample: palettes to RGB, low-depth grey expanded, 16 bits cut.
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (type == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (depth == 16) png_set_strip_16(png);
  png_read_update_info(png, info);
  const int channels = png_get_channels(png, info);
  if (channels != 1 && channels != 3) png_error(png, "unexpected channel count");
  im.resize(int(png_get_image_width(png, info)), int(png_get_image_height(png, info)), channels);
  for (int y = 0; y < im.height; ++y) pointers.push_back(im.row(y));
  png_read_image(png, pointers.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  im.bilevel = one_bit;
  return im;
}

// --- Netpbm --------------------------------------------------------------------------

std::string encode_pnm(const Image& im, Format f) {
  std::ostringstream head;
  const char* magic = f == Format::Pbm ? "P4" : f == Format::Pgm ? "P5" : "P6";
  head << magic << "\n" << im.width << " " << im.height << "\n";
  if (f != Format::Pbm) head << "255\n";
  std::string bytes = head.str();
  for (int y = 0; y < im.height; ++y) {
    const uint8_t* src = im.row(y);
    if (f == Format::Pbm) {  // 1 = black (ink), most significant bit first
      std::string row((size_t(im.width) + 7) / 8, '\0');
      for (int x = 0; x < im.width; ++x)
        if (src[x] < 128) row[size_t(x) / 8] = char(uint8_t(row[size_t(x) / 8]) | (0x80u >> (x % 8)));
      bytes += row;
    } else {
      bytes.append(reinterpret_cast<const char*>(src), size_t(im.width) * size_t(im.channels));
    }
  }
  return bytes;
}

Image decode_pnm(const std::string& bytes) {
  std::istringstream in(bytes);
  std::string magic;
  in >> magic;
  auto number = [&]() {
    in >> std::ws;
    while (in.peek() == '#') {  // comments run to the end of the line
      std::string skip;
      std::getline(in, skip);
      in >> std::ws;
    }
    long v = -1;
    if (!(in >> v) || v < 0 || v > 65535) throw std::runtime_error("bad Netpbm header");
    return int(v);
  };
  if (magic != "P4" && magic != "P5" && magic != "P6") throw std::runtime_error("not a binary PBM, PGM or PPM file");
  const int w = number(), h = number();
  const int maxval = magic == "P4" ? 1 : number();
  if (maxval != 1 && maxval != 255) throw std::runtime_error("only 8-bit Netpbm files are read");
  in.get();  // the single whitespace byte before the raster
  const size_t at = size_t(in.tellg());
  Image im;
  im.resize(w, h, magic == "P6" ? 3 : 1);
  const size_t row_bytes = magic == "P4" ? (size_t(w) + 7) / 8 : size_t(w) * size_t(im.channels);
  if (bytes.size() < at + row_bytes * size_t(h)) throw std::runtime_error("file is truncated");
  for (int y = 0; y < h; ++y) {
    const auto* src = reinterpret_cast<const uint8_t*>(bytes.data() + at + row_bytes * size_t(y));
    uint8_t* dst = im.row(y);
    if (magic == "P4") {
      for (int x = 0; x < w; ++x) dst[x] = (src[x / 8] & (0x80u >> (x % 8))) ? 0 : 255;
    } else {
      std::memcpy(dst, src, row_bytes);
    }
  }
  im.bilevel = magic == "P4";
  return im;
}

}  // namespace

std::string raster_extensions() { return ".png, .pgm, .ppm, .pbm"; }

bool is_raster_path(const std::string& path) { return format_of(path) != Format::Unknown; }

std::string encode_image(const Image& picture, const std::string& path, const ImageOptions& options) {
  const Format f = format_of(path);
  if (f == Format::Unknown)
    throw std::runtime_error("cannot write " + path + ": unknown picture format '" + lower_extension(path) +
                             "' (use " + raster_extensions() + ")");
  if (picture.width <= 0 || picture.height <= 0) throw std::runtime_error("cannot write " + path + ": empty picture");
  std::string bytes;
  try {
    switch (f) {
      case Format::Png: bytes = encode_png(picture, options.png_level); break;
      case Format::Pgm: bytes = encode_pnm(grey_of(picture), f); break;
      case Format::Ppm: bytes = encode_pnm(rgb_of(picture), f); break;
      case Format::Pbm:
        bytes = encode_pnm(picture.bilevel ? grey_of(picture)
                                           : dither(picture, options.pbm_dither == Dither::None
                                                                 ? Dither::FloydSteinberg
                                                                 : options.pbm_dither),
                           f);
        break;
      case Format::Unknown: break;
    }
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot write " + path + ": " + e.what());
  }
  return bytes;
}

void write_image(const Image& picture, const std::string& path, const ImageOptions& options) {
  write_file_atomically(path, encode_image(picture, path, options));
}

Image read_image(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read picture " + path + ": no such file");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  try {
    static const unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPngSignature, 8) == 0) return decode_png(bytes);
    return decode_pnm(bytes);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot read picture " + path + ": " + e.what());
  }
}

}  // namespace avenues
