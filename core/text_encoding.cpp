// Avenues — UTF-16 and byte-order marks (see text_encoding.h).
#include "core/text_encoding.h"

#include <cstdint>
#include <vector>

namespace avenues {

bool append_utf8(std::string& out, uint32_t cp) {
  if (cp > 0x10FFFF || (cp >= 0xD800 && cp < 0xE000)) return false;
  if (cp < 0x80) {
    out += char(cp);
  } else if (cp < 0x800) {
    out += char(0xC0 | (cp >> 6));
    out += char(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += char(0xE0 | (cp >> 12));
    out += char(0x80 | ((cp >> 6) & 0x3F));
    out += char(0x80 | (cp & 0x3F));
  } else {
    out += char(0xF0 | (cp >> 18));
    out += char(0x80 | ((cp >> 12) & 0x3F));
    out += char(0x80 | ((cp >> 6) & 0x3F));
    out += char(0x80 | (cp & 0x3F));
  }
  return true;
}

std::string utf8_of_utf16(std::span<const uint16_t> units) {
  std::string out;
  out.reserve(units.size());
  for (size_t i = 0; i < units.size(); ++i) {
    uint32_t c = units[i];
    if (c >= 0xD800 && c < 0xDC00 && i + 1 < units.size() && units[i + 1] >= 0xDC00 && units[i + 1] < 0xE000)
      c = 0x10000 + ((c - 0xD800) << 10) + (units[++i] - 0xDC00u);
    else if (c >= 0xD800 && c < 0xE000)
      c = 0xFFFD;
    append_utf8(out, c);
  }
  return out;
}

bool utf16_marked(std::string_view bytes) {
  return bytes.size() >= 2 && ((uint8_t(bytes[0]) == 0xFF && uint8_t(bytes[1]) == 0xFE) ||
                               (uint8_t(bytes[0]) == 0xFE && uint8_t(bytes[1]) == 0xFF));
}

std::string utf8_of_text(std::string_view bytes) {
  const auto b = [bytes](size_t i) { return uint32_t(uint8_t(bytes[i])); };
  if (bytes.size() >= 3 && b(0) == 0xEF && b(1) == 0xBB && b(2) == 0xBF) return std::string(bytes.substr(3));
  if (!utf16_marked(bytes)) return std::string(bytes);
  const bool little = b(0) == 0xFF;
  std::vector<uint16_t> units;
  units.reserve(bytes.size() / 2);
  for (size_t i = 2; i + 1 < bytes.size(); i += 2) units.push_back(uint16_t(little ? b(i) | b(i + 1) << 8 : b(i) << 8 | b(i + 1)));
  return utf8_of_utf16(units);
}

}  // namespace avenues
