// Avenues — telling a file's format by its content (plans/formats/file_format.h).
#include "plans/formats/file_format.h"

#include "core/file_name.h"
#include "plans/mesh.h"

#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

namespace avenues {
namespace {

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

/// The head without a UTF-8 byte order mark and leading white space.
std::string_view trimmed(std::string_view s) {
  if (starts_with(s, "\xEF\xBB\xBF")) s.remove_prefix(3);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  return s;
}

/// The first lines of `head`, each without surrounding white space.
std::vector<std::string> lines_of(std::string_view head, size_t most) {
  std::vector<std::string> out;
  std::istringstream in{std::string(head)};
  std::string line;
  while (out.size() < most && std::getline(in, line)) {
    size_t a = 0, b = line.size();
    while (a < b && std::isspace(static_cast<unsigned char>(line[a]))) ++a;
    while (b > a && std::isspace(static_cast<unsigned char>(line[b - 1]))) --b;
    out.push_back(line.substr(a, b - a));
  }
  return out;
}

/// An ASCII DXF file is pairs of lines, a group code (an integer) and a value; it opens
/// with "0 / SECTION", possibly after "999 / comment" pairs.
bool looks_like_dxf(std::string_view head) {
  const std::vector<std::string> l = lines_of(head, 16);
  for (size_t i = 0; i + 1 < l.size(); i += 2) {
    if (l[i] == "0") return l[i + 1] == "SECTION";
    if (l[i] != "999") return false;
  }
  return false;
}

/// OBJ: the first line that is not a comment is a vertex, a face or a grouping statement,
/// words and numbers with no '=' (which would make it TOML).
bool looks_like_obj(std::string_view head) {
  for (const std::string& l : lines_of(head, 64)) {
    if (l.empty() || l[0] == '#') continue;
    if (l.find('=') != std::string::npos) return false;
    // The first word, then white space (no std::regex: its matcher recurses per character).
    const size_t end = l.find_first_of(" \t");
    if (end == std::string::npos) return false;
    const std::string_view word = std::string_view(l).substr(0, end);
    for (const char* statement : {"v", "vt", "vn", "f", "o", "g", "s", "mtllib", "usemtl"})
      if (word == statement) return true;
    return false;
  }
  return false;
}

bool is_text(std::string_view head) {
  for (char ch : head) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == 0 || (c < 32 && c != '\t' && c != '\n' && c != '\r' && c != '\f')) return false;
  }
  return true;
}

}  // namespace

const char* format_name(FileFormat f) {
  switch (f) {
    case FileFormat::Unknown: return "a file of unknown format";
    case FileFormat::Toml: return "a TOML plan";
    case FileFormat::Cells: return "a saved cells file";
    case FileFormat::DoomWad: return "a Doom WAD";
    case FileFormat::SweetHome: return "a Sweet Home 3D home";
    case FileFormat::Off: return "an OFF mesh";
    case FileFormat::Obj: return "an OBJ mesh";
    case FileFormat::Ply: return "a PLY mesh";
    case FileFormat::Stl: return "an STL mesh";
    case FileFormat::Crow: return "a Crow object";
    case FileFormat::Model: return "a 3D model";
    case FileFormat::Ifc: return "an IFC model";
    case FileFormat::Dxf: return "a DXF drawing";
    case FileFormat::FloorplanVectors: return "floor-plan annotations";
    case FileFormat::Png: return "a PNG image";
    case FileFormat::Jpeg: return "a JPEG image";
    case FileFormat::Pdf: return "a PDF document";
    case FileFormat::Gzip: return "a gzip-compressed file";
  }
  return "a file of unknown format";
}

bool is_mesh_format(FileFormat f) {
  return f == FileFormat::Off || f == FileFormat::Obj || f == FileFormat::Ply || f == FileFormat::Stl;
}

FileFormat format_of_extension(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".toml") return FileFormat::Toml;
  if (ext == ".cells") return FileFormat::Cells;
  if (ext == ".wad") return FileFormat::DoomWad;
  if (ext == ".sh3d" || ext == ".xml") return FileFormat::SweetHome;
  if (ext == ".off") return FileFormat::Off;
  if (ext == ".obj") return FileFormat::Obj;
  if (ext == ".ply") return FileFormat::Ply;
  if (ext == ".stl") return FileFormat::Stl;
  if (ext == ".crow") return FileFormat::Crow;
  if (ext == ".ifc" || ext == ".ifczip") return FileFormat::Ifc;
  if (ext == ".dxf") return FileFormat::Dxf;
  if (ext == ".png") return FileFormat::Png;
  if (ext == ".jpg" || ext == ".jpeg") return FileFormat::Jpeg;
  if (ext == ".pdf") return FileFormat::Pdf;
  if (ext == ".gz") return FileFormat::Gzip;
  return FileFormat::Unknown;
}

FileFormat detect_format(const std::string& path, const std::string& head, uint64_t size) {
  const std::string_view h(head);
  // Signatures: these decide whatever the name says.
  if (h.size() >= 8 && std::memcmp(h.data(), "AVCELLS\0", 8) == 0) return FileFormat::Cells;
  if (starts_with(h, "PK\x03\x04")) return FileFormat::SweetHome;
  if (starts_with(h, "IWAD") || starts_with(h, "PWAD")) return FileFormat::DoomWad;
  if (starts_with(h, "\x89PNG\r\n\x1a\n")) return FileFormat::Png;
  if (starts_with(h, "\xFF\xD8\xFF")) return FileFormat::Jpeg;
  if (starts_with(h, "%PDF-")) return FileFormat::Pdf;
  if (starts_with(h, "\x1F\x8B")) return FileFormat::Gzip;
  if (starts_with(h, "AutoCAD Binary DXF")) return FileFormat::Dxf;
  const std::string_view t = trimmed(h);
  if (starts_with(t, "ISO-10303-21;")) return FileFormat::Ifc;
  if (starts_with(h, "ply\n") || starts_with(h, "ply\r\n")) return FileFormat::Ply;
  if (looks_like_dxf(t)) return FileFormat::Dxf;
  {
    const std::vector<std::string> first = lines_of(t, 1);
    if (!first.empty() && is_off_keyword(std::string_view(first[0]).substr(0, first[0].find_first_of(" \t"))))
      return FileFormat::Off;
  }
  if (starts_with(t, "<?xml") || starts_with(t, "<home")) {
    if (t.find("<home") != std::string_view::npos) return FileFormat::SweetHome;
  }
  // A binary STL: an 80-byte header, a u32 triangle count, 50 bytes per triangle.
  if (size >= 84 && h.size() >= 84) {
    uint32_t n = 0;
    for (int k = 3; k >= 0; --k) n = (n << 8) | static_cast<unsigned char>(h[80 + size_t(k)]);
    if (size == 84 + 50 * uint64_t(n)) return FileFormat::Stl;
  }
  // No signature: the extension, then what the text looks like.
  // (A TOML plan is text: binary bytes under a .toml name are no plan Avenues knows.)
  if (const FileFormat by_name = format_of_extension(path); by_name != FileFormat::Unknown)
    return by_name == FileFormat::Toml && !is_text(h) ? FileFormat::Unknown : by_name;
  if (starts_with(t, "solid") && t.find("facet") != std::string_view::npos) return FileFormat::Stl;
  if (looks_like_obj(t)) return FileFormat::Obj;
  if (is_text(h)) return FileFormat::Toml;
  return FileFormat::Unknown;
}

FileFormat detect_format(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return format_of_extension(path);
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  head.resize(size_t(in.gcount()));
  const uint64_t size = std::filesystem::file_size(path, ec);
  return detect_format(path, head, ec ? head.size() : size);
}

}  // namespace avenues
