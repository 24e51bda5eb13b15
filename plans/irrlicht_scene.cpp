// Avenues — Irrlicht's XML scenes and meshes (see irrlicht_scene.h).
#include "plans/irrlicht_scene.h"

#include <pugixml.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/affine.h"
#include "core/file_name.h"
#include "core/line_index.h"
#include "core/srgb.h"
#include "core/text_encoding.h"
#include "plans/image_colour.h"
#include "plans/obj_materials.h"
#include "plans/primitive_shapes.h"

namespace avenues {

namespace {

namespace fs = std::filesystem;

constexpr std::uintmax_t kMaxBytes = std::uintmax_t(1) << 28;

/// The file's bytes as UTF-8 text (core/text_encoding.h: Irrlicht writes UTF-16); at
/// most `limit` bytes are read.
std::optional<std::string> utf8_text(const std::string& path, std::uintmax_t limit, std::string* why = nullptr) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    if (why) *why = "no such file";
    return std::nullopt;
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) {
    if (why) *why = "its size cannot be read";
    return std::nullopt;
  }
  if (size > kMaxBytes) {
    if (why) *why = "larger than 256 MiB";
    return std::nullopt;
  }
  std::ifstream in(path, std::ios::binary);
  std::string bytes(size_t(std::min(size, limit)), '\0');
  in.read(bytes.data(), std::streamsize(bytes.size()));
  bytes.resize(size_t(in.gcount()));
  return utf8_of_text(bytes);
}

/// The name of the text's first element (after the declaration, comments and a DOCTYPE).
std::string_view root_name(std::string_view text) {
  for (size_t at = text.find('<'); at != std::string_view::npos; at = text.find('<', at + 1)) {
    if (at + 1 >= text.size()) break;
    const char next = text[at + 1];
    if (next == '?' || next == '!') continue;
    size_t end = at + 1;
    while (end < text.size() && !std::isspace(uint8_t(text[end])) && text[end] != '>' && text[end] != '/') ++end;
    return text.substr(at + 1, end - at - 1);
  }
  return {};
}

/// Irrlicht's relative transformation of a node: translate · rotate (degrees; the matrix
/// Rz·Ry·Rx, as matrix4::setRotationDegrees makes it) · scale.
Affine3 placed(Vec3 t, Vec3 rotation_deg, Vec3 s) {
  const double k = std::numbers::pi / 180;
  return Affine3::translation(t) * Affine3::rotation({0, 0, 1}, rotation_deg.z * k) *
         Affine3::rotation({0, 1, 0}, rotation_deg.y * k) * Affine3::rotation({1, 0, 0}, rotation_deg.x * k) *
         Affine3::scaling(s);
}

/// A material as far as Avenues uses it.
struct IrrMaterial {
  std::string name;
  std::array<double, 3> colour{1, 1, 1};  ///< linear RGB
};

/// Geometry in Irrlicht's space: triangles as Irrlicht's front faces have them ((b − a) ×
/// (c − a) towards the side they are seen from), each with a material of `materials`.
struct IrrGeometry {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> material_of;  ///< per triangle, into `materials`
  std::vector<IrrMaterial> materials;
  /// Irrlicht's own meshes (.irrmesh, a cube, a sphere): a node's <materials> replace
  /// these one for one. A model read through Assimp keeps its own.
  bool materials_replaceable = false;
};

std::optional<double> number(std::string_view s) {
  while (!s.empty() && std::isspace(uint8_t(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(uint8_t(s.back()))) s.remove_suffix(1);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// Irrlicht's "aarrggbb" colour (sRGB) in linear light.
std::optional<std::array<double, 3>> hex_colour(std::string_view s) {
  uint32_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v, 16);
  if (ec != std::errc() || end != s.data() + s.size() || s.size() > 8) return std::nullopt;
  return linear_from_srgb(std::array<double, 3>{((v >> 16) & 0xFF) / 255.0, ((v >> 8) & 0xFF) / 255.0, (v & 0xFF) / 255.0});
}

class Reader {
 public:
  Reader(const std::string& path, const ImportOptions& options) : path_(path), options_(options) {}

  ImportedScene read() {
    const auto t0 = std::chrono::steady_clock::now();
    std::string why;
    const std::optional<std::string> text = utf8_text(path_, kMaxBytes, &why);
    if (!text) fail(0, why);
    text_ = *text;
    parse(doc_, text_, path_);
    lines_.emplace(text_);
    const pugi::xml_node root = doc_.document_element();
    const std::string name = root ? root.name() : "";
    out_.path = path_;
    out_.nodes.push_back({});
    out_.nodes[0].name = "root";
    scale_ = options_.axes.metres_per_unit.value_or(1);
    if (options_.axes.up && *options_.axes.up != 'y')
      warn("up axis '" + std::string(1, *options_.axes.up) + "' ignored: Irrlicht's files are y up");
    if (name == "irr_scene") {
      out_.format = "Irrlicht scene (Avenues' reader)";
      read_scene(root);
    } else if (name == "mesh") {
      out_.format = "Irrlicht mesh (Avenues' reader)";
      IrrGeometry g = read_mesh(root, path_, *lines_);
      add_node(fs::path(path_).stem().string(), 0, g, Affine3{}, {});
    } else {
      fail(lines_->line(root ? root.offset_debug() : 0),
           "not an Irrlicht scene or mesh: the root element is <" + name + ">, not <irr_scene> or <mesh>");
    }
    size_t triangles = 0;
    for (const ImportedNode& n : out_.nodes) triangles += n.triangles.size();
    if (triangles == 0) {
      std::string gone;  // what was left out, as the warnings say it
      for (const std::string& w : out_.warnings)
        if (w.find("left out") != std::string::npos && gone.size() < 400) gone += "; " + w.substr(path_.size() + 2);
      throw std::runtime_error("cannot read model " + path_ + ": it holds no triangle Avenues can draw" + gone);
    }
    out_.import_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return std::move(out_);
  }

 private:
  /// Parses `text` into `doc`. Irrlicht's own XML reader passes over a tag that is not
  /// well-formed (an attribute written value="="file.png" by a tool's slip): so does this one
  /// where the tag stands alone on its line, which is blanked (with a warning naming it) and
  /// the text parsed again, a few times at most. Anything else is refused naming the line.
  void parse(pugi::xml_document& doc, std::string& text, const std::string& file) {
    for (int tries = 0;; ++tries) {
      const pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
      if (parsed) return;
      const size_t line = LineIndex(text).line(parsed.offset);
      const size_t at = std::min(text.size(), size_t(std::max<ptrdiff_t>(0, parsed.offset)));
      const size_t begin = text.rfind('\n', at == 0 ? 0 : at - 1), start = begin == std::string::npos ? 0 : begin + 1;
      size_t end = text.find('\n', at);
      if (end == std::string::npos) end = text.size();
      std::string_view l = std::string_view(text).substr(start, end - start);
      while (!l.empty() && std::isspace(uint8_t(l.front()))) l.remove_prefix(1);
      while (!l.empty() && std::isspace(uint8_t(l.back()))) l.remove_suffix(1);
      const bool lone_tag = l.size() > 2 && l.front() == '<' && l.back() == '>' && l[1] != '/' &&
                            std::count(l.begin(), l.end(), '<') == 1 && l.substr(l.size() - 2) == "/>";
      if (!lone_tag || tries >= 16)
        throw std::runtime_error("cannot read model " + file + ":" + std::to_string(line) + ": XML syntax error: " +
                                 parsed.description());
      warn("line " + std::to_string(line) + (file == path_ ? std::string() : " of " + file) + " is not well-formed XML (" +
           parsed.description() + "): left out, as Irrlicht's own reader passes over it");
      std::fill(text.begin() + ptrdiff_t(start), text.begin() + ptrdiff_t(end), ' ');
    }
  }

  [[noreturn]] void fail(size_t line, const std::string& what) const {
    throw std::runtime_error("cannot read model " + path_ + (line ? ":" + std::to_string(line) : std::string()) + ": " +
                             what);
  }
  void warn(const std::string& what) { out_.warnings.push_back(path_ + ": " + what); }
  /// A point of Irrlicht's space in Avenues': its (x, y, z) is (x, z, y), in metres.
  Vec3 ours(Vec3 p) const { return {p.x * scale_, p.z * scale_, p.y * scale_}; }

  /// The file `name` means beside `from` (file_beside: as written, in any case, by its name
  /// alone), or from `from`'s folder where it begins with '/' ("/../Obj/x.jpg", as
  /// Irrlicht's meshes name their textures); "" when there is none.
  static std::string beside(const std::string& from, const std::string& name) {
    const std::string at = file_beside(from, name);
    const size_t rooted = name.find_first_not_of('/');
    if (!at.empty() || rooted == 0 || rooted == std::string::npos) return at;
    return file_beside(from, name.substr(rooted));
  }

  /// Named attributes of an <attributes> or <material> element: name → (element, value).
  struct Attrs {
    std::map<std::string, std::pair<std::string, std::string>, std::less<>> by_name;
    std::optional<std::string> get(std::string_view name) const {
      const auto it = by_name.find(name);
      if (it == by_name.end()) return std::nullopt;
      return it->second.second;
    }
    std::optional<double> real(std::string_view name) const {
      const auto v = get(name);
      return v ? number(*v) : std::nullopt;
    }
    /// Irrlicht's vector3d "x, y, z".
    std::optional<Vec3> vec(std::string_view name) const {
      const auto v = get(name);
      if (!v) return std::nullopt;
      double c[3];
      std::string_view s = *v;
      for (int k = 0; k < 3; ++k) {
        const size_t comma = k < 2 ? s.find(',') : s.size();
        if (comma == std::string_view::npos) return std::nullopt;
        const auto x = number(s.substr(0, comma));
        if (!x) return std::nullopt;
        c[k] = *x;
        s.remove_prefix(std::min(s.size(), comma + 1));
      }
      return Vec3{c[0], c[1], c[2]};
    }
  };
  static Attrs attrs_of(pugi::xml_node e) {
    Attrs a;
    for (pugi::xml_node c : e.children())
      if (c.type() == pugi::node_element && c.attribute("name"))
        a.by_name[c.attribute("name").value()] = {c.name(), c.attribute("value").value()};
    return a;
  }

  /// A material's colour: its first texture's mean, found beside `file`, else Diffuse.
  IrrMaterial material_of(pugi::xml_node e, const std::string& file, const std::string& what) {
    const Attrs a = attrs_of(e);
    IrrMaterial m;
    m.name = what;
    if (const auto d = a.get("Diffuse"))
      if (const auto c = hex_colour(*d)) m.colour = *c;
    const std::string texture = a.get("Texture1").value_or("");
    if (texture.empty()) return m;
    const std::string at = beside(file, texture);
    if (at.empty()) {
      if (missing_.insert(texture).second)
        warn("texture '" + texture + "' (" + what + ") is not beside " + file + ": its Diffuse colour stands");
      return m;
    }
    bool first = false;
    const MaterialFiles::Image& image = images_.image(at, &first);
    if (first && !image.problem.empty()) warn(image.problem + ": its Diffuse colour stands");
    if (image.colour) m.colour = *image.colour;
    return m;
  }

  /// An .irrmesh's <mesh>: its buffers' triangles (`lines`: the file's, for messages).
  IrrGeometry read_mesh(pugi::xml_node mesh, const std::string& file, const LineIndex& lines) {
    IrrGeometry g;
    g.materials_replaceable = true;
    int buffer_number = 0;
    for (pugi::xml_node buffer : mesh.children("buffer")) {
      ++buffer_number;
      const std::string which = "buffer " + std::to_string(buffer_number) + " of " + fs::path(file).filename().string();
      const pugi::xml_node vertices = buffer.child("vertices"), indices = buffer.child("indices");
      if (!vertices || !indices) {
        warn(which + " (line " + std::to_string(lines.line(buffer.offset_debug())) + ") has no " + (vertices ? "<indices>" : "<vertices>") + ": left out");
        continue;
      }
      const std::string type = vertices.attribute("type").value();
      const size_t per = type == "standard" || type.empty() ? 9 : type == "2tcoords" ? 11 : type == "tangents" ? 15 : 0;
      if (per == 0) {
        warn(which + " has vertices of type '" + type + "', none of Irrlicht's (standard, 2tcoords, tangents): left out");
        continue;
      }
      // Vertices: the position is the first three numbers of each record. (A word's line:
      // that of the element's text, and the line ends before it there; pugixml's own copy
      // of the text has one '\n' for each of the file's line ends.)
      std::vector<std::string_view> words;
      const std::string_view vtext = vertices.child_value();
      const auto line_of = [&lines](pugi::xml_node element, std::string_view body, std::string_view word) {
        return lines.line(element.first_child().offset_debug()) +
               size_t(std::count(body.data(), word.data(), '\n'));
      };
      split(vtext, words);
      const size_t declared = size_t(std::max(0LL, vertices.attribute("vertexCount").as_llong(0)));
      const size_t count = words.size() / per;
      if (count != declared)
        warn(which + " holds " + std::to_string(count) + " whole vertices where it declares " + std::to_string(declared) +
             " (line " + std::to_string(lines.line(vertices.offset_debug())) + "): those it holds are read");
      const int base = int(g.vertices.size());
      std::vector<char> usable(count, 1);
      size_t unusable = 0, first_bad_line = 0;
      for (size_t v = 0; v < count; ++v) {
        const auto x = number(words[v * per]), y = number(words[v * per + 1]), z = number(words[v * per + 2]);
        if (!x || !y || !z) {
          usable[v] = 0;
          if (unusable++ == 0) first_bad_line = line_of(vertices, vtext, words[v * per]);
        }
        g.vertices.push_back({x.value_or(0), y.value_or(0), z.value_or(0)});
      }
      // Triangles, three indices each.
      const std::string_view itext = indices.child_value();
      split(itext, words);
      size_t dropped = 0, first_dropped_line = 0;
      const int material = int(g.materials.size());
      for (size_t t = 0; t + 3 <= words.size(); t += 3) {
        std::array<int, 3> tri{};
        bool ok = true;
        for (int k = 0; k < 3 && ok; ++k) {
          long long i = -1;
          const std::string_view w = words[t + size_t(k)];
          const auto [end, ec] = std::from_chars(w.data(), w.data() + w.size(), i);
          ok = ec == std::errc() && end == w.data() + w.size() && i >= 0 && size_t(i) < count && usable[size_t(i)];
          tri[size_t(k)] = base + int(ok ? i : 0);
        }
        if (!ok) {
          if (dropped++ == 0) first_dropped_line = line_of(indices, itext, words[t]);
          continue;
        }
        g.triangles.push_back(tri);
        g.material_of.push_back(material);
      }
      if (words.size() % 3 != 0) warn(which + ": " + std::to_string(words.size() % 3) + " index(es) after its last whole triangle left out");
      if (unusable > 0)
        warn(which + ": " + std::to_string(unusable) + " vertex(es) whose position is not a number (the first on line " +
             std::to_string(first_bad_line) + ") dropped, with their triangles");
      if (dropped > 0)
        warn(which + ": " + std::to_string(dropped) + " triangle(s) naming no usable vertex (the first on line " +
             std::to_string(first_dropped_line) + ") dropped");
      const pugi::xml_node m = buffer.child("material");
      g.materials.push_back(m ? material_of(m, file, which) : IrrMaterial{which, {1, 1, 1}});
    }
    return g;
  }

  /// Whitespace-separated words of s (into `out`, which is cleared).
  static void split(std::string_view s, std::vector<std::string_view>& out) {
    out.clear();
    size_t i = 0;
    while (i < s.size()) {
      while (i < s.size() && std::isspace(uint8_t(s[i]))) ++i;
      const size_t start = i;
      while (i < s.size() && !std::isspace(uint8_t(s[i]))) ++i;
      if (i > start) out.push_back(s.substr(start, i - start));
    }
  }

  /// Irrlicht's cube, `size` on a side, and sphere (`across` segments around, `down` from
  /// pole to pole), centred on their node (plans/primitive_shapes.h: outward, as Irrlicht's
  /// front faces are).
  static IrrGeometry cube(double size) {
    IrrGeometry g;
    g.materials_replaceable = true;
    box_shape({size, size, size}, {g.vertices, g.triangles});
    g.material_of.assign(g.triangles.size(), 0);
    g.materials.push_back({"cube", {1, 1, 1}});
    return g;
  }
  static IrrGeometry sphere(double radius, int across, int down) {
    IrrGeometry g;
    g.materials_replaceable = true;
    sphere_shape(radius, across, down, {g.vertices, g.triangles});
    g.material_of.assign(g.triangles.size(), 0);
    g.materials.push_back({"sphere", {1, 1, 1}});
    return g;
  }

  /// The model a mesh node names, in Irrlicht's space; nullptr (said) when it cannot be read.
  const IrrGeometry* model(const std::string& name, const std::string& node) {
    const std::string at = beside(path_, name);
    if (at.empty()) {
      warn("node '" + node + "': its mesh '" + name + "' is not beside the scene: left out");
      return nullptr;
    }
    const auto cached = models_.find(at);
    if (cached != models_.end()) return cached->second ? &*cached->second : nullptr;
    std::optional<IrrGeometry>& g = models_[at];
    try {
      const IrrlichtFile kind = irrlicht_file_kind(at);
      if (kind == IrrlichtFile::Scene) {
        warn("node '" + node + "': its mesh '" + name + "' is a scene, not a mesh: left out");
      } else if (kind == IrrlichtFile::Mesh) {
        std::string why;
        std::optional<std::string> text = utf8_text(at, kMaxBytes, &why);
        if (!text) throw std::runtime_error("cannot read model " + at + ": " + why);
        pugi::xml_document doc;
        parse(doc, *text, at);
        g = read_mesh(doc.document_element(), at, LineIndex(*text));
      } else {
        // Through Assimp, y up as Irrlicht reads every model, then back into Irrlicht's
        // space: Assimp's (a, b, c) is Avenues' (a, −c, b) = (p, q, r); Irrlicht's OBJ
        // reader negates x, (−a, b, c) = (−p, r, −q); for the others Assimp's left-handed
        // scene negates z, (a, b, −c) = (p, r, q).
        ImportOptions o;
        o.axes.up = 'y';
        o.axes.metres_per_unit = 1;
        const ImportedScene s = import_scene(at, o);
        for (const std::string& w : s.warnings) warn(w);
        const bool obj = lower_extension(at) == ".obj";
        IrrGeometry m;
        for (const ImportedMaterial& im : s.materials) m.materials.push_back({im.name, im.colour});
        const int none = int(m.materials.size());
        m.materials.push_back({"none", {1, 1, 1}});
        for (const ImportedNode& n : s.nodes) {
          const int base = int(m.vertices.size());
          for (const Vec3& v : n.vertices) m.vertices.push_back(obj ? Vec3{-v.x, v.z, -v.y} : Vec3{v.x, v.z, v.y});
          for (size_t t = 0; t < n.triangles.size(); ++t) {
            // Mirrored into Irrlicht's space, turned over as its readers turn them.
            m.triangles.push_back({base + n.triangles[t][0], base + n.triangles[t][2], base + n.triangles[t][1]});
            const int mat = t < n.triangle_material.size() ? n.triangle_material[t] : -1;
            m.material_of.push_back(mat >= 0 && mat < none ? mat : none);
          }
        }
        g = std::move(m);
      }
    } catch (const std::runtime_error& e) {
      warn("node '" + node + "': " + e.what() + ": left out");
      g.reset();
    }
    return g ? &*g : nullptr;
  }

  void read_scene(pugi::xml_node root) {
    struct Todo {
      pugi::xml_node node;
      Affine3 parent;
      int parent_index;
    };
    std::vector<Todo> todo;
    for (pugi::xml_node n : root.children("node")) todo.push_back({n, Affine3{}, 0});
    std::reverse(todo.begin(), todo.end());
    std::map<std::string, int> left_out;  // type → nodes
    int animators = 0;
    while (!todo.empty()) {
      const Todo t = todo.back();
      todo.pop_back();
      const std::string type = t.node.attribute("type").value();
      const Attrs a = attrs_of(t.node.child("attributes"));
      const std::string name = a.get("Name").value_or("") .empty() ? type : *a.get("Name");
      const size_t line = lines_->line(t.node.offset_debug());
      const std::string label = name + "' (" + type + ", line " + std::to_string(line);
      if (a.get("Visible").value_or("true") == "false") {
        warn("node '" + label + ") is hidden (Visible false): left out, with what it holds");
        continue;
      }
      const Affine3 here = t.parent * placed(a.vec("Position").value_or(Vec3{0, 0, 0}),
                                                    a.vec("Rotation").value_or(Vec3{0, 0, 0}),
                                                    a.vec("Scale").value_or(Vec3{1, 1, 1}));
      animators += int(std::distance(t.node.child("animators").children("attributes").begin(),
                                     t.node.child("animators").children("attributes").end()));
      std::optional<IrrGeometry> made;
      const IrrGeometry* g = nullptr;
      // The types by name in any case, as Assimp's reader takes them ("Mesh").
      const std::string lower = ascii_lower(type);
      if (lower == "mesh" || lower == "animatedmesh" || lower == "octtree") {
        const std::string mesh = a.get("Mesh").value_or("");
        if (mesh.empty()) warn("node '" + label + ") names no mesh: left out");
        else g = model(mesh, name);
      } else if (lower == "cube") {
        g = &made.emplace(cube(a.real("Size").value_or(10)));
      } else if (lower == "sphere") {
        g = &made.emplace(sphere(a.real("Radius").value_or(5), int(a.real("PolyCountX").value_or(16)),
                                 int(a.real("PolyCountY").value_or(16))));
      } else if (lower == "camera" || lower == "camerafps" || lower == "cameramaya") {
        // The first camera: where the scene's viewer starts, looking at its Target (in the
        // scene's space), Fovy the height of a 16:9 picture's angle.
        const auto target = a.vec("Target");
        if (!out_.viewpoint && target) {
          const double fovy = std::clamp(a.real("Fovy").value_or(std::numbers::pi / 2.5), 0.01, 3.0);
          out_.viewpoint = Viewpoint{ours(here.apply({0, 0, 0})), ours(*target), fov_deg_of_vertical(fovy)};
        }
      } else if (lower != "empty" && lower != "dummytransformation") {
        static const char* const kNotBuilding[] = {"light", "skybox", "skydome", "billboard",
                                                   "billboardtext", "particlesystem", "text", "terrain", "watersurface", "shadowvolume"};
        const bool known = std::find(std::begin(kNotBuilding), std::end(kNotBuilding), lower) != std::end(kNotBuilding);
        ++left_out[known ? type : "'" + type + "' (no type Irrlicht defines)"];
      }
      int index = t.parent_index;
      if (g) {
        std::vector<IrrMaterial> own;
        int k = 0;
        for (pugi::xml_node m : t.node.child("materials").children("attributes"))
          own.push_back(material_of(m, path_, "material " + std::to_string(++k) + " of node '" + name + "'"));
        index = add_node(name, t.parent_index, *g, here, own);
      }
      // Children, in the file's order.
      const size_t mark = todo.size();
      for (pugi::xml_node c : t.node.children("node")) todo.push_back({c, here, index});
      std::reverse(todo.begin() + ptrdiff_t(mark), todo.end());
    }
    for (const auto& [type, n] : left_out)
      warn(std::to_string(n) + " node(s) of type " + type + " left out: no surface of a building (their children are kept)");
    if (animators > 0)
      warn(std::to_string(animators) + " animator(s) not played: the scene is shown as placed");
  }

  /// Appends geometry g placed by `place` as a node of the scene; returns its index.
  int add_node(const std::string& name, int parent, const IrrGeometry& g, const Affine3& place,
               const std::vector<IrrMaterial>& own) {
    ImportedNode n;
    n.name = name;
    n.parent = parent;
    n.vertices.reserve(g.vertices.size());
    for (const Vec3& v : g.vertices) n.vertices.push_back(ours(place.apply(v)));
    // Irrlicht's front faces have (b − a) × (c − a) towards the viewer in Irrlicht's
    // coordinates; the mirror into Avenues' turns that normal inward, so each triangle's
    // corners are reversed, unless the placement itself mirrors (a negative scale).
    n.triangles = g.triangles;
    if (place.det() >= 0)
      for (auto& t : n.triangles) std::swap(t[1], t[2]);
    const int first = int(out_.materials.size());
    for (size_t m = 0; m < g.materials.size(); ++m) {
      const IrrMaterial& im = g.materials_replaceable && m < own.size() ? own[m] : g.materials[m];
      out_.materials.push_back({im.name, im.colour, true});
    }
    for (int m : g.material_of) n.triangle_material.push_back(first + m);
    if (!g.materials.empty()) n.colour = out_.materials[size_t(first)].colour, n.coloured = true;
    out_.nodes.push_back(std::move(n));
    return int(out_.nodes.size()) - 1;
  }

  std::string path_;
  ImportOptions options_;
  std::string text_;
  std::optional<LineIndex> lines_;  ///< text_'s
  pugi::xml_document doc_;
  ImportedScene out_;
  double scale_ = 1;
  MaterialFiles images_{read_material_file};  ///< textures' mean colours, each decoded once
  std::set<std::string> missing_;             ///< textures named but not at hand, said once each
  std::map<std::string, std::optional<IrrGeometry>> models_;
};

}  // namespace

IrrlichtFile irrlicht_file_kind(const std::string& path) {
  const std::optional<std::string> head = utf8_text(path, 8192);
  if (!head) return IrrlichtFile::None;
  const std::string_view root = root_name(*head);
  if (root == "irr_scene") return IrrlichtFile::Scene;
  if (root == "mesh" && (head->find("irrlicht") != std::string::npos || head->find("<buffer") != std::string::npos))
    return IrrlichtFile::Mesh;
  return IrrlichtFile::None;
}

ImportedScene read_irrlicht(const std::string& path, const ImportOptions& options) { return Reader(path, options).read(); }

}  // namespace avenues
