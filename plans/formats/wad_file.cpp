// Avenues — reading a WAD's header, directory and lumps (see wad_file.h).
#include "plans/formats/wad_file.h"

#include <algorithm>
#include <fstream>
#include <set>

namespace avenues {

namespace {

int32_t le32(const uint8_t* p) {
  return int32_t(uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24);
}

/// The lumps that may follow a Doom or Hexen map's marker (the binary formats).
bool is_binary_map_lump(const std::string& n) {
  static const std::set<std::string> names{"THINGS",  "LINEDEFS", "SIDEDEFS", "VERTEXES", "SEGS",     "SSECTORS",
                                           "NODES",   "SECTORS",  "REJECT",   "BLOCKMAP", "BEHAVIOR", "SCRIPTS"};
  return names.count(n) > 0;
}

}  // namespace

WadFile open_wad(const std::string& path) {
  const SourceLoc at{path, 0, 0, ""};
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PlanError(at, "cannot open the file");
  in.seekg(0, std::ios::end);
  WadFile wad;
  wad.path = path;
  wad.file_size = int64_t(in.tellg());
  in.seekg(0);
  uint8_t header[12];
  if (wad.file_size < 12 || !in.read(reinterpret_cast<char*>(header), 12))
    throw PlanError(at, "not a WAD file: " + std::to_string(wad.file_size) + " bytes, shorter than a WAD's header");
  const std::string magic(reinterpret_cast<const char*>(header), 4);
  if (magic != "IWAD" && magic != "PWAD") {
    std::string shown;
    for (char ch : magic) shown += (ch >= 32 && ch < 127) ? ch : '?';
    throw PlanError(at, "not a WAD file: it starts with \"" + shown + "\", not IWAD or PWAD");
  }
  wad.iwad = magic == "IWAD";
  const int64_t count = le32(header + 4), dir = le32(header + 8);
  if (count < 0 || dir < 0 || dir + 16 * count > wad.file_size)
    throw PlanError(at, "the directory (" + std::to_string(count) + " lumps at byte " + std::to_string(dir) +
                            ") lies beyond the end of the file (" + std::to_string(wad.file_size) +
                            " bytes): truncated or not a WAD");
  std::vector<uint8_t> entries(size_t(16 * count));
  in.seekg(dir);
  if (count > 0 && !in.read(reinterpret_cast<char*>(entries.data()), std::streamsize(entries.size())))
    throw PlanError(at, "cannot read the directory");
  wad.lumps.resize(size_t(count));
  for (size_t i = 0; i < size_t(count); ++i) {
    const uint8_t* e = entries.data() + 16 * i;
    WadLump& l = wad.lumps[i];
    l.offset = le32(e);
    l.size = le32(e + 4);
    for (int k = 0; k < 8 && e[8 + k] != 0; ++k) l.name += char(e[8 + k]);
  }
  return wad;
}

std::vector<WadMap> WadFile::maps() const {
  std::vector<WadMap> out;
  for (size_t i = 0; i + 1 < lumps.size(); ++i) {
    const std::string& next = lumps[i + 1].name;
    if (next == "TEXTMAP") {  // UDMF: everything up to ENDMAP
      size_t e = i + 1;
      while (e < lumps.size() && lumps[e].name != "ENDMAP") ++e;
      out.push_back({lumps[i].name, i, std::min(e + 1, lumps.size())});
      i = e;
    } else if (next == "THINGS") {
      size_t e = i + 1;
      while (e < lumps.size() && is_binary_map_lump(lumps[e].name)) ++e;
      out.push_back({lumps[i].name, i, e});
      i = e - 1;
    }
  }
  return out;
}

long WadFile::find(const std::string& name, size_t from, size_t to) const {
  for (size_t i = from; i < std::min(to, lumps.size()); ++i)
    if (lumps[i].name == name) return long(i);
  return -1;
}

std::vector<uint8_t> WadFile::read(size_t i, const std::string& where) const {
  const WadLump& l = lumps.at(i);
  const SourceLoc at{where, 0, 0, "lump " + l.name};
  if (l.offset < 0 || l.size < 0 || l.offset + l.size > file_size)
    throw PlanError(at, std::to_string(l.size) + " bytes at byte " + std::to_string(l.offset) +
                            " lie beyond the end of the file (" + std::to_string(file_size) + " bytes): truncated");
  std::vector<uint8_t> bytes(size_t(l.size));
  std::ifstream in(path, std::ios::binary);
  in.seekg(l.offset);
  if (!in || (l.size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(l.size))))
    throw PlanError(at, "cannot read the lump");
  return bytes;
}

}  // namespace avenues
