// Avenues — a zip archive cut short, read as far as it is whole (see zip_salvage.h).
#include "plans/formats/zip_salvage.h"

#include <cstdint>

namespace avenues {

namespace {

constexpr uint32_t kLocal = 0x04034b50, kDescriptor = 0x08074b50, kCentral = 0x02014b50, kEnd = 0x06054b50;

uint32_t le32(std::string_view b, size_t at) {
  return uint32_t(uint8_t(b[at])) | uint32_t(uint8_t(b[at + 1])) << 8 | uint32_t(uint8_t(b[at + 2])) << 16 |
         uint32_t(uint8_t(b[at + 3])) << 24;
}
uint16_t le16(std::string_view b, size_t at) { return uint16_t(uint8_t(b[at]) | uint8_t(b[at + 1]) << 8); }
void put16(std::string& out, uint32_t v) { out += char(v & 0xFF), out += char((v >> 8) & 0xFF); }
void put32(std::string& out, uint32_t v) { put16(out, v & 0xFFFF), put16(out, v >> 16); }

struct Entry {
  size_t header = 0;  ///< offset of its local header
  uint16_t flags = 0, method = 0, time = 0, date = 0;
  uint32_t crc = 0, csize = 0, usize = 0;
  std::string name;
};

}  // namespace

std::optional<SalvagedZip> salvage_zip(std::string_view b) {
  SalvagedZip out;
  std::vector<Entry> whole;
  size_t at = 0, end = 0;
  while (at + 30 <= b.size() && le32(b, at) == kLocal) {
    Entry e;
    e.header = at;
    e.flags = le16(b, at + 6), e.method = le16(b, at + 8), e.time = le16(b, at + 10), e.date = le16(b, at + 12);
    e.crc = le32(b, at + 14), e.csize = le32(b, at + 18), e.usize = le32(b, at + 22);
    const size_t name_len = le16(b, at + 26), extra_len = le16(b, at + 28);
    const size_t data = at + 30 + name_len + extra_len;
    if (data > b.size()) break;
    e.name = std::string(b.substr(at + 30, name_len));
    out.first_lost = e.name;
    size_t next = 0;
    if (e.flags & 0x08) {
      // Sizes follow the data, in a descriptor (Java writes its signature): the first
      // signature whose compressed size is the distance from the data's start.
      size_t p = data;
      for (;;) {
        p = b.find("PK\x07\x08", p);
        if (p == std::string_view::npos || p + 16 > b.size()) break;
        if (le32(b, p) == kDescriptor && le32(b, p + 8) == p - data) break;
        ++p;
      }
      if (p == std::string_view::npos || p + 16 > b.size()) break;
      e.crc = le32(b, p + 4), e.csize = le32(b, p + 8), e.usize = le32(b, p + 12);
      next = p + 16;
    } else {
      next = data + e.csize;
      if (next > b.size()) break;
    }
    whole.push_back(std::move(e));
    out.first_lost.clear();
    end = at = next;
  }
  if (whole.empty()) return std::nullopt;
  out.bytes = std::string(b.substr(0, end));
  const size_t directory = out.bytes.size();
  for (const Entry& e : whole) {
    put32(out.bytes, kCentral);
    put16(out.bytes, 20), put16(out.bytes, 20);  // made by, needed: 2.0
    put16(out.bytes, e.flags), put16(out.bytes, e.method), put16(out.bytes, e.time), put16(out.bytes, e.date);
    put32(out.bytes, e.crc), put32(out.bytes, e.csize), put32(out.bytes, e.usize);
    put16(out.bytes, uint32_t(e.name.size())), put16(out.bytes, 0), put16(out.bytes, 0);  // name, extra, comment
    put16(out.bytes, 0), put16(out.bytes, 0), put32(out.bytes, 0);                       // disk, attributes
    put32(out.bytes, uint32_t(e.header));
    out.bytes += e.name;
    out.kept.push_back(e.name);
  }
  const size_t directory_size = out.bytes.size() - directory;
  put32(out.bytes, kEnd);
  put16(out.bytes, 0), put16(out.bytes, 0);
  put16(out.bytes, uint32_t(whole.size())), put16(out.bytes, uint32_t(whole.size()));
  put32(out.bytes, uint32_t(directory_size)), put32(out.bytes, uint32_t(directory));
  put16(out.bytes, 0);
  return out;
}

}  // namespace avenues
