// Fuzz target: the mean colour of a texture image (plans/image_colour.h), PNG by
// libpng and JPEG by libjpeg, from the bytes of a .sh3d entry. A refusal is a
// std::runtime_error naming the image; anything else (a crash, a hang, an exit from
// libjpeg's default error handler, memory out of proportion to the input) is a finding.
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "plans/image_colour.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    (void)avenues::mean_image_colour(std::string_view(reinterpret_cast<const char*>(data), size), "7");
  } catch (const std::runtime_error&) {
  }
  return 0;
}
