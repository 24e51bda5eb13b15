// Avenues — grey and RGB forms of a picture, and the sRGB tables (see raster.h).
#include "render/raster.h"
#include "render/raster_srgb.h"

namespace avenues {

const SrgbEncoder& srgb_encoder() {
  static const SrgbEncoder encoder;
  return encoder;
}

const SrgbDecoder& srgb_decoder() {
  static const SrgbDecoder decoder;
  return decoder;
}

Image grey_of(const Image& picture) {
  if (picture.channels == 1) return picture;
  const SrgbDecoder& lin = srgb_decoder();
  const SrgbEncoder& enc = srgb_encoder();
  Image out;
  out.resize(picture.width, picture.height, 1);
  const size_t n = size_t(picture.width) * size_t(picture.height);
  for (size_t i = 0; i < n; ++i) {
    const uint8_t* p = &picture.data[3 * i];
    out.data[i] = enc(luminance(lin(p[0]), lin(p[1]), lin(p[2])));
  }
  return out;
}

Image rgb_of(const Image& picture) {
  if (picture.channels == 3) return picture;
  Image out;
  out.resize(picture.width, picture.height, 3);
  const size_t n = size_t(picture.width) * size_t(picture.height);
  for (size_t i = 0; i < n; ++i) out.data[3 * i] = out.data[3 * i + 1] = out.data[3 * i + 2] = picture.data[i];
  return out;
}

}  // namespace avenues
