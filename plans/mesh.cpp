// Avenues — reading meshes with OpenMesh (see mesh.h).
#include "plans/mesh.h"
#include "core/file_name.h"
#include "core/text_encoding.h"
#include "plans/assimp_reader.h"
#include "plans/obj_materials.h"
#include "plans/polygon_triangulation.h"
#include "core/angles.h"
#include "core/float_rounding.h"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include "plans/quiet_openmesh.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <vector>
#include <map>
#include <optional>
#include <unordered_map>
#include <stdexcept>

namespace avenues {

namespace {
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<>;

/// A turn about x, then y, then z (degrees), its sines and cosines taken once: placing a
/// mesh turns every vertex, corner normal and polygon's light point by one.
struct Rotation {
  double cx, sx, cy, sy, cz, sz;
  explicit Rotation(Vec3 deg) {
    const double ax = rad_from_deg(deg.x), ay = rad_from_deg(deg.y), az = rad_from_deg(deg.z);
    cx = std::cos(ax), sx = std::sin(ax), cy = std::cos(ay), sy = std::sin(ay), cz = std::cos(az), sz = std::sin(az);
  }
  Vec3 operator()(Vec3 p) const {
    Vec3 q{p.x, cx * p.y - sx * p.z, sx * p.y + cx * p.z};
    q = {cy * q.x + sy * q.z, q.y, -sy * q.x + cy * q.z};
    return {cz * q.x - sz * q.y, sz * q.x + cz * q.y, q.z};
  }
};
}  // namespace

namespace {

bool whole_integer(const std::string& t, long long& v) {
  char* end = nullptr;
  v = std::strtoll(t.c_str(), &end, 10);
  return !t.empty() && *end == '\0';
}

bool whole_number(const std::string& t) {
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  return !t.empty() && *end == '\0' && std::isfinite(v);
}

/// OpenMesh keeps coordinates in single precision: a number beyond it would become
/// infinite (and the faces around it vanish). The one rule of every mesh reader: a vertex
/// that is not a finite number of that range, or a face naming a vertex there is not,
/// refuses the file with a message naming the line (or triangle).
constexpr double kMaxCoordinate = 1e30;
bool coordinate(const std::string& t) {
  char* end = nullptr;
  const double v = std::strtod(t.c_str(), &end);
  return !t.empty() && *end == '\0' && std::isfinite(v) && std::abs(v) <= kMaxCoordinate;
}
const std::string kCoordinateRule = "is not a coordinate (a finite number of magnitude at most 1e30)";

/// An OBJ file's vertices and faces, checked by the rule above, and made readable the way
/// OBJ's own tools are lenient: a vertex that is no coordinate (every "v" line has three, or
/// four), or a face or line corner that names no vertex (1-based, or negative: counted back
/// from the last vertex so far), costs its element, not the file. A bad vertex's line
/// becomes a copy of a good vertex (so that the numbering stays, and the extent too) and
/// every face using it goes; a bad face's line goes. Returns the text to read; `dropped`
/// gets one line per element dropped ("line 11: '3.1+e2' is not a coordinate ..."), and
/// `vertices`, where given, every vertex of the text to read in double (see mesh_of_openmesh).
std::string readable_obj(const std::string& bytes, std::vector<std::string>& dropped,
                         std::vector<Vec3>* vertices_in_double = nullptr) {
  // Positive indices may name vertices listed later; negative ones count back from here.
  // A first pass finds every vertex and which are bad, since a face may name one listed later.
  std::vector<uint8_t> bad_vertex(1, 0);  // 1-based
  std::string stand_in;                   // the first good vertex's line
  {
    std::istringstream count(bytes);
    std::string l;
    while (std::getline(count, l)) {
      std::istringstream ls(l.substr(0, l.find('#')));
      std::string key, t;
      if (!(ls >> key) || key != "v") continue;
      int n = 0;
      while (n < 3 && ls >> t && coordinate(t)) ++n;
      bad_vertex.push_back(n < 3);
      if (n == 3 && stand_in.empty()) stand_in = l.substr(0, l.find('#'));
    }
  }
  const long long total = (long long)bad_vertex.size() - 1;
  if (stand_in.empty()) stand_in = "v 0 0 0";
  Vec3 stand_in_at;
  {
    std::istringstream ls(stand_in);
    std::string key;
    ls >> key >> stand_in_at.x >> stand_in_at.y >> stand_in_at.z;
  }
  if (vertices_in_double) vertices_in_double->clear();
  std::ostringstream out;
  std::istringstream in(bytes);
  std::string line;
  int lineno = 0;
  long long vertices = 0;
  while (std::getline(in, line)) {
    ++lineno;
    std::string body = line;
    const size_t hash = body.find('#');
    if (hash != std::string::npos) body.erase(hash);
    std::istringstream ls(body);
    std::string key, why;
    ls >> key;  // stays empty on a blank line
    if (key == "v") {
      std::string t;
      double at[3] = {0, 0, 0};
      int n = 0;
      while (n < 3 && why.empty() && ls >> t) {
        if (!coordinate(t)) why = "'" + t + "' " + kCoordinateRule;
        else at[n] = std::strtod(t.c_str(), nullptr);
        ++n;
      }
      if (why.empty() && n < 3) why = "a vertex needs three coordinates";
      ++vertices;
      if (vertices_in_double) vertices_in_double->push_back(why.empty() ? Vec3{at[0], at[1], at[2]} : stand_in_at);
      if (!why.empty()) {
        dropped.push_back("line " + std::to_string(lineno) + ": " + why + ": the vertex is dropped, with its faces");
        out << stand_in << '\n';
        continue;
      }
    } else if (key == "f" || key == "l") {
      std::string t;
      while (why.empty() && ls >> t) {
        long long v = 0;
        const std::string index = t.substr(0, t.find('/'));
        if (!whole_integer(index, v) || v == 0 || v > total || v < -vertices)
          why = "face corner '" + t + "' names no vertex (the file has " + std::to_string(total) + ", " +
                std::to_string(vertices) + " of them before this line)";
        else if (bad_vertex[size_t(v > 0 ? v : vertices + 1 + v)])
          why = "face corner '" + t + "' names a vertex that is dropped";
      }
      if (!why.empty()) {
        dropped.push_back("line " + std::to_string(lineno) + ": " + why + ": the " +
                          (key == "f" ? "face" : "line") + " is dropped");
        out << '\n';
        continue;
      }
    }
    out << line << '\n';
  }
  return dropped.empty() ? bytes : out.str();
}

/// The warning for elements a lenient reader dropped: how many, and the first few.
std::string said_dropped(const std::string& name, const std::vector<std::string>& dropped) {
  constexpr size_t kListed = 3;
  std::string said = "mesh " + name + ": " + std::to_string(dropped.size()) + " element(s) that cannot be used were dropped; ";
  for (size_t i = 0; i < dropped.size() && i < kListed; ++i) said += (i ? "; " : "") + dropped[i];
  if (dropped.size() > kListed) said += "; ...";
  return said;
}

/// A file whose every face was dropped: refused, naming what cost it the first.
[[noreturn]] void throw_no_face_left(const std::string& name, const std::vector<std::string>& dropped) {
  throw std::runtime_error("cannot read mesh " + name + ": no face is left: " + dropped.front() +
                           (dropped.size() > 1 ? " (and " + std::to_string(dropped.size() - 1) + " more)" : ""));
}

/// An OBJ's text as bytes: UTF-16 (a byte-order mark, as some Windows tools write it) and a
/// UTF-8 byte-order mark are read as the ASCII they hold (core/text_encoding.h); a NUL
/// anywhere else is no OBJ.
std::string obj_text(const std::string& bytes, const std::string& name) {
  auto bad = [&](const std::string& what) { throw std::runtime_error("cannot read mesh " + name + ": " + what); };
  if (utf16_marked(bytes)) {
    if (bytes.size() % 2) bad("UTF-16 text of an odd number of bytes");
    const std::string text = utf8_of_text(bytes);
    for (size_t i = 0; i < text.size(); ++i)  // all ASCII before it: the character at byte 2 + 2i
      if (text[i] == '\0' || uint8_t(text[i]) > 0x7F)
        bad("UTF-16 text with a character that is not ASCII at byte " + std::to_string(2 + 2 * i) +
            " (OBJ's keywords and numbers are ASCII)");
    return text;
  }
  std::string text = utf8_of_text(bytes);
  if (text.find('\0') != std::string::npos) bad("an OBJ file holds no NUL bytes");
  return text;
}

/// The bytes of a PLY number type ("uchar", "float32", ...); 0 for a name that is none.
int ply_type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

/// A PLY file's header, as check_ply read it.
struct PlyHeader {
  struct Property {
    std::string type, name;            ///< type "list" for a list property
    std::string count_type, item_type; ///< a list's
  };
  struct Element {
    std::string name;
    long long count = 0;
    std::vector<Property> properties;
  };
  std::string format;             ///< "ascii", "binary_little_endian", "binary_big_endian"
  std::vector<Element> elements;  ///< the vertices first
  std::streamoff data_start = 0;  ///< where the elements' data begins

  /// The header as Avenues writes it: what was read of it, and nothing else (no comments,
  /// no lines of unknown keywords), in the usual form.
  std::string text() const {
    std::string t = "ply\nformat " + format + " 1.0\n";
    for (const Element& e : elements) {
      t += "element " + e.name + " " + std::to_string(e.count) + "\n";
      for (const Property& p : e.properties)
        t += p.type == "list" ? "property list " + p.count_type + " " + p.item_type + " " + p.name + "\n"
                              : "property " + p.type + " " + p.name + "\n";
    }
    return t + "end_header\n";
  }
};

/// A PLY header's element counts, checked against the file's size before OpenMesh
/// allocates for them: each element takes at least one byte per property (binary) or two
/// (ASCII: a digit and a separator). Returns the header. OpenMesh's header reader trusts
/// its input: a format version that is no number makes it loop for ever, a property before
/// any element makes it crash (both found by fuzzing). So it is given the header as
/// PlyHeader::text() writes it, from what is read and checked here.
PlyHeader check_ply(const std::string& path) {
  auto bad = [&](const std::string& what) { throw std::runtime_error("cannot read mesh " + path + ": " + what); };
  std::ifstream in(path, std::ios::binary);
  std::string line;
  PlyHeader h;
  std::vector<PlyHeader::Element>& elements = h.elements;
  int lineno = 0;
  bool ended = false;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // The header is text: a NUL or control byte in it is no PLY (OpenMesh's own check of
    // the header reads past such a line).
    for (char ch : line)
      if (const auto c = static_cast<unsigned char>(ch); (c < 32 && c != '\t') || c > 126)
        bad("line " + std::to_string(lineno) + ": a byte that is not text in the header");
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "end_header") {
      ended = true;
      break;
    }
    if (key == "format") {
      // One of PLY's three, and a version that is a number: OpenMesh's reader loops for
      // ever on one that is not ("format ascii 1.eel", found by fuzzing).
      std::string version;
      ls >> h.format >> version;
      if (h.format != "ascii" && h.format != "binary_little_endian" && h.format != "binary_big_endian")
        bad("line " + std::to_string(lineno) + ": format '" + h.format + "' is none of PLY's (ascii, binary_little_endian, binary_big_endian)");
      if (!whole_number(version)) bad("line " + std::to_string(lineno) + ": format version '" + version + "' is not a number");
    } else if (key == "element") {
      PlyHeader::Element e;
      std::string count;
      ls >> e.name >> count;
      if (!whole_integer(count, e.count) || e.count < 0)
        bad("line " + std::to_string(lineno) + ": element '" + e.name + "' has no count");
      elements.push_back(e);
    } else if (key == "property") {
      // "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME", of PLY's types
      // (OpenMesh's reader loops for ever on a type it does not know), in an element.
      if (elements.empty()) bad("line " + std::to_string(lineno) + ": a property before any element");
      PlyHeader::Property p;
      ls >> p.type;
      if (p.type == "list") ls >> p.count_type >> p.item_type;
      ls >> p.name;
      for (const std::string& t : p.type == "list" ? std::vector<std::string>{p.count_type, p.item_type} : std::vector<std::string>{p.type})
        if (ply_type_size(t) == 0)
          bad("line " + std::to_string(lineno) + ": property type '" + t + "' is none of PLY's number types");
      if (p.name.empty()) bad("line " + std::to_string(lineno) + ": a property with no name");
      elements.back().properties.push_back(p);
    }
    if (lineno > 10000) bad("its header does not end (no end_header in 10000 lines)");
  }
  if (!ended) bad("its header has no end_header line");
  if (elements.empty() || elements.front().name != "vertex")
    bad("its header does not declare its vertices first (element vertex N)");
  h.data_start = in ? static_cast<std::streamoff>(in.tellg()) : 0;
  const auto body = static_cast<long double>(std::filesystem::file_size(path)) - static_cast<long double>(h.data_start);
  long double need = 0;
  for (const PlyHeader::Element& e : elements) {
    need += static_cast<long double>(e.count) * std::max<size_t>(1, e.properties.size()) * (h.format == "ascii" ? 2 : 1);
    if (need > body)
      bad("its header announces " + std::to_string(e.count) + " " + e.name + " elements, more than its " +
          std::to_string(static_cast<long long>(std::max<long double>(body, 0))) + " bytes of data can hold");
  }
  // Only faces make a surface: a scan's point cloud (vertices alone) has nothing to stand
  // between free space and free space.
  long long faces = 0;
  for (const PlyHeader::Element& e : elements)
    if (e.name == "face") faces += e.count;
  if (faces == 0)
    bad("it holds " + std::to_string(elements.front().count) +
        " points and no faces (a point cloud): Avenues needs surfaces, polygons joining the points");
  return h;
}

/// An ASCII PLY's data, checked before OpenMesh reads it, value by value as its reader
/// will (OpenMesh 9.0, _PLYReader_::read_ascii): a coordinate or normal is read with the
/// stream's >> into a float, a colour into an int (a float where its type is), a face's
/// vertex count and indices into unsigned ints; anything else, a list too, is one word
/// skipped. Its reader stops after the first face element. Those variables are not set
/// first: once one value is not read whole ("nan", a stray byte, "1.5" for a count) or the
/// data ends early, the stream fails and every later >> leaves its variable as it was, so a
/// face's vertex count is whatever an earlier call left on the stack, often a part of an
/// address: OpenMesh then pushes billions of vertex handles (found by fuzzing; it depended
/// on the file read before and on the address layout). A count read whole can be as bad
/// ("-3" reads as 4294967293). So each value it reads must be there, up to the end of the
/// first face element, and be one its >> reads whole and keeps.
void check_ply_ascii_data(std::string_view data, const PlyHeader& h, const std::string& path) {
  enum Kind { Skip, Float, Int, Index };
  size_t at = 0;
  auto word = [&]() -> std::optional<std::string_view> {
    auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; };
    while (at < data.size() && space(data[at])) ++at;
    if (at == data.size()) return std::nullopt;
    const size_t from = at;
    while (at < data.size() && !space(data[at])) ++at;
    return data.substr(from, at - from);
  };
  // The value as >> reads it: all of the word, within the type's range.
  auto read_whole = [](std::string_view w, Kind k) {
    size_t i = 0;
    const bool sign = !w.empty() && (w[0] == '+' || w[0] == '-');
    if (k == Index && sign && w[0] == '-') return false;  // >> reads "-3" as 4294967293
    i += sign;
    const auto digits = [&] {
      const size_t from = i;
      while (i < w.size() && w[i] >= '0' && w[i] <= '9') ++i;
      return i - from;
    };
    size_t n = digits();
    if (k != Float) {
      if (n == 0 || i != w.size()) return false;  // strtoll saturates beyond long long
      const long long v = std::strtoll(std::string(w).c_str(), nullptr, 10);
      return k == Index ? v <= 4294967295LL : v >= -2147483648LL && v <= 2147483647LL;
    }
    if (i < w.size() && w[i] == '.') {
      ++i;
      n += digits();
    }
    if (n == 0) return false;
    if (i < w.size() && (w[i] == 'e' || w[i] == 'E')) {
      ++i;
      if (i < w.size() && (w[i] == '+' || w[i] == '-')) ++i;
      if (digits() == 0) return false;
    }
    return i == w.size() && std::isfinite(std::strtof(std::string(w).c_str(), nullptr));
  };
  long long face_count = 0;  // OpenMesh reads the first face element as many times as the last says
  for (const PlyHeader::Element& e : h.elements)
    if (e.name == "face") face_count = e.count;
  auto kind = [](const std::string& element, const PlyHeader::Property& p) {
    static const std::vector<std::string> coordinates = {"x", "y", "z", "nx", "ny", "nz", "u", "s", "v", "t"};
    static const std::vector<std::string> colours = {"red", "green", "blue", "alpha"};
    static const std::vector<std::string> vertex_colours = {"diffuse_red", "diffuse_green", "diffuse_blue"};
    const auto in = [&](const std::vector<std::string>& names) { return std::find(names.begin(), names.end(), p.name) != names.end(); };
    const bool floating = p.type == "float" || p.type == "float32";
    if (element == "face" && p.type == "list") return p.name == "vertex_indices" || p.name == "vertex_index" ? Index : Skip;
    if (p.type == "list" || (element != "vertex" && element != "face")) return Skip;
    if (element == "vertex" && in(coordinates)) return Float;
    if (in(colours) || (element == "vertex" && in(vertex_colours))) return floating ? Float : Int;
    return Skip;
  };
  static const char* const what[] = {"", "a number in a float's range", "a whole number in an int's range",
                                     "a vertex count or index (a whole number from 0 to 4294967295)"};
  for (const PlyHeader::Element& e : h.elements) {
    const long long records = e.properties.empty() ? 0 : e.name == "face" ? face_count : e.count;
    for (long long r = 0; r < records; ++r) {
      const std::string where = e.name + " " + std::to_string(r + 1) + " (of " + std::to_string(records) + ")";
      auto value = [&](Kind k) {
        const std::optional<std::string_view> w = word();
        if (!w) throw std::runtime_error("cannot read mesh " + path + ": its data ends within " + where);
        if (k == Skip || read_whole(*w, k)) return *w;
        std::string shown(w->substr(0, 24));
        for (char& c : shown)
          if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
        throw std::runtime_error("cannot read mesh " + path + ": " + where + ": '" + shown + (w->size() > 24 ? "...'" : "'") +
                                 " is not " + what[k]);
      };
      for (const PlyHeader::Property& p : e.properties) {
        const Kind k = kind(e.name, p);
        if (k != Index) {
          value(k);
          continue;
        }
        const std::string_view n = value(Index);
        for (long long i = std::strtoll(std::string(n).c_str(), nullptr, 10); i > 0; --i) value(Index);
      }
    }
    if (e.name == "face") break;  // OpenMesh reads no further
  }
}

/// A binary STL's triangle count against the file's size (a file cut short is refused),
/// and every vertex by the rule above; an ASCII STL's vertex lines likewise. An STL is a
/// list of separate triangles, so one with a vertex that is no coordinate is dropped, as
/// its tools drop it, and said in `dropped` ("triangle 7: ..."). Returns the bytes to read
/// when something was dropped ("" when the file reads as it is). `vertices_in_double`, where
/// given, gets an ASCII STL's vertices in double, one per distinct float position in the
/// order OpenMesh's reader first meets them (it joins the corners of separate triangles
/// that are the same floats); a binary STL holds floats, and gets none.
std::string readable_stl(const std::string& path, std::vector<std::string>& dropped,
                         std::vector<Vec3>* vertices_in_double = nullptr) {
  auto bad = [&](const std::string& what) { throw std::runtime_error("cannot read mesh " + path + ": " + what); };
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const bool ascii = bytes.compare(0, 5, "solid") == 0 && bytes.find("facet") != std::string::npos &&
                     bytes.find('\0') == std::string::npos;
  if (ascii) {
    // A facet's lines are held until its "endfacet": kept, or dropped whole.
    std::istringstream lines(bytes);
    std::string line, facet, kept, why;
    int lineno = 0, facets = 0;
    bool in_facet = false;
    std::vector<Vec3> corners, facet_corners;  // of the facets kept, in order
    while (std::getline(lines, line)) {
      ++lineno;
      std::istringstream ls(line);
      std::string key, t;
      ls >> key;
      if (key == "facet") in_facet = true, ++facets, facet.clear(), why.clear(), facet_corners.clear();
      if (key == "vertex") {
        double at[3] = {0, 0, 0};
        for (int k = 0; k < 3 && why.empty(); ++k) {
          if (!(ls >> t) || !coordinate(t)) why = "line " + std::to_string(lineno) + ": '" + t + "' " + kCoordinateRule;
          else at[k] = std::strtod(t.c_str(), nullptr);
        }
        if (why.empty()) (in_facet ? facet_corners : corners).push_back({at[0], at[1], at[2]});
      }
      (in_facet ? facet : kept) += line + '\n';
      if (key == "endfacet" && in_facet) {
        in_facet = false;
        if (why.empty()) kept += facet, corners.insert(corners.end(), facet_corners.begin(), facet_corners.end());
        else dropped.push_back("facet " + std::to_string(facets) + ", " + why + ": the triangle is dropped");
        facet.clear(), facet_corners.clear();
      }
    }
    kept += facet;  // an unfinished facet: OpenMesh's to judge
    corners.insert(corners.end(), facet_corners.begin(), facet_corners.end());
    if (vertices_in_double) {
      // OpenMesh reads each coordinate into a float and joins equal floats: one vertex per
      // distinct float position, the first met's doubles (mesh_of_openmesh checks each).
      std::map<std::array<double, 3>, size_t> seen;
      vertices_in_double->clear();
      for (const Vec3& p : corners)
        if (seen.try_emplace({to_float(p.x), to_float(p.y), to_float(p.z)}, vertices_in_double->size()).second)
          vertices_in_double->push_back(p);
    }
    return dropped.empty() ? std::string() : kept;
  }
  if (bytes.size() < 84) bad("a binary STL file needs 84 bytes of header, this has " + std::to_string(bytes.size()));
  uint32_t n = 0;
  for (int k = 3; k >= 0; --k) n = (n << 8) | static_cast<unsigned char>(bytes[80 + size_t(k)]);
  const uint64_t room = (bytes.size() - 84) / 50;
  if (n > room)
    bad("its header announces " + std::to_string(n) + " triangles, its " + std::to_string(bytes.size()) +
        " bytes hold " + std::to_string(room));
  std::string kept = bytes.substr(0, 84);
  uint32_t left = 0;
  for (uint32_t t = 0; t < n; ++t) {
    bool good = true;
    for (int k = 0; k < 9 && good; ++k) {
      float v = 0;
      std::memcpy(&v, bytes.data() + 84 + 50 * size_t(t) + 12 + 4 * size_t(k), 4);
      good = std::isfinite(v) && std::abs(v) <= kMaxCoordinate;
    }
    if (!good) {
      dropped.push_back("triangle " + std::to_string(t + 1) + " has a vertex that " + kCoordinateRule +
                        ": the triangle is dropped");
      continue;
    }
    kept.append(bytes, 84 + 50 * size_t(t), 50);
    ++left;
  }
  if (dropped.empty()) return std::string();
  for (int k = 0; k < 4; ++k) kept[80 + size_t(k)] = char((left >> (8 * k)) & 0xFF);
  return kept;
}

/// OpenMesh's ASCII OFF reader trusts its input: a negative face size ("-1 1 1"), a
/// token like "2-1", a file cut short or a stray control byte (all found by fuzzing,
/// tests/fuzz/regressions/mesh/) make it allocate until memory runs out. So an ASCII
/// OFF file is checked here first — the header and the counts strictly, then every vertex
/// line (three or more numbers) and every face line (a count, that many vertex indices,
/// optional colour numbers), one per line as every OFF writer puts them; a vertex or face
/// line that fails costs its element (`dropped`), as in an OBJ — and the reading is left
/// to OpenMesh. OpenMesh's reader also loses every face after a comment or a blank line,
/// so the checked lines, without comments and blank lines, are what it is given: the
/// returned text (empty for a binary OFF file, which OpenMesh reads from the file).
/// `vertices_in_double`, where given, gets the text's vertices in double (see mesh_of_openmesh;
/// none for a binary or homogeneous OFF file).
std::string check_off(const std::string& path, std::vector<std::string>& dropped,
                      std::vector<Vec3>* vertices_in_double = nullptr) {
  auto bad = [&](const std::string& what) { throw std::runtime_error("cannot read mesh " + path + ": " + what); };
  std::ifstream in(path, std::ios::binary);
  std::string line;
  int lineno = 0;
  std::vector<std::string> tok;
  auto next_line = [&]() {
    while (std::getline(in, line)) {
      ++lineno;
      for (char ch : line)
        if (static_cast<unsigned char>(ch) < 32 && ch != '\t' && ch != '\r')
          bad("line " + std::to_string(lineno) + " holds a control character");
      const size_t hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      std::istringstream ls(line);
      tok.assign(std::istream_iterator<std::string>(ls), std::istream_iterator<std::string>());
      if (!tok.empty()) return true;
    }
    return false;
  };
  auto joined = [&](size_t n) {  // the first n tokens as one line
    std::string l;
    for (size_t j = 0; j < n && j < tok.size(); ++j) l += tok[j] + (j + 1 == n ? "\n" : " ");
    return l;
  };
  auto at = [&]() { return "line " + std::to_string(lineno) + ": "; };
  if (!next_line()) return {};  // empty: OpenMesh refuses it
  // [ST][C][N][4][n]OFF [BINARY], the counts on this line or the next.
  if (!is_off_keyword(tok[0])) bad("it does not start with an OFF header");
  const std::string header = tok[0];
  if (line.find("BINARY") != std::string::npos || tok[0].find("nOFF") != std::string::npos) return {};
  std::vector<std::string> counts(tok.begin() + 1, tok.end());
  if (counts.empty()) {
    if (!next_line()) bad("it ends before its vertex and face counts");
    counts = tok;
  }
  long long nv = -1, nf = -1;
  constexpr long long kMax = 100'000'000;
  if (counts.size() < 2 || !whole_integer(counts[0], nv) || !whole_integer(counts[1], nf) || nv < 0 || nf < 0 ||
      nv > kMax || nf > kMax)
    bad(at() + "the vertex and face counts are not two whole numbers");
  // The file's structure (its counts, and a line for each vertex and face) is checked
  // strictly: a file cut short or out of step is refused. A vertex or a face that cannot
  // be used costs itself, as in OBJ: a bad vertex's line becomes a copy of a good one (the
  // numbering kept) and the faces using it go, with a line in `dropped`.
  std::vector<std::string> vertex_lines;
  std::vector<uint8_t> bad_vertex(size_t(nv), 0);
  std::string stand_in;
  std::vector<Vec3> coords;  // each vertex line's x, y, z in double (a bad one's: the stand-in's)
  Vec3 stand_in_at;
  for (long long i = 0; i < nv; ++i) {
    if (!next_line()) bad("it ends after " + std::to_string(i) + " of its " + std::to_string(nv) + " vertices");
    std::string why;
    if (tok.size() < 3) why = "a vertex needs three coordinates";
    for (size_t k = 0; k < tok.size() && why.empty(); ++k)
      if (!whole_number(tok[k])) why = "'" + tok[k] + "' is not a number";
    for (size_t k = 0; k < 3 && why.empty(); ++k)
      if (!coordinate(tok[k])) why = "'" + tok[k] + "' " + kCoordinateRule;
    if (!why.empty()) {
      bad_vertex[size_t(i)] = 1;
      dropped.push_back(at() + why + ": the vertex is dropped, with its faces");
      vertex_lines.emplace_back();
      coords.emplace_back();
      continue;
    }
    vertex_lines.push_back(joined(tok.size()));
    coords.push_back({std::strtod(tok[0].c_str(), nullptr), std::strtod(tok[1].c_str(), nullptr),
                  std::strtod(tok[2].c_str(), nullptr)});
    if (stand_in.empty()) stand_in = vertex_lines.back(), stand_in_at = coords.back();
  }
  if (stand_in.empty()) stand_in = "0 0 0\n";
  if (vertices_in_double && header.find('4') == std::string::npos) {  // 4OFF: homogeneous, x y z w
    for (size_t i = 0; i < coords.size(); ++i)
      if (bad_vertex[i]) coords[i] = stand_in_at;
    *vertices_in_double = std::move(coords);
  }
  std::string faces;
  long long kept = 0;
  for (long long f = 0; f < nf; ++f) {
    if (!next_line()) bad("it ends after " + std::to_string(f) + " of its " + std::to_string(nf) + " faces");
    long long k = 0;
    std::string why;
    if (!whole_integer(tok[0], k) || k < 1 || k > 1'000'000) why = "a face needs a vertex count";
    else if (tok.size() < size_t(k) + 1) why = "the face lists fewer than its " + std::to_string(k) + " vertices";
    for (size_t j = 1; why.empty() && j <= size_t(k); ++j) {
      long long v = -1;
      if (!whole_integer(tok[j], v) || v < 0 || v >= nv)
        why = "'" + tok[j] + "' is not a vertex number from 0 to " + std::to_string(nv - 1);
      else if (bad_vertex[size_t(v)])
        why = "vertex " + tok[j] + " is dropped";
    }
    for (size_t j = size_t(k) + 1; why.empty() && j < tok.size(); ++j)
      if (!whole_number(tok[j])) why = "'" + tok[j] + "' is not a colour number";
    if (!why.empty()) {
      dropped.push_back(at() + why + ": the face is dropped");
      continue;
    }
    // OpenMesh takes a face's colour numbers for more faces: Avenues does not use face
    // colours, so the face goes on with its count and vertices alone.
    faces += joined(size_t(k) + 1);
    ++kept;
  }
  // OpenMesh reads the header again: give it the counts alone, in the usual form.
  std::string clean = header + "\n" + std::to_string(nv) + " " + std::to_string(kept) + " 0\n";
  for (const std::string& v : vertex_lines) clean += v.empty() ? stand_in : v;
  return clean + faces;
}

}  // namespace

void smooth_corner_normals(Mesh& m, double crease_deg) {
  // Each polygon's normal, area-weighted: the sum of its triangles' cross products.
  size_t polygons = 0;
  for (int p : m.polygon_of) polygons = std::max(polygons, size_t(p) + 1);
  auto polygon = [&](size_t t) { return t < m.polygon_of.size() ? size_t(m.polygon_of[t]) : polygons + t; };
  std::vector<Vec3> normal(polygons + m.triangles.size(), Vec3{0, 0, 0});
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tr = m.triangles[t];
    const Vec3 a = m.vertices[size_t(tr[0])], b = m.vertices[size_t(tr[1])], c = m.vertices[size_t(tr[2])];
    normal[polygon(t)] = normal[polygon(t)] + cross(b - a, c - a);
  }
  std::vector<Vec3> unit(normal.size(), Vec3{0, 0, 0});
  for (size_t p = 0; p < normal.size(); ++p)
    if (const double l = length(normal[p]); l > 0) unit[p] = (1.0 / l) * normal[p];
  // The polygons around each vertex, each once.
  std::vector<std::vector<size_t>> around(m.vertices.size());
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int v : m.triangles[t]) {
      auto& list = around[size_t(v)];
      if (std::find(list.begin(), list.end(), polygon(t)) == list.end()) list.push_back(polygon(t));
    }
  const double cos_crease = std::cos(rad_from_deg(crease_deg));
  m.corner_normals.assign(3 * m.triangles.size(), Vec3{0, 0, 1});
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const Vec3 own = unit[polygon(t)];
    if (length(own) == 0) continue;  // a zero-area polygon: never shaded
    for (size_t k = 0; k < 3; ++k) {
      Vec3 sum{0, 0, 0};
      for (size_t q : around[size_t(m.triangles[t][k])])
        if (dot(unit[q], own) >= cos_crease) sum = sum + normal[q];
      const double l = length(sum);
      m.corner_normals[3 * t + k] = l > 0 ? (1.0 / l) * sum : own;
    }
  }
}

namespace {

/// OpenMesh reads every coordinate of an OBJ, OFF or PLY file into a float, whatever its
/// mesh's traits: a model in site coordinates (a survey's 5,400,000 m northing) lands on a
/// grid half a metre wide, its rooms a step larger or smaller and its shelves flattened.
/// So the readers in front of OpenMesh read the file's own numbers in double as they check
/// it, in the order of its vertices: an OBJ's "v" lines (readable_obj), an OFF's vertex
/// lines (check_off), a PLY's x, y and z (ply_vertices_in_double), an ASCII STL's vertex
/// lines (readable_stl; a binary STL holds floats). mesh_of_openmesh takes
/// them where they are the vertices OpenMesh read, each its float (else it keeps OpenMesh's).
Mesh mesh_of_openmesh(const PolyMesh& pm, const std::string& path, std::vector<std::string>* dropped = nullptr,
                      const std::vector<Vec3>* exact = nullptr);

/// A PLY file's vertices in double, from its own x, y and z properties (ASCII, or binary
/// either way round, of any of PLY's number types); empty where the vertex element holds a
/// list or lacks a coordinate. `header` is check_ply's (the vertex element first); `data`
/// the file's bytes after it, read once for this and for OpenMesh.
std::vector<Vec3> ply_vertices_in_double(std::string_view data, const PlyHeader& header) {
  const std::string& format = header.format;
  const long long count = header.elements.front().count;
  const std::vector<PlyHeader::Property>& props = header.elements.front().properties;
  for (const PlyHeader::Property& p : props)
    if (p.type == "list") return {};
  int at[3] = {-1, -1, -1};
  size_t record = 0;
  std::vector<size_t> offset;
  for (size_t k = 0; k < props.size(); ++k) {
    const int sz = ply_type_size(props[k].type);
    if (sz == 0) return {};
    offset.push_back(record);
    record += size_t(sz);
    for (int c = 0; c < 3; ++c)
      if (props[k].name == std::string(1, char('x' + c))) at[c] = int(k);
  }
  if (count <= 0 || at[0] < 0 || at[1] < 0 || at[2] < 0) return {};
  std::vector<Vec3> out;
  out.reserve(size_t(std::min<long long>(count, 1 << 24)));
  if (format == "ascii") {
    std::vector<double> value(props.size());
    std::string line;
    for (size_t from = 0; static_cast<long long>(out.size()) < count && from < data.size();) {
      const size_t eol = std::min(data.find('\n', from), data.size());
      line.assign(data.substr(from, eol - from));
      from = eol + 1;
      const char* c = line.c_str();
      char* end = nullptr;
      size_t k = 0;
      for (; k < props.size(); ++k, c = end) {
        value[k] = std::strtod(c, &end);
        if (end == c) break;
      }
      if (k == 0 && line.find_first_not_of(" \t\r") == std::string::npos) continue;
      if (k < props.size()) return {};
      out.push_back({value[size_t(at[0])], value[size_t(at[1])], value[size_t(at[2])]});
    }
    return out;
  }
  const bool big = format == "binary_big_endian";
  if (!big && format != "binary_little_endian") return {};
  std::vector<unsigned char> r(record);
  auto read = [&](size_t k) {
    unsigned char b[8];
    const int sz = ply_type_size(props[k].type);
    for (int i = 0; i < sz; ++i) b[i] = r[offset[k] + size_t(big ? sz - 1 - i : i)];  // little-endian now
    uint64_t u = 0;
    for (int i = sz - 1; i >= 0; --i) u = (u << 8) | b[i];
    const std::string& t = props[k].type;
    if (t == "float" || t == "float32") { float f; uint32_t w = uint32_t(u); std::memcpy(&f, &w, 4); return double(f); }
    if (t == "double" || t == "float64") { double d; std::memcpy(&d, &u, 8); return d; }
    const bool is_signed = t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
    if (is_signed && sz < 8 && (u >> (8 * sz - 1)) & 1) return double(int64_t(u) - (int64_t(1) << (8 * sz)));
    return double(u);
  };
  for (size_t from = 0; static_cast<long long>(out.size()) < count && from + record <= data.size(); from += record) {
    std::memcpy(r.data(), data.data() + from, record);
    out.push_back({read(size_t(at[0])), read(size_t(at[1])), read(size_t(at[2]))});
  }
  return static_cast<long long>(out.size()) == count ? out : std::vector<Vec3>{};
}

}  // namespace

std::optional<char> up_axis_named(const std::string& name) {
  if (name == "x" || name == "y" || name == "z") return name[0];
  return std::nullopt;
}

std::optional<double> metres_per_unit_named(const std::string& name) {
  if (name == "m") return 1.0;
  if (name == "cm") return 0.01;
  if (name == "mm") return 0.001;
  if (name == "in") return 0.0254;
  if (name == "ft") return 0.3048;
  return std::nullopt;
}

void orient_z_up(Mesh& m, char up, double metres_per_unit) {
  // Rotations (no mirror), so triangles keep their winding: y up -> (x, -z, y), x up -> (y, z, x).
  auto turn = [up](Vec3 p) {
    if (up == 'y') return Vec3{p.x, -p.z, p.y};
    if (up == 'x') return Vec3{p.y, p.z, p.x};
    return p;
  };
  for (Vec3& v : m.vertices) v = metres_per_unit * turn(v);
  for (Vec3& n : m.corner_normals) n = turn(n);
}

std::optional<char> guessed_up_axis(const Mesh& m) {
  if (m.vertices.empty()) return std::nullopt;
  Vec3 lo = m.vertices[0], hi = m.vertices[0];
  for (const Vec3& v : m.vertices) {
    lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
    hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
  }
  const double height = hi.y - lo.y, depth = hi.z - lo.z;
  if (!(height > 0) || !(depth > 0)) return std::nullopt;
  const bool stands_on_y0 = std::fabs(lo.y) <= 0.02 * height && hi.y > 0;
  const bool z_straddles = lo.z < -0.05 * depth && hi.z > 0.05 * depth;
  if (stands_on_y0 && z_straddles) return 'y';
  return std::nullopt;
}

namespace {

/// An OBJ file read with its materials: usemtl groups (read_mesh_bytes) coloured by the MTL
/// libraries beside it (colour_obj_materials); what is missing is one warning each.
Mesh load_obj(const std::string& path, std::vector<std::string>* warnings) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> said, libraries;
  Mesh m = read_mesh_bytes(bytes, ".obj", path, &said, &libraries);
  if (!m.materials.empty()) {
    MaterialFiles files(read_material_file);
    const std::string who = "mesh " + path + ": ";
    const ObjColouring c = colour_obj_materials(m, libraries, path, files, who, said);
    if (!c.undefined.empty() && (libraries.empty() || c.libraries_missing == 0)) {
      // (A library not at hand has been said already, and may define them.)
      said.push_back(who + std::to_string(c.undefined.size()) + " material(s) its faces use are defined in " +
                     (libraries.empty() ? "no MTL library (it names none: mtllib)" : "no MTL library") +
                     " nor among Java 3D's built-in materials (" + ObjColouring::listed(c.undefined) +
                     "): they keep Avenues' default colour");
    }
  }
  if (warnings) warnings->insert(warnings->end(), said.begin(), said.end());
  return m;
}

}  // namespace

Mesh load_mesh(const std::string& path, const MeshAxes& axes, std::vector<std::string>* warnings) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!fs::exists(st)) throw std::runtime_error("cannot read mesh " + path + ": no such file");
  if (fs::is_directory(st)) throw std::runtime_error("cannot read mesh " + path + ": it is a directory, not a mesh");
  if (!fs::is_regular_file(st))
    throw std::runtime_error("cannot read mesh " + path + ": it is not a regular file (a device or FIFO?)");
  const std::string ext = lower_extension(path);
  if (ext != ".off" && ext != ".obj" && ext != ".ply" && ext != ".stl") {
    // A name that says nothing (no extension, or one no reader has): the content may.
    if (!assimp_reads_extension(ext) && assimp_importer_by_content(path).empty())
      throw std::runtime_error("cannot read mesh " + path + ": " +
                               (ext.empty() ? std::string("its name has no extension") : "'" + ext + "' is not a mesh format Avenues reads") +
                               ", and no reader knows its content");
    return load_assimp_mesh(path, axes, warnings);
  }
  std::vector<Vec3> exact;  // the vertices in double (see mesh_of_openmesh)
  std::string ply;  // the PLY with the header Avenues writes (check_ply)
  if (ext == ".ply") {
    const PlyHeader header = check_ply(path);
    std::ifstream in(path, std::ios::binary);
    in.seekg(header.data_start);
    ply = header.text();
    const size_t data_at = ply.size();
    ply.append(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (header.format == "ascii") check_ply_ascii_data(std::string_view(ply).substr(data_at), header, path);
    exact = ply_vertices_in_double(std::string_view(ply).substr(data_at), header);
  }
  std::vector<std::string> stl_dropped;
  const std::string stl = ext == ".stl" ? readable_stl(path, stl_dropped, &exact) : std::string();
  const auto oriented = [&axes](Mesh m) {
    if (axes.up.value_or('z') != 'z' || axes.metres_per_unit.value_or(1) != 1)
      orient_z_up(m, axes.up.value_or('z'), axes.metres_per_unit.value_or(1));
    return m;
  };
  if (ext == ".obj") return oriented(load_obj(path, warnings));
  std::vector<std::string> off_dropped;
  const std::string off_text = ext == ".off" ? check_off(path, off_dropped, &exact) : std::string();
  PolyMesh pm;
  OpenMesh::IO::Options opt;
  const QuietOpenMesh quiet;
  // Checked text, a PLY under its checked header, or an STL with its bad triangles taken
  // out, is read from memory.
  const std::string& cleaned = !off_text.empty() ? off_text : !ply.empty() ? ply : stl;
  std::istringstream cleaned_stream(cleaned);
  if (!stl.empty() && stl.compare(0, 5, "solid") != 0) opt += OpenMesh::IO::Options::Binary;
  const bool read = cleaned.empty() ? OpenMesh::IO::read_mesh(pm, path, opt)
                                    : OpenMesh::IO::read_mesh(pm, cleaned_stream, ext, opt);
  if (!read)
    throw std::runtime_error("cannot read mesh " + path + ": not a mesh OpenMesh can read (OBJ, OFF, PLY, STL)");
  std::vector<std::string>& dropped = ext == ".off" ? off_dropped : stl_dropped;
  if (pm.n_faces() == 0 && !dropped.empty()) throw_no_face_left(path, dropped);
  Mesh m = oriented(mesh_of_openmesh(pm, path, &dropped, exact.empty() ? nullptr : &exact));
  if (!dropped.empty() && warnings) warnings->push_back(said_dropped(path, dropped));
  return m;
}

Mesh read_mesh_bytes(const std::string& bytes, const std::string& ext, const std::string& name,
                     std::vector<std::string>* warnings, std::vector<std::string>* material_libraries) {
  if (ext != ".obj") throw std::runtime_error("cannot read mesh " + name + ": only OBJ models are read from memory");
  std::vector<std::string> dropped;
  std::vector<Vec3> exact;  // the vertices in double (see mesh_of_openmesh)
  const std::string text = readable_obj(obj_text(bytes, name), dropped, &exact);
  PolyMesh pm;
  OpenMesh::IO::Options opt;
  const QuietOpenMesh quiet;
  std::istringstream in(text);
  if (!OpenMesh::IO::read_mesh(pm, in, ext, opt)) throw std::runtime_error("cannot read mesh " + name + ": not an OBJ mesh");
  if (pm.n_faces() == 0 && !dropped.empty()) throw_no_face_left(name, dropped);
  Mesh m = mesh_of_openmesh(pm, name, nullptr, &exact);
  if (!dropped.empty() && warnings) warnings->push_back(said_dropped(name, dropped));
  ObjMaterialUse use = obj_material_use(text);
  const std::string why = name_obj_materials(m, use, pm.n_faces());
  if (!why.empty() && warnings) warnings->push_back("mesh " + name + ": " + why);
  if (material_libraries) *material_libraries = std::move(use.libraries);
  return m;
}

namespace {

Mesh mesh_of_openmesh(const PolyMesh& pm, const std::string& path, std::vector<std::string>* dropped,
                      const std::vector<Vec3>* exact) {
  if (pm.n_faces() == 0) throw std::runtime_error("mesh " + path + " has no faces");
  // The text's doubles, where they are the vertices OpenMesh read (each rounds to its float).
  // (Decimal to float directly and through double may differ by one float in rare ties.)
  auto near = [](double d, float f) {
    const float g = float(d);
    return g == f || std::nextafter(g, HUGE_VALF) == f || std::nextafter(g, -HUGE_VALF) == f;
  };
  bool use_exact = exact && exact->size() == pm.n_vertices();
  for (auto v : pm.vertices()) {
    if (!use_exact) break;
    const auto p = pm.point(v);
    const Vec3 q = (*exact)[size_t(v.idx())];
    use_exact = near(q.x, p[0]) && near(q.y, p[1]) && near(q.z, p[2]);
  }
  // A vertex that is not a finite number (a binary PLY's NaN, which no check in front of
  // OpenMesh reads) costs the faces using it, said in `dropped`; without `dropped` it
  // refuses the mesh. It keeps its number, as a copy of a finite vertex.
  std::vector<Vec3> vertices;
  std::vector<uint8_t> finite;
  for (auto v : pm.vertices()) {
    auto p = pm.point(v);
    finite.push_back(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
    if (!finite.back() && !dropped) throw std::runtime_error("mesh " + path + " has a vertex that is not a finite number");
    if (!finite.back()) dropped->push_back("vertex " + std::to_string(v.idx()) + " is not a finite number: it is dropped, with its faces");
    vertices.push_back(!finite.back() ? Vec3{} : use_exact ? (*exact)[size_t(v.idx())] : Vec3{p[0], p[1], p[2]});
  }
  if (const auto good = std::find(finite.begin(), finite.end(), 1); good != finite.end())
    for (size_t i = 0; i < vertices.size(); ++i)
      if (!finite[i]) vertices[i] = vertices[size_t(good - finite.begin())];
  // OpenMesh keeps polygons; convex ones are the rule.
  std::vector<std::vector<int>> polygons;
  for (auto f : pm.faces()) {
    polygons.emplace_back();
    for (auto v : pm.fv_range(f)) polygons.back().push_back(v.idx());
    if (std::any_of(polygons.back().begin(), polygons.back().end(), [&](int i) { return !finite[size_t(i)]; }))
      polygons.pop_back();
  }
  if (polygons.empty() && dropped) throw_no_face_left(path, *dropped);
  return mesh_of_polygons(path, std::move(vertices), std::move(polygons));
}

/// Puts into each polygon's edges the vertices lying on them (T-junctions), in order along
/// the edge; `inserted` says, per polygon corner, whether it was put in here.
void insert_t_junctions(const std::vector<Vec3>& v, std::vector<std::vector<int>>& polygons,
                        std::vector<std::vector<uint8_t>>& inserted) {
  // The vertices in use, sorted along each axis: an edge looks in the slab around it that
  // holds fewest, so that few vertices are tried.
  std::vector<uint8_t> used(v.size(), 0);
  for (const auto& p : polygons)
    for (int i : p) used[size_t(i)] = 1;
  auto coord = [](const Vec3& p, int axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; };
  std::array<std::vector<int>, 3> by;
  for (int axis = 0; axis < 3; ++axis) {
    for (size_t i = 0; i < v.size(); ++i)
      if (used[i]) by[size_t(axis)].push_back(int(i));
    std::sort(by[size_t(axis)].begin(), by[size_t(axis)].end(),
              [&](int a, int b) { return coord(v[size_t(a)], axis) < coord(v[size_t(b)], axis); });
  }
  inserted.assign(polygons.size(), {});
  std::vector<std::pair<double, int>> on_edge;
  for (size_t pi = 0; pi < polygons.size(); ++pi) {
    const std::vector<int> p = polygons[pi];
    if (p.size() < 3) continue;
    std::vector<int> out;
    std::vector<uint8_t> flags;
    for (size_t k = 0; k < p.size(); ++k) {
      const int ia = p[k], ib = p[(k + 1) % p.size()];
      out.push_back(ia);
      flags.push_back(0);
      const Vec3 a = v[size_t(ia)], d = v[size_t(ib)] - a;
      const double l2 = dot(d, d);
      if (!(l2 > 0)) continue;
      // On the edge: strictly between its ends, within 1e-9 of its length of its line.
      // The candidates: the vertices in the edge's slab along the axis whose slab holds
      // fewest (an edge of a floor laid on a grid has all the floor's vertices in its
      // thinnest slab, and few in the slab along its own length).
      const double tol = 1e-9 * std::sqrt(l2);
      size_t best = SIZE_MAX;
      std::vector<int>::const_iterator it, end;
      for (int axis = 0; axis < 3; ++axis) {
        const std::vector<int>& order = by[size_t(axis)];
        const double c0 = std::min(coord(a, axis), coord(a + d, axis)) - tol,
                     c1 = std::max(coord(a, axis), coord(a + d, axis)) + tol;
        const auto lo = std::lower_bound(order.begin(), order.end(), c0,
                                         [&](int i, double c) { return coord(v[size_t(i)], axis) < c; });
        const auto hi = std::upper_bound(lo, order.end(), c1,
                                         [&](double c, int i) { return c < coord(v[size_t(i)], axis); });
        if (size_t(hi - lo) < best) best = size_t(hi - lo), it = lo, end = hi;
      }
      on_edge.clear();
      for (; it != end; ++it) {
        const int iv = *it;
        if (iv == ia || iv == ib) continue;
        const Vec3 w = v[size_t(iv)] - a;
        const double t = dot(w, d) / l2;
        if (!(t > 1e-9 && t < 1 - 1e-9)) continue;
        const Vec3 off = w - t * d;
        if (dot(off, off) > tol * tol) continue;
        if (std::find(p.begin(), p.end(), iv) != p.end()) continue;  // a corner of this polygon already
        on_edge.push_back({t, iv});
      }
      std::sort(on_edge.begin(), on_edge.end());
      for (const auto& [t, iv] : on_edge) {
        if (out.back() == iv) continue;
        out.push_back(iv);
        flags.push_back(1);
      }
    }
    polygons[pi] = std::move(out);
    inserted[pi] = std::move(flags);
  }
}

}  // namespace

Mesh mesh_of_polygons(std::string path, std::vector<Vec3> vertices, std::vector<std::vector<int>> polygons) {
  Mesh m;
  m.path = std::move(path);
  m.vertices = std::move(vertices);
  std::vector<std::vector<uint8_t>> inserted;
  insert_t_junctions(m.vertices, polygons, inserted);
  // Each polygon a fan, from a corner of its own with no vertex put into either side of it:
  // a fan from beside such a vertex would hold a triangle of no area.
  for (size_t pi = 0; pi < polygons.size(); ++pi) {
    const std::vector<int>& p = polygons[pi];
    const size_t n = p.size();
    if (n < 3) continue;  // no triangle; its number stays its own (paint is by polygon number)
    if (!polygon_is_convex(m.vertices, p)) {
      const std::vector<std::array<int, 3>> cut = triangulate_polygon(m.vertices, p);
      if (!cut.empty()) {
        for (const auto& t : cut) {
          m.triangles.push_back(t);
          m.polygon_of.push_back(int(pi));
        }
        continue;
      }
    }
    size_t apex = 0;
    for (size_t i = 0; i < n; ++i)
      if (!inserted[pi][i] && !inserted[pi][(i + 1) % n] && !inserted[pi][(i + n - 1) % n]) {
        apex = i;
        break;
      }
    for (size_t k = 1; k + 1 < n; ++k) {
      m.triangles.push_back({p[apex], p[(apex + k) % n], p[(apex + k + 1) % n]});
      m.polygon_of.push_back(int(pi));
    }
  }
  smooth_corner_normals(m);
  // Closed: every polygon edge is shared by exactly two polygons.
  m.boundary_edges = boundary_edges(polygons);
  m.closed = m.boundary_edges == 0;
  return m;
}

Mesh box_mesh(Vec3 size) {
  Mesh m;
  m.path = mesh_key_of_box(size);
  const double x = size.x / 2, y = size.y / 2, z = size.z;
  m.vertices = {{-x, -y, 0}, {x, -y, 0}, {x, y, 0}, {-x, y, 0}, {-x, -y, z}, {x, -y, z}, {x, y, z}, {-x, y, z}};
  // Counter-clockwise seen from outside: bottom, top, then the four sides.
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (int q = 0; q < 6; ++q) {
    m.triangles.push_back({quads[q][0], quads[q][1], quads[q][2]});
    m.triangles.push_back({quads[q][0], quads[q][2], quads[q][3]});
    m.polygon_of.push_back(q);
    m.polygon_of.push_back(q);
  }
  smooth_corner_normals(m);
  m.closed = true;
  return m;
}

std::string mesh_key_of_box(Vec3 size) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "box %.6g x %.6g x %.6g", size.x, size.y, size.z);
  return buf;
}

std::string mesh_key(const Object& object) {
  if (object.model) return "model " + object.model->path;
  if (object.mesh.empty()) return mesh_key_of_box(object.box);
  std::string key = object.mesh;
  if (object.axes.up) key += " up " + std::string(1, *object.axes.up);
  if (object.axes.metres_per_unit) key += " unit " + std::to_string(*object.axes.metres_per_unit);
  return key;
}

Mesh load_object_mesh(const Object& object, std::vector<std::string>* warnings) {
  if (object.model) return *object.model;
  if (object.mesh.empty()) {
    if (!(object.box.x > 0 && object.box.y > 0 && object.box.z > 0))
      throw std::runtime_error(object.where.str() + ": object '" + object.name + "' has neither a mesh nor a box size");
    return box_mesh(object.box);
  }
  try {
    std::vector<std::string> said;
    Mesh m = load_mesh(object.mesh, object.axes, &said);
    if (warnings)
      for (const std::string& w : said) warnings->push_back((object.where.str().empty() ? "" : object.where.str() + ": ") + w);
    return m;
  } catch (const std::runtime_error& e) {
    const std::string where = object.where.str();
    if (where.empty()) throw;
    throw std::runtime_error(where + ": " + e.what());
  }
}

Mesh place(const Mesh& mesh, const Object& o, double floor_z) {
  Mesh m = mesh;
  const Vec3 at = o.position + Vec3{0, 0, floor_z};
  const Rotation rotate(o.rotation_deg);
  for (Vec3& v : m.vertices) v = rotate({v.x * o.scale.x, v.y * o.scale.y, v.z * o.scale.z}) + at;
  for (Vec3& v : m.polygon_light) v = rotate({v.x * o.scale.x, v.y * o.scale.y, v.z * o.scale.z}) + at;
  for (Vec3& n : m.corner_normals) {
    Vec3 r = rotate({n.x / o.scale.x, n.y / o.scale.y, n.z / o.scale.z});
    double l = length(r);
    n = l > 0 ? (1.0 / l) * r : n;
  }
  return m;
}

namespace {
template <class Rings>
int count_boundary_edges(const Rings& rings) {
  std::unordered_map<uint64_t, int> uses;  // by the edge's two vertices, the lower first
  for (const auto& r : rings) {
    if (r.size() < 3) continue;
    for (size_t k = 0; k < r.size(); ++k) {
      const uint32_t a = uint32_t(r[k]), b = uint32_t(r[(k + 1) % r.size()]);
      ++uses[uint64_t(std::min(a, b)) << 32 | std::max(a, b)];
    }
  }
  int once = 0;
  for (const auto& [edge, count] : uses) once += count == 1;
  return once;
}
}  // namespace

int boundary_edges(const std::vector<std::vector<int>>& rings) { return count_boundary_edges(rings); }
int boundary_edges(const std::vector<std::array<int, 3>>& triangles) { return count_boundary_edges(triangles); }

bool is_off_keyword(std::string_view w) {
  // Written out rather than as a std::regex, whose matcher recurses once per character.
  auto take = [&w](std::string_view prefix) {
    if (w.substr(0, prefix.size()) != prefix) return false;
    w.remove_prefix(prefix.size());
    return true;
  };
  take("ST");
  take("C");
  take("N");
  take("4");
  take("n");
  return w == "OFF";
}

}  // namespace avenues
