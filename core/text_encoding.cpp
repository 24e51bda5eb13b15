// Avenues — UTF-16 and byte-order marks (see text_encoding.h).
#include "core/text_encoding.h"

#include <cstdint>

namespace avenues {

namespace {

/// Code point c appended to `out` as UTF-8.
void append_utf8(std::string& out, uint32_t c) {
  if (c < 0x80) {
    out += char(c);
  } else if (c < 0x800) {
    out += char(0xC0 | (c >> 6));
    out += char(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += char(0xE0 | (c >> 12));
    out += char(0x80 | ((c >> 6) & 0x3F));
    out += char(0x80 | (c & 0x3F));
  } else {
    out += char(0xF0 | (c >> 18));
    out += char(0x80 | ((c >> 12) & 0x3F));
    out += char(0x80 | ((c >> 6) & 0x3F));
    out += char(0x80 | (c & 0x3F));
  }
}

}  // namespace

bool utf16_marked(std::string_view bytes) {
  return bytes.size() >= 2 && ((uint8_t(bytes[0]) == 0xFF && uint8_t(bytes[1]) == 0xFE) ||
                               (uint8_t(bytes[0]) == 0xFE && uint8_t(bytes[1]) == 0xFF));
}

std::string utf8_of_text(std::string_view bytes) {
  const auto b = [bytes](size_t i) { return uint32_t(uint8_t(bytes[i])); };
  if (bytes.size() >= 3 && b(0) == 0xEF && b(1) == 0xBB && b(2) == 0xBF) return std::string(bytes.substr(3));
  if (!utf16_marked(bytes)) return std::string(bytes);
  const bool little = b(0) == 0xFF;
  const auto unit = [&](size_t i) { return little ? b(i) | b(i + 1) << 8 : b(i) << 8 | b(i + 1); };
  std::string out;
  out.reserve(bytes.size() / 2);
  for (size_t i = 2; i + 1 < bytes.size(); i += 2) {
    uint32_t c = unit(i);
    if (c >= 0xD800 && c < 0xDC00 && i + 3 < bytes.size() && unit(i + 2) >= 0xDC00 && unit(i + 2) < 0xE000) {
      c = 0x10000 + ((c - 0xD800) << 10) + (unit(i + 2) - 0xDC00);
      i += 2;
    } else if (c >= 0xD800 && c < 0xE000) {
      c = 0xFFFD;
    }
    append_utf8(out, c);
  }
  return out;
}

}  // namespace avenues
