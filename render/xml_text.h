// Avenues — text for hand-written XML (the SVG drawings): one escaping rule for all.
#pragma once

#include <string>

namespace avenues {

/// `in` with XML's five special characters escaped; control characters other than tab
/// and newline (not allowed in XML 1.0) become spaces.
inline std::string xml_escape(const std::string& in) {
  std::string out;
  out.reserve(in.size());
  for (char ch : in) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += static_cast<unsigned char>(ch) < 0x20 && ch != '\t' && ch != '\n' ? ' ' : ch;
    }
  }
  return out;
}

}  // namespace avenues
