// Avenues — the mean colour of an image (see image_colour.h).
#include "plans/image_colour.h"

#include <jpeglib.h>
#include <png.h>
#include <stb_image.h>

#include <csetjmp>
#include <cstdio>
#include <climits>
#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/srgb.h"

namespace avenues {
namespace {

/// Sums of linear components weighted by alpha, and of the weights.
struct Sums {
  double rgb[3] = {0, 0, 0};
  double weight = 0;
  double linear[256];
  Sums() {
    for (int i = 0; i < 256; ++i) linear[i] = linear_from_srgb(i / 255.0);
  }
  void add(const unsigned char* px, double alpha) {
    for (int k = 0; k < 3; ++k) rgb[k] += alpha * linear[px[k]];
    weight += alpha;
  }
};

std::array<double, 3> mean_of(const Sums& s, const std::string& name) {
  if (!(s.weight > 0)) throw std::runtime_error(name + ": the image is wholly transparent");
  return {s.rgb[0] / s.weight, s.rgb[1] / s.weight, s.rgb[2] / s.weight};
}

std::array<double, 3> mean_png(std::string_view bytes, const std::string& name) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
    throw std::runtime_error(name + ": not a readable PNG image (" + image.message + ")");
  if ((long long)image.width * image.height > kMaxImagePixels) {
    png_image_free(&image);
    throw std::runtime_error(name + ": a PNG image of " + std::to_string(image.width) + " x " +
                             std::to_string(image.height) + " pixels, more than Avenues reads");
  }
  image.format = PNG_FORMAT_RGBA;  // 8-bit sRGB with alpha, whatever the file holds
  std::vector<unsigned char> px(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, px.data(), 0, nullptr)) {
    const std::string why = image.message;
    png_image_free(&image);
    throw std::runtime_error(name + ": the PNG image is damaged (" + why + ")");
  }
  Sums s;
  for (size_t i = 0; i + 3 < px.size(); i += 4) s.add(&px[i], px[i + 3] / 255.0);
  return mean_of(s, name);
}

/// libjpeg reports a fatal error by calling error_exit, which must not return: jump back.
struct JpegError {
  jpeg_error_mgr mgr;
  std::jmp_buf back;
  char message[JMSG_LENGTH_MAX];
};
void on_jpeg_error(j_common_ptr cinfo) {
  JpegError* e = reinterpret_cast<JpegError*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, e->message);
  std::longjmp(e->back, 1);
}
void on_jpeg_message(j_common_ptr, int) {}  // warnings (a corrupt byte) are not reported

/// Decodes row by row into `row` (sized by the caller once the header is read); the
/// sums live outside so that nothing with a destructor is skipped by the jump.
bool decode_jpeg(std::string_view bytes, Sums& s, std::vector<unsigned char>& row, JpegError& err, long long& pixels) {
  jpeg_decompress_struct cinfo;
  cinfo.err = jpeg_std_error(&err.mgr);
  err.mgr.error_exit = on_jpeg_error;
  err.mgr.emit_message = on_jpeg_message;
  if (setjmp(err.back)) {
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  jpeg_create_decompress(&cinfo);
  cinfo.mem->max_memory_to_use = 256L << 20;  // a progressive image keeps all its coefficients: cap them
  jpeg_mem_src(&cinfo, reinterpret_cast<const unsigned char*>(bytes.data()), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&cinfo, TRUE);
  pixels = (long long)cinfo.image_width * cinfo.image_height;
  if (pixels > kMaxImagePixels) {
    jpeg_destroy_decompress(&cinfo);
    return true;  // the caller refuses it
  }
  cinfo.out_color_space = JCS_RGB;  // grey and CMYK/YCCK are converted (or refused: an error)
  jpeg_start_decompress(&cinfo);
  row.resize(size_t(cinfo.output_width) * 3);
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW r = row.data();
    jpeg_read_scanlines(&cinfo, &r, 1);
    for (size_t i = 0; i + 2 < row.size(); i += 3) s.add(&row[i], 1.0);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return true;
}

std::array<double, 3> mean_jpeg(std::string_view bytes, const std::string& name) {
  Sums s;
  std::vector<unsigned char> row;
  JpegError err;
  err.message[0] = 0;
  long long pixels = 0;
  if (!decode_jpeg(bytes, s, row, err, pixels))
    throw std::runtime_error(name + ": not a readable JPEG image (" + err.message + ")");
  if (pixels > kMaxImagePixels)
    throw std::runtime_error(name + ": a JPEG image of " + std::to_string(pixels) + " pixels, more than Avenues reads");
  return mean_of(s, name);
}

/// Any other format stb_image reads (TGA, which older models' textures often are: a
/// COLLADA duck's, a 3DS's; BMP, GIF, PSD, PNM): its size checked before it is decoded.
std::optional<std::array<double, 3>> mean_other(std::string_view bytes, const std::string& name) {
  if (bytes.size() > size_t(INT32_MAX)) return std::nullopt;
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int length = int(bytes.size());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(data, length, &w, &h, &channels)) return std::nullopt;
  if (w <= 0 || h <= 0 || (long long)w * h > kMaxImagePixels)
    throw std::runtime_error(name + ": an image of " + std::to_string(w) + " x " + std::to_string(h) +
                             " pixels, more than Avenues reads");
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, length, &w, &h, &channels, 4),
                                                    stbi_image_free);
  if (!pixels) {
    const char* why = stbi_failure_reason();
    throw std::runtime_error(name + ": not a readable image (" + (why ? why : "stb_image gives no reason") + ")");
  }
  return mean_pixels_colour({pixels.get(), 4 * size_t(w) * size_t(h)}, name);
}

}  // namespace

std::array<double, 3> mean_pixels_colour(std::span<const unsigned char> rgba, const std::string& name) {
  Sums s;
  for (size_t i = 0; i + 4 <= rgba.size(); i += 4) s.add(&rgba[i], rgba[i + 3] / 255.0);
  return mean_of(s, name);
}

std::array<double, 3> mean_image_colour(std::string_view bytes, const std::string& name) {
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return mean_png(bytes, name);
  if (bytes.size() >= 3 && std::memcmp(bytes.data(), "\xFF\xD8\xFF", 3) == 0) return mean_jpeg(bytes, name);
  if (const std::optional<std::array<double, 3>> other = mean_other(bytes, name)) return *other;
  throw std::runtime_error(name + ": not an image Avenues reads (PNG, JPEG, TGA, BMP, GIF, PSD or PNM)");
}

}  // namespace avenues
