// Avenues — text as Windows tools often save it: UTF-16 with a byte-order mark, or UTF-8
// with one. Readers of text formats (an OBJ, Irrlicht's XML, the text formats Assimp reads)
// take it as the UTF-8 it holds. Part of core/, below every other module.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace avenues {

/// Appends code point `cp` to `out` as UTF-8; false (nothing appended) for a surrogate or
/// a number beyond U+10FFFF, which are no characters.
bool append_utf8(std::string& out, uint32_t cp);

/// UTF-16 code units as UTF-8: a surrogate pair is one character, a surrogate without its
/// other half U+FFFD (as Java strings and Windows file names may hold one).
std::string utf8_of_utf16(std::span<const uint16_t> units);

/// Whether the bytes begin with a UTF-16 byte-order mark (FF FE little-endian, FE FF big).
bool utf16_marked(std::string_view bytes);

/// The text of `bytes` as UTF-8: UTF-16 told by its byte-order mark (either order)
/// converted, a UTF-8 byte-order mark dropped, other bytes as they are. In UTF-16, a
/// surrogate without its other half becomes U+FFFD and an odd last byte is dropped.
std::string utf8_of_text(std::string_view bytes);

}  // namespace avenues
