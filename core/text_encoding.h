// Avenues — text as Windows tools often save it: UTF-16 with a byte-order mark, or UTF-8
// with one. Readers of text formats (an OBJ, Irrlicht's XML, the text formats Assimp reads)
// take it as the UTF-8 it holds. Part of core/, below every other module.
#pragma once

#include <string>
#include <string_view>

namespace avenues {

/// Whether the bytes begin with a UTF-16 byte-order mark (FF FE little-endian, FE FF big).
bool utf16_marked(std::string_view bytes);

/// The text of `bytes` as UTF-8: UTF-16 told by its byte-order mark (either order)
/// converted, a UTF-8 byte-order mark dropped, other bytes as they are. In UTF-16, a
/// surrogate without its other half becomes U+FFFD and an odd last byte is dropped.
std::string utf8_of_text(std::string_view bytes);

}  // namespace avenues
