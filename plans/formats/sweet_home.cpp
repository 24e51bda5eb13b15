// Avenues — reading a Sweet Home 3D home into a Plan (see sweet_home.h).
//
// The reader works in the order the elements depend on each other:
//   1. the bytes: a zip (libzip, from memory, every entry capped) whose "Home.xml" entry
//      is read, else its serialized "Home" (sweet_home_serialized.cpp), or bare XML;
//   2. pugixml parses the XML into the home tree (home_tree.h) that the serialized Home
//      also becomes; every element keeps its line and column ("Home.xml:120:3 (wall
//      'wall7')"), or the byte its Java object starts at ("Home (wall 'wall7' at byte 912)");
//   3. levels → storeys; walls → drafts (centre lines in metres, rounded to 0.1 mm to
//      undo Sweet Home's float noise; arcs tessellated); drafts joined end to end
//      (wallAtStart / wallAtEnd naming each other, same thickness and height) → one
//      polyline each, so their corners are mitred as Sweet Home draws them; a free end
//      stopping just short of another wall is stretched into it so that no hairline gap
//      joins two rooms;
//   4. doors and windows → openings of the nearest parallel wall; where the wall bends a
//      little under one (a tessellated arc) it is straightened to the opening's chord,
//      across a real corner the opening is cut in parts, so that every opening lies on
//      one straight segment as outline.cpp wants;
//   5. sloped walls → pieces of constant height, never cut inside an opening;
//   6. rooms, furniture (each piece's OBJ model, read once with OpenMesh, its materials
//      coloured from its MTL libraries, fitted to the piece and recoloured by the piece's
//      modelMaterials; a box of its size where the model is not at hand), staircase
//      cut-outs (floor openings), the observer camera.
// Mistakes the file cannot be read past (no home entry, XML syntax, a malformed Java
// stream, a number that is not a number, a level that does not exist) are PlanErrors;
// odd but readable data (NaN, zero-length walls, a window in no wall, a wall or piece
// without its coordinates or size) is repaired or dropped with a line in Plan::warnings.
#include "plans/formats/sweet_home.h"
#include "plans/formats/svg_path.h"
#include "core/file_name.h"
#include "core/line_index.h"
#include "plans/formats/zip_salvage.h"
#include "plans/formats/home_tree.h"
#include "core/number_format.h"
#include "core/srgb.h"

#include "plans/arc.h"
#include "plans/mesh.h"
#include "plans/obj_materials.h"

#include <pugixml.hpp>
#include <zip.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

namespace avenues {
namespace {

constexpr double kCm = 0.01;            ///< [m] per Sweet Home length unit
constexpr double kAbsurd = 1e8;         ///< [m] any length beyond this is taken for garbage
constexpr double kJoinGap = 0.002;      ///< [m] wall ends this close are one joint
constexpr double kReach = 0.02;         ///< [m] a free wall end this far short of another wall is stretched into it
constexpr double kStep = 0.05;          ///< [m] largest height step between pieces of a sloped wall
constexpr double kMinStepPiece = 0.02;  ///< [m] shortest piece a sloped wall is cut into
constexpr double kDoorSill = 0.05;      ///< [m] a door or window reaching this close to the floor is a door
constexpr double kParallelSin = 0.26;   ///< sin 15°: how far a piece may turn from its wall
constexpr double kTouch = 0.001;        ///< [m] a door or window entering a wall less than this only touches it
constexpr double kMinOpening = 0.01;    ///< [m] narrower or lower openings (and lower walls) are dropped
constexpr double kDefaultSlab = 0.12;   ///< [m] Sweet Home's default floor thickness

/// A Sweet Home colour ("FF8080C0": ARGB in hex, as HomeXMLExporter writes it; alpha
/// ignored) as linear RGB; nullopt when it is not one.
std::optional<std::array<double, 3>> colour_of(const std::string& hex) {
  if (hex.size() != 8 && hex.size() != 6) return std::nullopt;
  uint32_t v = 0;
  const auto [end, ec] = std::from_chars(hex.data(), hex.data() + hex.size(), v, 16);
  if (ec != std::errc() || end != hex.data() + hex.size()) return std::nullopt;
  return std::array<double, 3>{linear_from_srgb(((v >> 16) & 0xFF) / 255.0), linear_from_srgb(((v >> 8) & 0xFF) / 255.0),
                               linear_from_srgb((v & 0xFF) / 255.0)};
}

// --- the bytes -------------------------------------------------------------------------

std::string read_bytes(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw PlanError(SourceLoc{path, 0, 0, ""}, "cannot read home: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PlanError(SourceLoc{path, 0, 0, ""}, std::string("cannot open home: ") + std::strerror(errno));
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw PlanError(SourceLoc{path, 0, 0, ""}, "cannot read home");
  return s.str();
}

bool looks_like_zip(const std::string& b) {
  return b.size() >= 4 && b[0] == 'P' && b[1] == 'K' && ((b[2] == 3 && b[3] == 4) || (b[2] == 5 && b[3] == 6));
}

bool has_sh3d_extension(const std::string& path) {
  return lower_extension(path) == ".sh3d";
}

/// A .sh3d archive held in memory (libzip), for its Home.xml and the models beside it.
class ZipArchive {
 public:
  ZipArchive(const std::string& path, const std::string& bytes, size_t max_entry_bytes)
      : path_(path), max_entry_bytes_(max_entry_bytes) {
    const SourceLoc at{path, 0, 0, ""};
    std::string why;
    bool no_source = false;
    zip_t* za = open_in_memory(bytes, why, no_source);
    if (!za && no_source) throw PlanError(at, "cannot read the archive: " + why);
    if (!za) {
      // It starts like a zip (read_sweet_home checked): a damaged one, most often cut short.
      // Sweet Home 3D reads such a home from the entries that are whole; so does Avenues.
      std::optional<SalvagedZip> whole = salvage_zip(bytes);
      const std::string damaged = "the archive is damaged (truncated, or its central directory is missing: " + why + ")";
      if (!whole) throw PlanError(at, damaged + ", and not even its first entry is whole");
      salvaged_ = std::move(whole->bytes);
      za = open_in_memory(salvaged_, why, no_source);
      if (!za) throw PlanError(at, damaged + ", and its whole entries cannot be read either: " + why);
      repaired_ = damaged + ": read from the " + std::to_string(whole->kept.size()) + " entries whole before the damage" +
                  (whole->first_lost.empty() ? std::string() : ", the rest lost from '" + whole->first_lost + "' on");
    }
    archive_.reset(za);
  }
  /// What was wrong with an archive read from the entries whole before its damage ("" if none).
  const std::string& repaired() const { return repaired_; }
  bool has(const std::string& name) const { return zip_name_locate(archive_.get(), name.c_str(), 0) >= 0; }
  /// The entry's bytes; nullopt when there is no such entry. A damaged entry: PlanError.
  std::optional<std::string> entry(const std::string& name) const {
    const zip_int64_t idx = zip_name_locate(archive_.get(), name.c_str(), 0);
    if (idx < 0) return std::nullopt;
    const SourceLoc at{path_, 0, 0, ""};
    zip_file_t* f = zip_fopen_index(archive_.get(), zip_uint64_t(idx), 0);
    if (!f) throw PlanError(at, "cannot open " + name + " in the archive: " + std::string(zip_strerror(archive_.get())));
    std::string out;
    std::vector<char> buf(1 << 16);
    // A zip entry may claim anything in its header, and a small archive may inflate to
    // gigabytes: what is read is counted, and an entry past the limit is refused.
    for (;;) {
      const zip_int64_t n = zip_fread(f, buf.data(), buf.size());
      if (n < 0) {
        const std::string why = zip_file_strerror(f);
        zip_fclose(f);
        throw PlanError(at, "cannot read " + name + " in the archive: " + why);
      }
      if (n == 0) break;
      if (out.size() + size_t(n) > max_entry_bytes_) {
        zip_fclose(f);
        throw PlanError(at, "entry '" + name + "' of the archive inflates to more than " + size_text(max_entry_bytes_) +
                                ": refused (no Sweet Home entry is that large)");
      }
      out.append(buf.data(), size_t(n));
    }
    zip_fclose(f);
    return out;
  }

 private:
  struct Discard {
    void operator()(zip_t* z) const { zip_discard(z); }
  };
  /// libzip over `bytes`, which must outlive it; nullptr when it cannot, with libzip's
  /// reason in `why`, and `no_source` when it failed before reading the bytes at all.
  static zip_t* open_in_memory(const std::string& bytes, std::string& why, bool& no_source) {
    zip_error_t err;
    zip_error_init(&err);
    zip_source_t* src = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &err);
    no_source = src == nullptr;
    zip_t* za = src ? zip_open_from_source(src, ZIP_RDONLY, &err) : nullptr;
    if (!za) {
      if (src) zip_source_free(src);
      why = zip_error_strerror(&err);
    }
    zip_error_fini(&err);
    return za;
  }
  /// "512 MiB", "1 KiB", "100 bytes": a limit as a message says it.
  static std::string size_text(size_t n) {
    if (n >= (size_t(1) << 20) && n % (size_t(1) << 20) == 0) return std::to_string(n >> 20) + " MiB";
    if (n >= 1024 && n % 1024 == 0) return std::to_string(n >> 10) + " KiB";
    return std::to_string(n) + " bytes";
  }
  std::string path_;
  size_t max_entry_bytes_;
  std::string salvaged_;  ///< a damaged archive's whole entries with a new central directory
  std::string repaired_;
  std::unique_ptr<zip_t, Discard> archive_;
};

/// Where a piece's model is found: an entry of the .sh3d archive, or beside a bare Home.xml
/// (the model's path under the XML's folder, or its file name in a "models" folder there,
/// where .ci/install-deps puts the models of Sweet Home's catalogue). Returns its bytes.
using ModelSource = std::function<std::optional<std::string>(const std::string& model)>;

// --- geometry of walls -------------------------------------------------------------------

/// The part of polyline c from distance s0 to s1 along it (s0 < s1), with its arc flags.
void sub_polyline(const std::vector<Vec2>& c, const std::vector<bool>& arc, double s0, double s1,
                  std::vector<Vec2>& out, std::vector<bool>& out_arc) {
  out.clear();
  out_arc.clear();
  double along = 0;
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    const double len = length(c[i + 1] - c[i]);
    const double lo = std::max(s0, along), hi = std::min(s1, along + len);
    if (hi > lo && len > 0) {
      const Vec2 p = c[i] + ((lo - along) / len) * (c[i + 1] - c[i]);
      const Vec2 q = c[i] + ((hi - along) / len) * (c[i + 1] - c[i]);
      if (out.empty()) out.push_back(p);
      if (length(q - out.back()) > 1e-9) {
        out.push_back(q);
        out_arc.push_back(arc[i]);
      }
    }
    along += len;
  }
}

// --- what the reader collects before it builds the plan ------------------------------------

/// A <level>, in metres.
struct LevelIn {
  std::string id, name;
  double elevation = 0, floor = 0, height = 0;
  int index = 0;  ///< elevationIndex: order among levels of one elevation
  bool viewable = true;  ///< false: hidden in Sweet Home's plan and 3D view (Plan > Make level unviewable)
  const HomeElement* node = nullptr;
};

/// storey_of's answer for an element on a level that is not viewable: it is left out.
constexpr StoreyId kHiddenLevel = -2;

/// A wall on its way into the plan: one <wall> or several joined end to end.
struct Draft {
  std::vector<std::string> ids;  ///< Sweet Home ids of the walls it is made of
  Wall wall;                     ///< centre line, thickness, storey, name, where (height set last)
  double h0 = 0, h1 = 0;         ///< [m] heights at the start and end of the centre line
  std::string at_start, at_end;  ///< ids of the walls joined at its ends (single walls)
  bool sloped() const { return std::fabs(h1 - h0) > 1e-6; }
};

/// One of a piece's modelMaterials (<material name key color><texture/></material>, a
/// HomeMaterial): what it puts in place of the model's material it names.
struct ModelMaterialIn {
  std::string names;  ///< the model's material it replaces: its key where it has one, else its name
  std::optional<std::array<double, 3>> colour;  ///< linear RGB; nullopt: the model's own stays
  std::string what;   ///< "#RRGGBB" or "texture <image>": how the mesh's path tells pieces so coloured apart
  SourceLoc where;
};

/// A piece of furniture, door or window, in metres and plan axes.
struct PieceIn {
  std::string name;
  SourceLoc where;
  StoreyId storey = 0;
  Vec2 centre;            ///< [m]
  double angle = 0;       ///< [rad] anticlockwise in plan (Sweet Home's is clockwise on screen)
  double width = 0, depth = 0, height = 0, elevation = 0;  ///< [m], elevation above the level
  bool door_or_window = false;
  /// A door or window that cuts no wall (it enters none, or only as a niche): Sweet Home
  /// still shows its model where it stands, so it becomes a piece of furniture.
  bool in_no_wall = false;
  bool cut_both_sides = false;  ///< wallCutOutOnBothSides: Sweet Home cuts its wall through, however deep it is
  std::string cut_out;    ///< a staircase's staircaseCutOutShape (SVG path in the unit square)
  std::string wall_cut_out;  ///< a door's or window's cutOutShape: the hole it cuts (SVG path in the unit square of its face)
  bool mirrored = false;
  std::string model;      ///< its model: an entry of the .sh3d archive, or a catalogue path
  std::array<double, 9> model_rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  ///< row-major, applied to the model first
  MaterialId material = -1;  ///< its color, where it has one
  std::vector<ModelMaterialIn> model_materials;  ///< in the order Sweet Home tries them (the first that names a material wins)
  /// A light's sources (HomeLight's LightSource: x, y, z in fractions of the piece's width,
  /// depth and height; colour as written) and its power, 0 (off) to 1.
  struct LightSourceIn {
    double x = 0.5, y = 0.5, z = 0.5;
    std::string colour;
    SourceLoc where;
  };
  std::vector<LightSourceIn> light_sources;
  double power = 0.5;
  Vec2 screen_centre;     ///< [cm] (x, y) as Sweet Home has them, where its light sources are placed from
  double screen_angle = 0;  ///< [rad] clockwise on screen, as written
};

/// What one door or window opens of its wall: its span along the wall's centre line [m]
/// (as read, before straightening), and from `sill` up to `head` [m] above the floor; or,
/// not a rectangle (an arched or a round window), its cut-out, in the unit square of its
/// face, x along the wall's centre line from a0 to a1, y down from its top, the square
/// spanning `bottom` to `bottom + height` [m].
struct HoleShape {
  double a0 = 0, a1 = 0, sill = 0, head = 0;
  std::vector<Vec2> shape;
  double bottom = 0, height = 0;
};

/// A door or window on its way into the wall it sits in.
struct Hole {
  double a0 = 0, a1 = 0;  ///< [m] its span along the wall's centre line (as read, before straightening)
  Opening o;              ///< name, kind, sill, head, where (at and width set last)
  /// What each door or window drawn into the others opens (one, where none overlaps it):
  /// the opening cut is their union, in strips where it is no rectangle.
  std::vector<HoleShape> shapes;
};

class HomeReader {
 public:
  HomeReader(std::string path, const HomeTree& tree, ModelSource models)
      : path_(std::move(path)), file_(tree.file), tree_(tree), models_(std::move(models)),
        files_(models_, path_ + ":") {}

  Plan read();

 private:
  // --- locations, errors, numbers -----------------------------------------------------
  /// Home.xml: its line and column; the serialized Home: the byte its object starts at.
  SourceLoc loc(const HomeElement& n, const std::string& element) const {
    if (tree_.serialized) return SourceLoc{file_, 0, 0, element + " at byte " + std::to_string(n.offset)};
    return SourceLoc{file_, n.line, n.column, element};
  }
  [[noreturn]] void fail(const HomeElement& n, const std::string& element, const std::string& what) const {
    throw PlanError(loc(n, element), what);
  }
  void warn(const HomeElement& n, const std::string& element, const std::string& what) {
    plan_.warnings.push_back(loc(n, element).str() + ": " + what);
  }
  /// An attribute as a number; nullopt when absent. Not a number at all: PlanError.
  /// NaN and infinities are numbers (Java writes them so); callers decide.
  std::optional<double> number(const HomeElement& n, const char* attr, const std::string& element) const {
    const std::string* a = n.attribute(attr);
    if (!a) return std::nullopt;
    std::string_view s = *a;
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double v = 0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (s.empty() || ec != std::errc() || end != s.data() + s.size())
      fail(n, element, "attribute '" + std::string(attr) + "' of " + element + " is not a number: \"" +
                           *a + "\"");
    return v;
  }
  double need(const HomeElement& n, const char* attr, const std::string& element) const {
    auto v = number(n, attr, element);
    if (!v) fail(n, element, element + " has no '" + std::string(attr) + "' attribute");
    return *v;
  }
  static bool sane(double v) { return std::isfinite(v) && std::fabs(v) * kCm <= kAbsurd; }
  /// "wall 'wall3'" when it has an id (or name), "wall 3" otherwise.
  static std::string element_name(const HomeElement& n, const char* key, int count) {
    const std::string id = n.text(key);
    return id.empty() ? n.kind + " " + std::to_string(count) : n.kind + " '" + id + "'";
  }
  StoreyId storey_of(const HomeElement& n, const std::string& element, const char* inherited = "") const;
  /// Sweet Home (x, y) [cm] → plan [m], rounded to 0.1 mm: Sweet Home computes in floats,
  /// so a wall drawn along y = −5.5 may end at y = −5.4999795, and the hair between it and
  /// a wall on another storey along y = −5.5 would become a row of sliver cells.
  static Vec2 plan_point(double x, double y) {
    return {std::nearbyint(x * 100) / 10000, -std::nearbyint(y * 100) / 10000};  // 1/100 cm steps, in m
  }

  // --- the steps --------------------------------------------------------------------------
  void read_levels(const HomeElement& home);
  void read_walls(const HomeElement& home);
  void join_walls();
  void stretch_free_ends();
  void collect_pieces(const HomeElement& home);
  void find_wall(PieceIn& p);
  void cut_openings();
  void finish_walls();
  /// A <room> in plan: the room as it will enter the plan (label not yet placed) and its polygon.
  struct RoomIn {
    Room room;
    std::vector<Vec2> poly;  ///< [m] as drawn, repeated points dropped
    bool named = false;
  };
  std::vector<RoomIn> collect_rooms(const HomeElement& home);
  void open_room_edges(const std::vector<RoomIn>& rooms);
  void read_rooms(std::vector<RoomIn> rooms);
  void add_furniture();
  void add_lights();
  void read_camera(const HomeElement& home);

  std::shared_ptr<const Mesh> model_of(const PieceIn& p);
  std::vector<ModelMaterialIn> model_materials_of(const HomeElement& n, const std::string& element);
  void read_light_sources(const HomeElement& n, const std::string& element, PieceIn& p);
  void colour_model(Mesh& m, const std::vector<std::string>& libraries, const PieceIn& p);
  /// The plan's material of a Sweet Home colour attribute (one per colour); -1 when the
  /// text is empty or not a colour.
  MaterialId material_of(const std::string& hex) {
    const std::optional<std::array<double, 3>> c = colour_of(hex);
    if (!c) return -1;
    const std::string rgb = hex.substr(hex.size() - 6);
    auto [it, fresh] = materials_.try_emplace(rgb, MaterialId(plan_.materials.size()));
    if (fresh) {
      Material m;
      m.name = "#" + rgb;
      m.colour = *c;
      m.where = SourceLoc{file_, 0, 0, ""};
      plan_.materials.push_back(m);
    }
    return it->second;
  }

  /// A surface's material, as Sweet Home paints it: its texture (the <texture> child whose
  /// attribute is `texture`) as its image's mean colour, else its colour attribute; -1 when
  /// it has neither (or its texture cannot be read: then with a warning).
  MaterialId surface_material(const HomeElement& n, const char* colour, const char* texture, const std::string& element) {
    for (size_t c : n.children) {
      const HomeElement& t = tree_.elements[c];
      if (t.kind != "texture" || t.text("attribute") != texture) continue;
      const MaterialId m = texture_material(t, element);
      if (m >= 0) return m;
      break;
    }
    return material_of(n.text(colour));
  }
  /// The plan's material of a texture's image, its mean colour in linear light (one per
  /// image); -1, with a warning naming `element`, when the image is not at hand or unreadable.
  MaterialId texture_material(const HomeElement& t, const std::string& element) {
    const std::string image = t.text("image");
    if (image.empty()) return -1;
    auto [it, fresh] = textures_.try_emplace(image, -1);
    if (!fresh) return it->second;
    const MaterialFiles::Image& mean = files_.image(image);
    const std::string name = t.text("name").empty() ? image : t.text("name");
    if (!mean.at_hand) {
      warn(t, element, "texture '" + name + "' (image " + image + ") is not at hand: its colour is used instead");
      return -1;
    }
    if (!mean.colour) {
      warn(t, element, mean.problem + ": the texture's colour is used instead");
      return -1;
    }
    Material m;
    m.colour = *mean.colour;
    m.name = "texture '" + name + "' (" + image + ")";  // two images may share a name
    m.where = loc(t, element);
    it->second = MaterialId(plan_.materials.size());
    plan_.materials.push_back(m);
    return it->second;
  }
  /// Sweet Home's own colour of a surface that has none, for one side of a wall whose other
  /// side has one (Avenues' default material).
  MaterialId default_material() {
    if (default_material_ < 0) {
      Material m;
      m.name = "default";
      m.where = SourceLoc{file_, 0, 0, ""};
      default_material_ = MaterialId(plan_.materials.size());
      plan_.materials.push_back(m);
    }
    return default_material_;
  }

  std::string path_, file_;
  const HomeTree& tree_;
  ModelSource models_;
  std::map<std::string, MaterialId> materials_;  ///< by colour "RRGGBB"
  std::map<std::string, MaterialId> textures_;   ///< by image entry (-1: unreadable)
  MaterialId default_material_ = -1;
  std::map<std::string, std::shared_ptr<const Mesh>> models_read_;  ///< by model name, as read (nullptr: none)
  /// The MTL libraries and images that models' materials, pieces' modelMaterials and
  /// surfaces' textures name, by entry: each read once.
  MaterialFiles files_;
  std::set<std::string> undefined_materials_;  ///< names models use that neither an MTL library at hand nor Java 3D defines
  int models_missing_ = 0;       ///< pieces left boxes because their model is not at hand
  Plan plan_;
  double wall_height_ = 2.5;   ///< [m] the home's default wall height
  bool has_levels_ = false;
  StoreyId default_storey_ = 0;
  std::unordered_map<std::string, StoreyId> storey_of_level_;
  std::unordered_set<std::string> hidden_levels_;  ///< ids of levels that are not viewable
  std::vector<Draft> drafts_;
  std::vector<PieceIn> pieces_;
  std::vector<std::vector<Hole>> holes_;  ///< per draft: the doors and windows found in it
  int piece_count_ = 0;
  int walls_dropped_ = 0;      ///< walls read_walls() dropped, each with a warning
  int walls_cut_ = 0;          ///< walls taller than their storey
  int sloped_ = 0, steps_ = 0; ///< sloped walls, and the pieces they became
};

StoreyId HomeReader::storey_of(const HomeElement& n, const std::string& element, const char* inherited) const {
  std::string id = n.text("level");
  if (id.empty()) id = inherited;
  if (id.empty()) return default_storey_;
  if (hidden_levels_.count(id)) return kHiddenLevel;
  auto it = storey_of_level_.find(id);
  if (it == storey_of_level_.end())
    fail(n, element, element + " is on level '" + id + "', which the home does not define");
  return it->second;
}

// --- levels → storeys ---------------------------------------------------------------------

void HomeReader::read_levels(const HomeElement& home) {
  std::vector<LevelIn> levels;
  int count = 0;
  for (const HomeElement* np : tree_.children(home, "level")) {
    const HomeElement& n = *np;
    const std::string element = element_name(n, "id", ++count);
    LevelIn l;
    l.id = n.text("id");
    l.name = n.text("name");
    if (l.name.empty()) l.name = l.id.empty() ? "level " + std::to_string(count) : l.id;
    l.elevation = need(n, "elevation", element);
    l.floor = need(n, "floorThickness", element);
    l.height = need(n, "height", element);
    const double index = number(n, "elevationIndex", element).value_or(0);
    l.index = std::isfinite(index) ? int(std::clamp(index, -1e6, 1e6)) : 0;
    l.viewable = std::string_view(n.text("viewable")) != "false";
    l.node = &n;
    if (!sane(l.elevation) || !sane(l.floor) || !sane(l.height) || l.height <= 0 || l.floor < 0)
      fail(n, element, element + " has an elevation, floorThickness or height that makes no sense (" +
                           format_number(l.elevation) + ", " + format_number(l.floor) + ", " + format_number(l.height) + ")");
    l.elevation *= kCm, l.floor *= kCm, l.height *= kCm;
    levels.push_back(l);
  }
  // A level made unviewable is hidden in Sweet Home's plan and 3D view, and in its virtual
  // visit: left out here too, with what stands on it. (Unless every level is: then the
  // home would be empty, and all are kept.)
  if (std::any_of(levels.begin(), levels.end(), [](const LevelIn& l) { return l.viewable; }))
    std::erase_if(levels, [&](const LevelIn& l) {
      if (l.viewable) return false;
      hidden_levels_.insert(l.id);
      warn(*l.node, "level '" + l.name + "'",
           "level '" + l.name + "' is not viewable in Sweet Home 3D (hidden in its plan and 3D view): left out, "
           "with the walls, rooms and furniture on it");
      return true;
    });
  has_levels_ = !levels.empty();
  if (!has_levels_) {  // one storey, as tall as the home's walls
    Storey s;
    s.name = "home";
    s.height = wall_height_;
    s.slab = kDefaultSlab;
    s.where = loc(home, "home");
    plan_.storeys.push_back(s);
    return;
  }
  std::stable_sort(levels.begin(), levels.end(), [](const LevelIn& a, const LevelIn& b) {
    return a.elevation != b.elevation ? a.elevation < b.elevation : a.index < b.index;
  });
  // Levels at one elevation (elevationIndex tells them apart) are one storey: Sweet Home
  // draws them as layers of the same floor.
  std::vector<std::vector<const LevelIn*>> groups;
  for (const LevelIn& l : levels) {
    if (!groups.empty() && std::fabs(l.elevation - groups.back().front()->elevation) < 1e-4)
      groups.back().push_back(&l);
    else
      groups.push_back({&l});
  }
  for (size_t g = 0; g < groups.size(); ++g) {
    const auto& grp = groups[g];
    Storey s;
    s.where = loc(*grp.front()->node, "level '" + grp.front()->name + "'");
    s.elevation = g == 0 ? grp.front()->elevation : plan_.storeys.back().elevation + plan_.storeys.back().height +
                                                        plan_.storeys.back().slab;
    s.height = 0;
    for (const LevelIn* l : grp) {
      s.name += (s.name.empty() ? "" : " + ") + l->name;
      s.height = std::max(s.height, l->height);
    }
    if (grp.size() > 1)
      plan_.warnings.push_back(s.where.str() + ": levels '" + s.name + "' share the elevation " +
                               format_number(grp.front()->elevation) + " m: merged into one storey " + format_number(s.height) +
                               " m high");
    if (g + 1 < groups.size()) {
      // The slab is the gap up to the next level's floor (its floorThickness, if the
      // levels are consistent). A level reaching into the next one's floor is cut.
      const LevelIn& next = *groups[g + 1].front();
      const double gap = next.elevation - grp.front()->elevation;
      if (s.height + next.floor > gap + 1e-6) {
        const double slab = std::clamp(next.floor, 0.0, gap / 2);
        const double h = gap - slab;
        plan_.warnings.push_back(s.where.str() + ": level '" + s.name + "' (" + format_number(s.height) +
                                 " m high) reaches into the floor of level '" + next.name + "' at " +
                                 format_number(next.elevation) + " m: cut to " + format_number(h) + " m");
        s.height = h;
      }
      s.slab = gap - s.height;
    } else {
      s.slab = grp.front()->floor;
    }
    for (const LevelIn* l : grp)
      if (!l->id.empty()) storey_of_level_[l->id] = StoreyId(plan_.storeys.size());
    plan_.storeys.push_back(s);
  }
  // Elements that name no level stand on the storey nearest the ground.
  double best = HUGE_VAL;
  for (size_t s = 0; s < plan_.storeys.size(); ++s)
    if (std::fabs(plan_.storeys[s].elevation) < best) best = std::fabs(plan_.storeys[s].elevation), default_storey_ = StoreyId(s);
}

// --- walls ----------------------------------------------------------------------------------

void HomeReader::read_walls(const HomeElement& home) {
  int count = 0;
  for (const HomeElement* np : tree_.children(home, "wall")) {
    const HomeElement& n = *np;
    const std::string element = element_name(n, "id", ++count);
    Draft d;
    const std::string id = n.text("id");
    d.ids.push_back(id.empty() ? "wall " + std::to_string(count) : id);
    d.wall.name = d.ids.front();
    d.wall.where = loc(n, element);
    d.wall.storey = storey_of(n, element);
    if (d.wall.storey == kHiddenLevel) continue;
    // Sweet Home cannot draw a wall without these: the wall is dropped, not the home.
    const char* missing = nullptr;
    for (const char* attr : {"xStart", "yStart", "xEnd", "yEnd", "thickness"})
      if (!missing && !n.attribute(attr)) missing = attr;
    if (missing) {
      warn(n, element, element + " has no '" + missing + "' attribute: wall dropped");
      ++walls_dropped_;
      continue;
    }
    const double xs = need(n, "xStart", element), ys = need(n, "yStart", element);
    const double xe = need(n, "xEnd", element), ye = need(n, "yEnd", element);
    const double th = need(n, "thickness", element);
    const auto h = number(n, "height", element), he = number(n, "heightAtEnd", element);
    const auto arc = number(n, "arcExtent", element);
    if (!sane(xs) || !sane(ys) || !sane(xe) || !sane(ye) || !sane(th) || (h && !sane(*h)) || (he && !sane(*he)) ||
        (arc && !std::isfinite(*arc))) {
      warn(n, element, "a coordinate, thickness, height or arcExtent is not a finite number: wall dropped");
      ++walls_dropped_;
      continue;
    }
    if (th < 0) {
      warn(n, element, "negative thickness " + format_number(th) + " cm: wall dropped");
      ++walls_dropped_;
      continue;
    }
    const Vec2 a = plan_point(xs, ys), b = plan_point(xe, ye);
    if (length(b - a) < 1e-6) {
      warn(n, element, "the wall has length 0: dropped");
      ++walls_dropped_;
      continue;
    }
    d.wall.thickness = th * kCm;
    const Storey& st = plan_.storeys[size_t(d.wall.storey)];
    d.h0 = h ? *h * kCm : (has_levels_ ? st.height : wall_height_);
    d.h1 = he ? *he * kCm : d.h0;
    if (d.h0 <= kMinOpening && d.h1 <= kMinOpening) {
      warn(n, element, "the wall has no height: dropped");
      ++walls_dropped_;
      continue;
    }
    d.wall.centre.push_back(a);
    if (arc && std::fabs(*arc) > 1e-6 && std::fabs(*arc) < 2 * std::numbers::pi - 1e-6) {
      // Sweet Home's arc bulges to the side of (ye − ys, xs − xe) on screen for a positive
      // extent, by the sagitta (chord/2)·tan(extent/4) at the chord's middle (Wall.java's
      // getArcCircleCenter, solved for the arc's midpoint).
      const double k = std::tan(*arc / 4) / 2;  // sagitta / chord
      const Vec2 m = plan_point((xs + xe) / 2 + k * (ye - ys), (ys + ye) / 2 + k * (xs - xe));
      // The circle through the three points, in pieces within the plan's tolerance (at most 10,000).
      if (const std::optional<Arc> curve = arc_through(a, m, b)) {
        curve->append(static_cast<long>(std::min(curve->pieces_for(plan_.arc_tolerance), 10000.0)), b, d.wall.centre);
        d.wall.from_arc.assign(d.wall.centre.size() - 1, true);
      }
    }
    if (d.wall.centre.size() == 1) {
      d.wall.centre.push_back(b);
      d.wall.from_arc.push_back(false);
    }
    d.at_start = n.text("wallAtStart");
    d.at_end = n.text("wallAtEnd");
    // Each side its own material: its texture's mean colour, else its colour; a side with
    // neither is Sweet Home's default (where the other side has one).
    const MaterialId left = surface_material(n, "leftSideColor", "leftSideTexture", element);
    const MaterialId right = surface_material(n, "rightSideColor", "rightSideTexture", element);
    d.wall.material = left;
    if (right != left) {
      d.wall.material = left >= 0 ? left : default_material();
      d.wall.right_material = right >= 0 ? right : default_material();
    }
    drafts_.push_back(std::move(d));
  }
}

/// Walls joined end to end (each naming the other at that end, ends within kJoinGap) of
/// the same storey, thickness and height become one centre line: outline.cpp then mitres
/// their corners as Sweet Home draws them. Closed rings stay closed.
void HomeReader::join_walls() {
  const size_t n = drafts_.size();
  std::unordered_map<std::string, size_t> index;
  for (size_t i = 0; i < n; ++i) index.emplace(drafts_[i].ids.front(), i);
  auto height_of = [&](const Draft& d) {
    const double sh = plan_.storeys[size_t(d.wall.storey)].height;
    return d.h0 >= sh - 1e-9 ? -1.0 : d.h0;
  };
  auto end_point = [&](size_t i, int e) { return e == 0 ? drafts_[i].wall.centre.front() : drafts_[i].wall.centre.back(); };
  // Direction of travel leaving wall i through end e.
  auto out_dir = [&](size_t i, int e) {
    const auto& c = drafts_[i].wall.centre;
    const Vec2 d = e == 1 ? c[c.size() - 1] - c[c.size() - 2] : c[0] - c[1];
    return (1.0 / length(d)) * d;
  };
  auto compatible = [&](size_t i, size_t j) {
    const Draft &a = drafts_[i], &b = drafts_[j];
    return a.wall.storey == b.wall.storey && !a.sloped() && !b.sloped() &&
           std::fabs(a.wall.thickness - b.wall.thickness) < 1e-6 && std::fabs(height_of(a) - height_of(b)) < 1e-6;
  };
  // Joined walls keep their sides' materials: end to start they must agree side by side;
  // end to end (or start to start) one is walked backwards, its left side then on the right.
  auto sides = [](const Draft& d) {
    return std::pair{d.wall.material, d.wall.right_material >= 0 ? d.wall.right_material : d.wall.material};
  };
  auto same_sides = [&](size_t i, int e, size_t j, int f) {
    const auto [li, ri] = sides(drafts_[i]);
    const auto [lj, rj] = sides(drafts_[j]);
    return e != f ? li == lj && ri == rj : li == rj && ri == lj;
  };
  struct Link { long other = -1; int end = 0; };
  std::vector<std::array<Link, 2>> link(n);
  for (size_t i = 0; i < n; ++i)
    for (int e = 0; e < 2; ++e) {
      const std::string& partner = e == 0 ? drafts_[i].at_start : drafts_[i].at_end;
      auto it = index.find(partner);
      if (partner.empty() || it == index.end() || it->second == i) continue;
      const size_t j = it->second;
      if (!compatible(i, j)) continue;
      for (int f = 0; f < 2; ++f) {
        const std::string& back = f == 0 ? drafts_[j].at_start : drafts_[j].at_end;
        if (back != drafts_[i].ids.front() || length(end_point(i, e) - end_point(j, f)) > kJoinGap) continue;
        if (!same_sides(i, e, j, f)) continue;
        // Not when the second wall folds back over the first.
        if (dot(out_dir(i, e), out_dir(j, f)) > 0.985) continue;
        link[i][size_t(e)] = {long(j), f};
        break;
      }
    }
  for (size_t i = 0; i < n; ++i)  // keep mutual links only
    for (int e = 0; e < 2; ++e) {
      const Link l = link[i][size_t(e)];
      if (l.other >= 0 && (link[size_t(l.other)][size_t(l.end)].other != long(i) || link[size_t(l.other)][size_t(l.end)].end != e))
        link[i][size_t(e)] = {};
    }

  std::vector<uint8_t> used(n, 0);
  std::vector<Draft> out;
  auto walk = [&](size_t first, bool reversed) {
    Draft d;
    size_t cur = first;
    bool rev = reversed;
    bool closed = false;
    for (;;) {
      used[cur] = 1;
      Draft& w = drafts_[cur];
      std::vector<Vec2> c = w.wall.centre;
      std::vector<bool> fa = w.wall.from_arc;
      if (rev) std::reverse(c.begin(), c.end()), std::reverse(fa.begin(), fa.end());
      if (d.ids.empty()) {
        d = w;
        d.ids.clear();
        d.wall.centre = c;
        d.wall.from_arc = fa;
        if (rev) std::swap(d.h0, d.h1), std::swap(d.at_start, d.at_end);
        if (rev && d.wall.right_material >= 0) std::swap(d.wall.material, d.wall.right_material);
      } else {
        // Not a wall that would make the chain's centre line cross itself (Sweet Home lets
        // joined walls overlap; a plan's wall may not): it starts a chain of its own.
        std::vector<Vec2> joined = d.wall.centre;
        joined.insert(joined.end(), c.begin() + 1, c.end());
        std::vector<Vec2> probe = joined;  // a ring closing here is checked as one
        const bool ring = probe.size() > 3 && length(probe.back() - probe.front()) <= kJoinGap;
        if (ring) probe.back() = probe.front();
        if (find_self_crossing(probe, ring).first >= 0) {
          used[cur] = 0;
          break;
        }
        d.wall.centre = std::move(joined);
        d.wall.from_arc.insert(d.wall.from_arc.end(), fa.begin(), fa.end());
        d.at_end = rev ? w.at_start : w.at_end;
      }
      d.ids.push_back(w.ids.front());
      const Link l = link[cur][rev ? 0 : 1];
      if (l.other < 0) break;
      if (size_t(l.other) == first && l.end == (reversed ? 1 : 0)) {
        closed = true;
        break;
      }
      if (used[size_t(l.other)]) break;
      cur = size_t(l.other);
      rev = l.end == 1;
    }
    if (closed && d.wall.centre.size() > 3) {
      d.wall.centre.back() = d.wall.centre.front();
      d.at_start.clear(), d.at_end.clear();
    }
    if (d.ids.size() > 1) {
      d.wall.name = d.ids[0];
      const size_t shown = std::min<size_t>(d.ids.size(), 3);
      for (size_t k = 1; k < shown; ++k) d.wall.name += "+" + d.ids[k];
      if (d.ids.size() > shown) d.wall.name += "+" + std::to_string(d.ids.size() - shown) + " more";
      d.wall.where.element = "wall '" + d.wall.name + "'";
    }
    out.push_back(std::move(d));
  };
  for (size_t i = 0; i < n; ++i) {
    if (used[i]) continue;
    if (link[i][0].other < 0) walk(i, false);
    else if (link[i][1].other < 0) walk(i, true);
  }
  for (size_t i = 0; i < n; ++i)  // what is left are rings
    if (!used[i]) walk(i, false);
  // Ends joined within kJoinGap may leave a segment of (almost) no length: drop it.
  drafts_.clear();
  for (Draft& d : out) {
    std::vector<Vec2> c{d.wall.centre.front()};
    std::vector<bool> arc;
    for (size_t k = 1; k < d.wall.centre.size(); ++k)
      if (length(d.wall.centre[k] - c.back()) > 1e-6) c.push_back(d.wall.centre[k]), arc.push_back(d.wall.from_arc[k - 1]);
    if (c.size() < 2) continue;
    if (d.wall.centre.front() == d.wall.centre.back()) c.back() = c.front();  // a ring stays closed
    d.wall.centre = std::move(c);
    d.wall.from_arc = std::move(arc);
    drafts_.push_back(std::move(d));
  }
}

/// A free wall end that stops just short of another wall of its storey (Sweet Home floats:
/// a T junction's end lands on the other wall's face, give or take a micrometre) is
/// stretched to that wall's centre line, so that outline.cpp sees the two touch and no
/// hairline gap lets two rooms run into each other.
void HomeReader::stretch_free_ends() {
  for (size_t i = 0; i < drafts_.size(); ++i) {
    Wall& w = drafts_[i].wall;
    if (w.centre.size() > 3 && w.centre.front() == w.centre.back()) continue;
    for (int e = 0; e < 2; ++e) {
      const size_t m = w.centre.size();
      const Vec2 p = e == 0 ? w.centre[0] : w.centre[m - 1];
      const Vec2 q = e == 0 ? w.centre[1] : w.centre[m - 2];
      const Vec2 d = (1.0 / length(p - q)) * (p - q);  // outwards
      double best = HUGE_VAL;
      bool inside = false;
      for (size_t j = 0; j < drafts_.size() && !inside; ++j) {
        const Wall& o = drafts_[j].wall;
        if (j == i || o.storey != w.storey || o.thickness <= 0) continue;
        for (size_t k = 0; k + 1 < o.centre.size(); ++k) {
          const Vec2 a = o.centre[k], b = o.centre[k + 1];
          if (distance_to_segment(p, a, b) <= o.thickness / 2 + 1e-9) {
            inside = true;  // already touches: outline.cpp caps it into the other wall
            break;
          }
          const Vec2 s = b - a;
          const double den = cross(d, s);
          const double sin_angle = std::fabs(den) / length(s);
          if (sin_angle < 0.2) continue;  // nearly parallel: not a junction
          const double t = cross(a - p, s) / den;   // p + t·d on the other centre line
          const double u = cross(a - p, d) / den;   // … at a + u·s
          if (t <= 0 || u < 0 || u > 1) continue;
          if (t <= (o.thickness / 2) / sin_angle + kReach) best = std::min(best, t);
        }
      }
      if (inside || best == HUGE_VAL) continue;
      (e == 0 ? w.centre[0] : w.centre[m - 1]) = p + best * d;
    }
  }
}

// --- doors and windows --------------------------------------------------------------------

/// Every piece of the home, groups opened, in document order. Iterative: a home may nest
/// groups thousands deep (each pending child is a stack entry, not a call).
void HomeReader::collect_pieces(const HomeElement& home) {
  struct Pending {
    const HomeElement* n;
    std::string level;  ///< inherited from the enclosing groups
  };
  std::vector<Pending> stack;
  for (auto it = home.children.rbegin(); it != home.children.rend(); ++it) stack.push_back({&tree_.elements[*it], ""});
  while (!stack.empty()) {
    const Pending top = std::move(stack.back());
    stack.pop_back();
    const HomeElement& n = *top.n;
    const std::string& level = top.level;
    const std::string_view kind = n.kind;
    if (kind == "furnitureGroup") {
      const std::string own = n.text("level");
      for (auto it = n.children.rbegin(); it != n.children.rend(); ++it)
        stack.push_back({&tree_.elements[*it], own.empty() ? level : own});
      continue;
    }
    if (kind != "pieceOfFurniture" && kind != "doorOrWindow" && kind != "light") continue;
    const std::string element = element_name(n, "name", ++piece_count_);
    PieceIn p;
    p.name = n.text("name");
    if (p.name.empty()) p.name = std::string(kind) + " " + std::to_string(piece_count_);
    p.where = loc(n, element);
    p.storey = storey_of(n, element, level.c_str());
    if (p.storey == kHiddenLevel) continue;
    // Sweet Home cannot place a piece without these: the piece is dropped, not the home.
    const char* missing = nullptr;
    for (const char* attr : {"x", "y", "width", "depth", "height"})
      if (!missing && !n.attribute(attr)) missing = attr;
    if (missing) {
      warn(n, element, element + " has no '" + missing + "' attribute: " + std::string(kind) + " dropped");
      continue;
    }
    const double x = need(n, "x", element), y = need(n, "y", element);
    const double w = need(n, "width", element), dp = need(n, "depth", element), h = need(n, "height", element);
    const double angle = number(n, "angle", element).value_or(0);
    const double elev = number(n, "elevation", element).value_or(0);
    if (n.text("visible") == "false") continue;
    if (!sane(x) || !sane(y) || !sane(w) || !sane(dp) || !sane(h) || !sane(elev) || !std::isfinite(angle) || w < 0 ||
        dp < 0 || h < 0) {
      warn(n, element, "a position, size or angle is not a finite, non-negative number: " + std::string(kind) +
                           " dropped");
      continue;
    }
    p.centre = plan_point(x, y);
    p.angle = -angle;  // clockwise on screen → anticlockwise in plan
    p.width = w * kCm, p.depth = dp * kCm, p.height = h * kCm, p.elevation = elev * kCm;
    p.door_or_window = kind == "doorOrWindow";
    const std::string both = n.text("wallCutOutOnBothSides");
    p.cut_both_sides = !both.empty() && std::strchr("1tTyY", both[0]) != nullptr;
    p.cut_out = n.text("staircaseCutOutShape");
    if (p.door_or_window) p.wall_cut_out = n.text("cutOutShape");
    const std::string mirrored = n.text("modelMirrored");  // a boolean as pugixml reads one
    p.mirrored = !mirrored.empty() && std::strchr("1tTyY", mirrored[0]) != nullptr;
    p.model = n.text("model");
    // A piece's colour is before its texture (HomePieceOfFurniture3D), a wall's or room's after.
    p.material = material_of(n.text("color"));
    if (p.material < 0) p.material = surface_material(n, "color", "", element);  // a piece's <texture> has no attribute
    // Else its modelMaterials, each in place of the model's material it names.
    if (p.material < 0) p.model_materials = model_materials_of(n, element);
    if (const std::string r = n.text("modelRotation"); !r.empty()) {
      std::istringstream in(r);
      std::array<double, 9> m{};
      bool ok = true;
      for (double& v : m) ok = ok && (in >> v) && std::isfinite(v);
      if (ok && (in >> std::ws).eof()) p.model_rotation = m;
      else warn(n, element, "modelRotation is not nine numbers: the model is used unrotated");
    }
    if (kind == "light") read_light_sources(n, element, p);
    pieces_.push_back(std::move(p));
  }
}

/// A light piece's power and sources. A source Sweet Home could not place (a coordinate
/// that is not a number) is dropped with a warning naming it; the piece stays.
void HomeReader::read_light_sources(const HomeElement& n, const std::string& element, PieceIn& p) {
  p.screen_centre = {need(n, "x", element), need(n, "y", element)};
  p.screen_angle = number(n, "angle", element).value_or(0);
  if (const std::optional<double> power = number(n, "power", element)) {
    if (std::isfinite(*power)) p.power = std::clamp(*power, 0.0, 1.0);
    else warn(n, element, "power is not a number: 0.5 (Sweet Home's default) used");
  }
  int k = 0;
  for (const HomeElement* s : tree_.children(n, "lightSource")) {
    const std::string who = element + ", light source " + std::to_string(++k);
    PieceIn::LightSourceIn src;
    src.where = loc(*s, who);
    bool ok = true;
    for (auto [attr, v] : {std::pair{"x", &src.x}, std::pair{"y", &src.y}, std::pair{"z", &src.z}}) {
      const std::optional<double> f = number(*s, attr, who);
      if (!f) continue;  // Sweet Home's LightSource has no default, but a missing one is the centre here
      if (!std::isfinite(*f) || std::fabs(*f) > 1e3) ok = false;
      else *v = *f;
    }
    if (!ok) {
      warn(*s, who, "a coordinate is not a finite number: light source dropped");
      continue;
    }
    src.colour = s->text("color");
    p.light_sources.push_back(std::move(src));
  }
}

/// A door's or window's cutOutShape (an SVG path in the unit square of its face, y down)
/// as the polygon it cuts, x turned end for end when `flip` (the piece's width runs against
/// the wall's centre line, or its model is mirrored); empty for a rectangle filling the
/// square, or a path that does not parse or encloses nothing (then the whole square is cut,
/// as the shape's bounds are).
std::vector<Vec2> wall_cut_out_shape(const std::string& path, bool flip) {
  const std::vector<Vec2> outline = svg_path_outline(path);
  if (std::fabs(signed_area(outline)) < 1e-6) return {};
  std::vector<Vec2> out;
  for (Vec2 u : outline) out.push_back({flip ? 1 - u.x : u.x, u.y});
  if (std::fabs(std::fabs(signed_area(out)) - 1) < 1e-6) return {};  // the square itself
  return out;
}

/// A strip across a cut-out: from u0 to u1 of its width, open from y0 down to y1 (unit
/// square, y down from the top).
struct CutOutStrip {
  double u0, u1, y0, y1;
};

/// The cut-out as strips side by side across its width, each open over what the shape opens
/// all across it (no more: a wall is never cut where Sweet Home leaves it standing). Samples
/// 1 cm apart; a strip runs on while its top and bottom stay within 4 cm of their extremes
/// (`height` and `width` [m], the face's), and is at least 4 cm and a twelfth of the width
/// wide: an arch is a few strips, each a doorway cell, stepped 4 cm where it is flat.
std::vector<CutOutStrip> cut_out_strips(const std::vector<Vec2>& shape, double height, double width) {
  constexpr double kStep = 0.04;  // [m]
  const int n = std::clamp(int(std::ceil(width / 0.01)), 12, 600);
  const int least = std::max(1, int(std::ceil(n * std::max(0.04 / width, 1.0 / 12))));  // samples a strip spans
  // The shape's open extent down a vertical line at u: the span between the first and last
  // crossings (a cut-out is one hole).
  auto extent = [&](double u) {
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (size_t k = 0; k < shape.size(); ++k) {
      const Vec2 a = shape[k], b = shape[(k + 1) % shape.size()];
      if ((a.x < u) == (b.x < u) && a.x != u) continue;
      const double y = a.x == b.x ? std::min(a.y, b.y) : a.y + (b.y - a.y) * (u - a.x) / (b.x - a.x);
      const double y2 = a.x == b.x ? std::max(a.y, b.y) : y;
      lo = std::min(lo, y), hi = std::max(hi, y2);
    }
    return std::pair{lo, hi};
  };
  std::vector<std::pair<double, double>> at(size_t(n) + 1);
  for (int k = 0; k <= n; ++k) at[size_t(k)] = extent(std::clamp(double(k) / n, 1e-9, 1 - 1e-9));
  std::vector<CutOutStrip> out;
  int from = 0;
  while (from < n) {
    double top_lo = at[size_t(from)].first, top_hi = top_lo, bot_lo = at[size_t(from)].second, bot_hi = bot_lo;
    int to = from + 1;
    for (; to <= n; ++to) {
      const auto [t, b] = at[size_t(to)];
      const double tl = std::min(top_lo, t), th = std::max(top_hi, t), bl = std::min(bot_lo, b), bh = std::max(bot_hi, b);
      if (to > from + least && ((th - tl) * height > kStep || (bh - bl) * height > kStep)) break;
      top_lo = tl, top_hi = th, bot_lo = bl, bot_hi = bh;
    }
    to = std::min(to - 1, n);
    if (to == from) to = from + 1;
    out.push_back({double(from) / n, double(to) / n, std::max(0.0, top_hi), std::min(1.0, bot_lo)});
    from = to;
  }
  return out;
}

/// The openings a hole cuts on one straight piece of wall, where `whole` spans it: strips
/// across it, between the ends of its doors and windows and their shapes' strips; each open
/// over the union of what they open all across it (where that is not one interval, from
/// the lowest to the highest, as one opening cut for both); neighbours open alike made one;
/// none where all is shut. Heights are clipped to the storey's `ceiling` [m].
std::vector<Opening> union_strips(const Hole& hole, const Opening& whole, double ceiling) {
  struct Strip {
    double u0, u1, sill, head;  // u: 0 … 1 across the hole
  };
  const double span = hole.a1 - hole.a0;
  std::vector<Strip> own;
  std::vector<double> cuts{0, 1};
  for (const HoleShape& m : hole.shapes) {
    const double u0 = (m.a0 - hole.a0) / span, u1 = (m.a1 - hole.a0) / span;
    if (m.shape.empty()) {
      own.push_back({u0, u1, m.sill, m.head});
    } else {
      for (const CutOutStrip& c : cut_out_strips(m.shape, m.height, (u1 - u0) * whole.width))
        own.push_back({u0 + c.u0 * (u1 - u0), u0 + c.u1 * (u1 - u0), m.bottom + m.height * (1 - c.y1),
                       m.bottom + m.height * (1 - c.y0)});
    }
  }
  for (const Strip& o : own) cuts.push_back(o.u0), cuts.push_back(o.u1);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end(), [](double a, double b) { return b - a < 1e-9; }), cuts.end());
  std::vector<Strip> out;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double u0 = cuts[k], u1 = cuts[k + 1];
    std::vector<std::pair<double, double>> open;
    for (const Strip& o : own)
      if (o.u0 <= u0 + 1e-9 && o.u1 >= u1 - 1e-9 && o.head - o.sill >= kMinOpening)
        open.push_back({std::max(0.0, o.sill), std::min(ceiling, o.head)});
    Strip s{u0, u1, -1, -1};
    if (!open.empty()) {
      std::sort(open.begin(), open.end());
      s.sill = open.front().first;
      s.head = open.front().second;
      for (const auto& [lo, hi] : open) s.head = std::max(s.head, hi);  // one interval, or their hull
      if (s.head - s.sill < kMinOpening) s.sill = s.head = -1;
    }
    if (!out.empty() && out.back().sill == s.sill && out.back().head == s.head) out.back().u1 = u1;
    else out.push_back(s);
  }
  out.erase(std::remove_if(out.begin(), out.end(), [](const Strip& s) { return s.head < 0; }), out.end());
  std::vector<Opening> parts;
  for (size_t k = 0; k < out.size(); ++k) {
    Opening part = whole;
    // Strips that touch share their end exactly; the last ends where the whole does.
    part.at = k > 0 && out[k - 1].u1 == out[k].u0 ? parts.back().at + parts.back().width
                                                   : whole.at + out[k].u0 * whole.width;
    part.width = out[k].u1 == 1 ? whole.at + whole.width - part.at : whole.at + out[k].u1 * whole.width - part.at;
    part.sill = out[k].sill;
    part.head = out[k].head;
    if (out.size() > 1) part.name += " (strip " + std::to_string(k + 1) + " of " + std::to_string(out.size()) + ")";
    parts.push_back(part);
  }
  return parts;
}

/// Finds the wall a door or window sits in, as Sweet Home 3D's Wall3D cuts it: the wall of
/// its storey, running parallel to its width, whose volume its footprint enters (an area
/// of their intersection, not a touch); of several, the one whose centre line passes
/// nearest its centre. Avenues cuts holes through a wall only, so it takes a piece that
/// crosses the wall's whole thickness, or one Sweet Home cuts through both sides anyway
/// (wallCutOutOnBothSides). A piece reaching only partly in (a shutter on the façade,
/// a frame laid on one face) makes a niche in Sweet Home: no opening, with a warning;
/// taken as a hole, it would widen the window beside it. Its span along that centre line
/// (the piece's width, clipped to the wall) is kept as two points, cut out by
/// cut_openings() once every piece has found its wall.
void HomeReader::find_wall(PieceIn& p) {
  const Vec2 axis{std::cos(p.angle), std::sin(p.angle)};
  long best_wall = -1, niche_wall = -1;
  double best_score = HUGE_VAL, best_s = 0, niche_reach = 0;
  bool best_forward = true;  // the piece's width axis runs along the wall's centre line
  for (size_t i = 0; i < drafts_.size(); ++i) {
    const Wall& w = drafts_[i].wall;
    if (w.storey != p.storey) continue;
    double along = 0;
    for (size_t k = 0; k + 1 < w.centre.size(); ++k) {
      const Vec2 a = w.centre[k], b = w.centre[k + 1];
      const double len = length(b - a);
      const Vec2 d = (1.0 / len) * (b - a);
      const double t = dot(p.centre - a, d);
      const double off = cross(d, p.centre - a);  // signed, across the wall
      const double sin_turn = std::fabs(cross(d, axis));
      // The footprint's half extent across the wall, and how far of the wall's thickness it covers.
      const double half = p.depth / 2 * std::fabs(dot(d, axis)) + p.width / 2 * sin_turn;
      const double t2 = w.thickness / 2;
      const double reach = std::min(off + half, t2) - std::max(off - half, -t2);
      const bool meets = w.thickness > 0 ? reach > kTouch : std::fabs(off) < half;
      const double beyond = std::max({0.0, -t, t - len});  // along the line, past the segment's ends
      if (sin_turn <= kParallelSin && meets && beyond <= p.width / 2) {
        if (p.cut_both_sides || reach >= w.thickness - kJoinGap) {
          const double score = std::fabs(off) + beyond;
          if (score < best_score)
            best_score = score, best_wall = long(i), best_s = along + std::clamp(t, 0.0, len),
            best_forward = dot(d, axis) > 0;
        } else if (reach > niche_reach) {
          niche_reach = reach, niche_wall = long(i);
        }
      }
      along += len;
    }
  }
  if (best_wall < 0 && niche_wall >= 0) {
    const Wall& w = drafts_[size_t(niche_wall)].wall;
    plan_.warnings.push_back(p.where.str() + ": reaches only " + format_number("%.1f", niche_reach * 100) +
                             " cm into wall '" + w.name + "' (" + format_number("%.1f", w.thickness * 100) +
                             " cm thick), a niche in Sweet Home 3D, not a hole through: no opening cut, it stands "
                             "as a piece of furniture");
    p.in_no_wall = true;
    return;
  }
  if (best_wall < 0) {
    plan_.warnings.push_back(p.where.str() + ": lies in no wall of its level (none parallel to it that it enters): "
                             "no opening cut, it stands as a piece of furniture");
    p.in_no_wall = true;
    return;
  }
  const Wall& w = drafts_[size_t(best_wall)].wall;
  const Storey& st = plan_.storeys[size_t(w.storey)];
  const double total = w.length();
  Hole h;
  h.a0 = std::max(0.0, best_s - p.width / 2);
  h.a1 = std::min(total, best_s + p.width / 2);
  h.o.name = p.name;
  h.o.where = p.where;
  h.o.sill = std::max(0.0, p.elevation);
  h.o.head = std::min(st.height, p.elevation + p.height);
  h.o.kind = p.elevation < kDoorSill ? OpeningKind::Door : OpeningKind::Window;
  if (h.o.head - h.o.sill < kMinOpening || h.a1 - h.a0 < kMinOpening) {
    plan_.warnings.push_back(p.where.str() + ": no part of it lies within wall '" + w.name + "' and below the ceiling " +
                             "of its storey: no opening cut");
    return;
  }
  HoleShape own{h.a0, h.a1, h.o.sill, h.o.head, {}, p.elevation, p.height};
  // An arched or round window: its cut-out along the wall (x from a0 to a1), unless the
  // wall's end clips it.
  if (!p.wall_cut_out.empty() && h.a0 <= best_s - p.width / 2 + 1e-9 && h.a1 >= best_s + p.width / 2 - 1e-9)
    own.shape = wall_cut_out_shape(p.wall_cut_out, p.mirrored != !best_forward);
  h.shapes = {own};
  holes_.resize(drafts_.size());
  holes_[size_t(best_wall)].push_back(h);
}

/// The point at distance s along polyline c.
Vec2 point_along(const std::vector<Vec2>& c, double s) {
  double along = 0;
  for (size_t i = 0; i + 1 < c.size(); ++i) {
    const double len = length(c[i + 1] - c[i]);
    if (s <= along + len || i + 2 == c.size())
      return c[i] + (len > 0 ? std::clamp((s - along) / len, 0.0, 1.0) : 0.0) * (c[i + 1] - c[i]);
    along += len;
  }
  return c.back();
}

/// Makes p a vertex of polyline c (it lies on it, on segment `from` or later): returns its
/// index. A point within `snap` of a vertex is that vertex.
size_t insert_vertex(std::vector<Vec2>& c, std::vector<bool>& arc, Vec2 p, double snap, size_t from) {
  size_t best = from;
  double best_d = HUGE_VAL;
  for (size_t i = from; i + 1 < c.size(); ++i) {
    const double d = distance_to_segment(p, c[i], c[i + 1]);
    if (d < best_d) best_d = d, best = i;
  }
  if (length(p - c[best]) <= snap) return best;
  if (length(p - c[best + 1]) <= snap) return best + 1;
  c.insert(c.begin() + long(best) + 1, p);
  arc.insert(arc.begin() + long(best) + 1, bool(arc[best]));
  return best + 1;
}

/// Does polyline c turn at its interior vertex i?
bool bends_at(const std::vector<Vec2>& c, size_t i) {
  if (i == 0 || i + 1 >= c.size()) return false;
  const Vec2 u = c[i] - c[i - 1], v = c[i + 1] - c[i];
  return std::fabs(cross(u, v)) > 1e-9 * length(u) * length(v);
}

/// Cuts the doors and windows found in each wall. Overlapping ones (a door frame and its
/// door, two windows drawn into each other) become one, their union along the wall and in
/// height. Where the centre line bends under an opening only a little (a tessellated arc:
/// Sweet Home's windows are flat boxes), the bend is straightened to the chord between the
/// opening's ends, so that the opening lies on one straight segment as outline.cpp wants;
/// across a real corner the opening is cut in one part per segment.
void HomeReader::cut_openings() {
  holes_.resize(drafts_.size());
  for (size_t wi = 0; wi < drafts_.size(); ++wi) {
    Wall& w = drafts_[wi].wall;
    auto& hs = holes_[wi];
    std::stable_sort(hs.begin(), hs.end(), [](const Hole& a, const Hole& b) { return a.a0 < b.a0; });
    std::vector<Hole> merged;
    for (Hole& h : hs) {
      if (!merged.empty() && h.a0 < merged.back().a1 - 1e-6) {
        Hole& m = merged.back();
        plan_.warnings.push_back(h.o.where.str() + ": overlaps " + m.o.where.element + " (line " +
                                 std::to_string(m.o.where.line) + ") in wall '" + w.name + "': one opening cut for both");
        m.a1 = std::max(m.a1, h.a1);
        m.shapes.insert(m.shapes.end(), h.shapes.begin(), h.shapes.end());
        m.o.sill = std::min(m.o.sill, h.o.sill);
        m.o.head = std::max(m.o.head, h.o.head);
        if (h.o.kind == OpeningKind::Door) m.o.kind = OpeningKind::Door;
        m.o.name += " + " + h.o.name;
        continue;
      }
      merged.push_back(std::move(h));
    }
    // Each span's ends become vertices, in order along the wall (a closed ring's first
    // point is also its last): later spans only change the line beyond earlier ones.
    // [m] An opening's end this close to a vertex ends at the vertex: no piece of the centre
    // line is shorter, so that outline.cpp's mitres (directions of pieces, compared to 1e-12)
    // see two pieces in line as in line.
    const double snap = 0.01;
    const std::vector<Vec2> read = w.centre;
    std::vector<std::pair<size_t, size_t>> span(merged.size());
    size_t from = 0;
    for (size_t j = 0; j < merged.size(); ++j) {
      size_t i0 = insert_vertex(w.centre, w.from_arc, point_along(read, merged[j].a0), snap, from);
      size_t i1 = std::max(i0, insert_vertex(w.centre, w.from_arc, point_along(read, merged[j].a1), snap, i0));
      if (i1 > i0 + 1) {
        double dev = 0;
        bool arc = false;
        for (size_t k = i0 + 1; k < i1; ++k) dev = std::max(dev, distance_to_segment(w.centre[k], w.centre[i0], w.centre[i1]));
        for (size_t k = i0; k < i1; ++k) arc |= w.from_arc[k];
        if (dev <= std::max(plan_.arc_tolerance, w.thickness / 4)) {  // else a real corner: parts
          w.centre.erase(w.centre.begin() + long(i0) + 1, w.centre.begin() + long(i1));
          w.from_arc.erase(w.from_arc.begin() + long(i0) + 1, w.from_arc.begin() + long(i1));
          w.from_arc[i0] = arc;
          i1 = i0 + 1;
        }
      }
      // Never start an opening where the line bends slightly (straightening makes such
      // bends): outline.cpp would clip its strip a hair past the mitre there, and the
      // clip's rounding leave a pocket of free space of no area. The solid wall runs on
      // past the mitre instead (h·tan(θ/2) on the faces), by at least `snap`.
      if (i1 > i0 && bends_at(w.centre, i0)) {
        const Vec2 u = w.centre[i0] - w.centre[i0 - 1], d = w.centre[i0 + 1] - w.centre[i0];
        const double lu = length(u), ld = length(d);
        const double tan_half = std::fabs(cross(u, d)) / (lu * ld + dot(u, d));  // tan(θ/2), θ the turn
        const double past = std::max(snap, w.thickness / 2 * tan_half + 1e-3);
        if (std::isfinite(past) && past <= 2 * snap && past < ld / 2) {
          w.centre.insert(w.centre.begin() + long(i0) + 1, w.centre[i0] + (past / ld) * d);
          w.from_arc.insert(w.from_arc.begin() + long(i0) + 1, bool(w.from_arc[i0]));
          ++i0, ++i1;
        }
      }
      span[j] = {i0, i1};
      from = i1;
    }
    // Distances along the final centre line, summed as outline.cpp sums them.
    std::vector<double> cum{0};
    for (size_t k = 0; k + 1 < w.centre.size(); ++k) cum.push_back(cum.back() + length(w.centre[k + 1] - w.centre[k]));
    for (size_t j = 0; j < merged.size(); ++j) {
      const auto [v0, v1] = span[j];
      std::vector<Opening> parts;
      for (size_t k = v0; k < v1; ++k) {
        Opening part = merged[j].o;
        // outline.cpp places an opening on the segment whose [start, start + length) holds
        // `at`, and clamps its end to the segment. Start a hair (far below its nanometre
        // grid) past the corner, end a hair beyond the next: with the sums rounded either
        // way, the opening then never lands on the segment before with width 1e-16, nor
        // leaves a solid strip of width 1e-16 before the next, whose clipped corners would
        // be pockets of free space of no area. The hair beyond is within the TOML reader's
        // slack of 1e-9 m, so that the plan saved as TOML (--save-plan) reads back.
        part.at = k == 0 ? 0.0 : cum[k] + 1e-11;
        part.width = cum[k + 1] + 5e-10 - part.at;
        if (part.width >= kMinOpening || v1 == v0 + 1) parts.push_back(part);
      }
      // An arched or round window, or doors and windows drawn into each other, on one
      // straight piece: strips across it, each open over what their union opens all across it.
      if (parts.size() == 1 && (merged[j].shapes.size() > 1 || !merged[j].shapes[0].shape.empty())) {
        const Storey& st = plan_.storeys[size_t(w.storey)];
        parts = union_strips(merged[j], parts[0], st.height);
        w.openings.insert(w.openings.end(), parts.begin(), parts.end());
        continue;
      }
      for (size_t k = 0; k < parts.size() && parts.size() > 1; ++k)
        parts[k].name += " (part " + std::to_string(k + 1) + " of " + std::to_string(parts.size()) + ")";
      w.openings.insert(w.openings.end(), parts.begin(), parts.end());
    }
  }
}

// --- walls into the plan: heights, and sloped walls stepped -------------------------------

void HomeReader::finish_walls() {
  for (Draft& d : drafts_) {
    const Storey& st = plan_.storeys[size_t(d.wall.storey)];
    auto cut = [&](double h) { return h >= st.height - 1e-9 ? -1.0 : h; };
    if (std::max(d.h0, d.h1) > st.height + 1e-6) ++walls_cut_;
    if (!d.sloped()) {
      d.wall.height = cut(d.h0);
      plan_.walls.push_back(std::move(d.wall));
      continue;
    }
    // A sloped top stands as it is (Wall::height_at_end), cut at the ceiling where it
    // rises through it; a wall lower than kMinOpening all along stands nowhere.
    if (d.wall.thickness > 0) {
      if (std::max(d.h0, d.h1) < kMinOpening) continue;
      if (std::min(d.h0, d.h1) >= st.height - 1e-9) {
        d.wall.height = -1;
      } else {
        d.wall.height = d.h0;
        d.wall.height_at_end = d.h1;
      }
      plan_.walls.push_back(std::move(d.wall));
      continue;
    }
    // A wall of no thickness has no top to slope: its top becomes steps of constant height
    // (the mean over the piece), at most kStep apart, never cut inside an opening.
    const double len = d.wall.length();
    const double rise = d.h1 - d.h0;
    const double most = std::clamp(std::floor(len / kMinStepPiece), 1.0, 1000.0);  // pieces
    const int n = int(std::clamp(std::ceil(std::fabs(rise) / kStep - 1e-9), 1.0, most));
    std::vector<double> cuts{0};
    for (int j = 1; j < n; ++j) {
      const double s = len * j / n;
      bool in_opening = false;
      for (const Opening& o : d.wall.openings) in_opening |= s > o.at + 1e-6 && s < o.at + o.width - 1e-6;
      if (!in_opening) cuts.push_back(s);
    }
    cuts.push_back(len);
    struct Step { double s0, s1, h; };
    std::vector<Step> steps;
    for (size_t j = 0; j + 1 < cuts.size(); ++j) {
      const double h = cut(d.h0 + rise * (cuts[j] + cuts[j + 1]) / (2 * len));
      if (!steps.empty() && std::fabs(steps.back().h - h) < 1e-9) steps.back().s1 = cuts[j + 1];
      else steps.push_back({cuts[j], cuts[j + 1], h});
    }
    const bool stepped = steps.size() > 1;  // not when the whole slope is above the ceiling
    sloped_ += stepped;
    int k = 0;
    for (const Step& s : steps) {
      ++k;
      if (s.h >= 0 && s.h < kMinOpening) continue;  // the low end of a wall sloping to nothing
      Wall piece;
      piece.name = steps.size() > 1 ? d.wall.name + " step " + std::to_string(k) : d.wall.name;
      piece.storey = d.wall.storey;
      piece.thickness = d.wall.thickness;
      piece.material = d.wall.material;
      piece.where = d.wall.where;
      piece.height = s.h;
      sub_polyline(d.wall.centre, d.wall.from_arc, s.s0, s.s1, piece.centre, piece.from_arc);
      if (piece.centre.size() < 2) continue;
      for (const Opening& o : d.wall.openings)
        if (o.at >= s.s0 - 1e-6 && o.at < s.s1) {
          Opening q = o;
          q.at = std::max(0.0, o.at - s.s0);
          piece.openings.push_back(q);
        }
      steps_ += stepped;
      plan_.walls.push_back(std::move(piece));
    }
  }
}

// --- rooms ----------------------------------------------------------------------------------

/// A point well inside a room: of points sampled over the polygon (a grid, then finer grids
/// around the best), the one farthest from the polygon's edges and from every wall face of
/// its storey. Not the centroid: rooms are often L-shaped, and partitions cross them.
Vec2 label_point(const std::vector<Vec2>& poly, const std::vector<const Wall*>& walls) {
  Vec2 lo{HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL};
  for (Vec2 p : poly) lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)}, hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  std::vector<const Wall*> near;  // walls with a segment whose box meets the room's
  for (const Wall* w : walls)
    for (size_t k = 0; k + 1 < w->centre.size(); ++k) {
      const Vec2 a = w->centre[k], b = w->centre[k + 1];
      const double r = w->thickness / 2;
      if (std::max(a.x, b.x) + r >= lo.x && std::min(a.x, b.x) - r <= hi.x && std::max(a.y, b.y) + r >= lo.y &&
          std::min(a.y, b.y) - r <= hi.y) {
        near.push_back(w);
        break;
      }
    }
  auto clearance = [&](Vec2 p) {
    double c = HUGE_VAL;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) c = std::min(c, distance_to_segment(p, poly[j], poly[i]));
    for (const Wall* w : near)
      for (size_t k = 0; k + 1 < w->centre.size(); ++k)
        c = std::min(c, distance_to_segment(p, w->centre[k], w->centre[k + 1]) - w->thickness / 2);
    return c;
  };
  Vec2 best = centroid(poly);
  double best_c = inside_polygon(poly, best) ? clearance(best) : -HUGE_VAL;
  double cell = std::max(hi.x - lo.x, hi.y - lo.y) / 32;
  if (!(cell > 0)) return best;
  for (double y = lo.y + cell / 2; y < hi.y; y += cell)
    for (double x = lo.x + cell / 2; x < hi.x; x += cell) {
      const Vec2 p{x, y};
      if (!inside_polygon(poly, p)) continue;
      const double c = clearance(p);
      if (c > best_c) best_c = c, best = p;
    }
  for (int round = 0; round < 3; ++round) {  // finer grids around the best so far
    const Vec2 centre = best;
    for (int j = -4; j <= 4; ++j)
      for (int i = -4; i <= 4; ++i) {
        const Vec2 p{centre.x + i * cell / 4, centre.y + j * cell / 4};
        if (!inside_polygon(poly, p)) continue;
        const double c = clearance(p);
        if (c > best_c) best_c = c, best = p;
      }
    cell /= 4;
  }
  return best;
}

std::vector<HomeReader::RoomIn> HomeReader::collect_rooms(const HomeElement& home) {
  std::vector<RoomIn> rooms;
  int count = 0;
  for (const HomeElement* np : tree_.children(home, "room")) {
    const HomeElement& n = *np;
    ++count;
    const std::string name = n.text("name");
    const std::string element = name.empty() ? "room " + std::to_string(count) : "room '" + name + "'";
    RoomIn r;
    r.named = !name.empty();
    r.room.name = r.named ? name : "room " + std::to_string(count);
    r.room.where = loc(n, element);
    r.room.storey = storey_of(n, element);
    if (r.room.storey == kHiddenLevel) continue;
    r.room.floor = surface_material(n, "floorColor", "floorTexture", element);
    r.room.ceiling = surface_material(n, "ceilingColor", "ceilingTexture", element);
    bool ok = true;
    for (const HomeElement* pt : tree_.children(n, "point")) {
      if (!pt->attribute("x") || !pt->attribute("y")) {
        ok = false;
        break;
      }
      const double x = need(*pt, "x", element), y = need(*pt, "y", element);
      ok &= sane(x) && sane(y);
      const Vec2 p = plan_point(x, y);
      if (r.poly.empty() || length(p - r.poly.back()) > 1e-9) r.poly.push_back(p);
    }
    while (r.poly.size() > 1 && length(r.poly.front() - r.poly.back()) <= 1e-9) r.poly.pop_back();
    if (!ok || r.poly.size() < 3 || std::fabs(signed_area(r.poly)) < 1e-6) {
      warn(n, element, ok ? "the room's polygon has no area: dropped"
                          : "a point has no x or y, or one that is not a finite number: room dropped");
      continue;
    }
    rooms.push_back(std::move(r));
  }
  return rooms;
}

// A home of rooms and no walls: Sweet Home 3D draws each room's floor and ceiling in the
// open. Here each edge of a room is a wall of no thickness with one gap its whole length
// and height: the room keeps its floor, ceiling and outline (the sheet's top and bottom
// edges are real lines), and is open to the outside and to its neighbours all round. An
// edge two rooms share is one wall; edges that overlap only in part are left to the exact
// triangulation, which splits them where they meet.
void HomeReader::open_room_edges(const std::vector<RoomIn>& rooms) {
  std::set<std::tuple<StoreyId, double, double, double, double>> seen;
  for (const RoomIn& r : rooms) {
    const double height = plan_.storeys[size_t(r.room.storey)].height;
    for (size_t i = 0; i < r.poly.size(); ++i) {
      Vec2 a = r.poly[i], b = r.poly[(i + 1) % r.poly.size()];
      if (std::tie(b.x, b.y) < std::tie(a.x, a.y)) std::swap(a, b);
      const double len = length(b - a);
      if (len < kMinOpening || !seen.insert({r.room.storey, a.x, a.y, b.x, b.y}).second) continue;
      Wall w;
      w.name = r.room.name + " edge " + std::to_string(i + 1);
      w.storey = r.room.storey;
      w.thickness = 0;
      w.centre = {a, b};
      w.from_arc = {false};
      w.where = r.room.where;
      Opening o;
      o.name = w.name;
      o.kind = OpeningKind::Gap;
      o.at = 0;
      o.width = len;
      o.sill = 0;
      o.head = height;
      o.where = r.room.where;
      w.openings.push_back(o);
      plan_.walls.push_back(std::move(w));
    }
  }
  plan_.warnings.push_back(file_ + ": the home has no walls: its " + std::to_string(rooms.size()) +
                           " room(s) stand in the open, each edge a gap of no thickness");
}

void HomeReader::read_rooms(std::vector<RoomIn> rooms) {
  std::vector<std::vector<const Wall*>> walls_of(plan_.storeys.size());
  for (const Wall& w : plan_.walls) walls_of[size_t(w.storey)].push_back(&w);
  for (RoomIn& r : rooms) r.room.label = label_point(r.poly, walls_of[size_t(r.room.storey)]);
  // Named rooms first; an unnamed one inside a named one is a floor or ceiling drawn apart,
  // not a room of its own (it would only rename the space "Kitchen + room 7").
  int inside_named = 0;
  std::map<std::pair<StoreyId, std::string>, int> seen;
  for (int pass = 0; pass < 2; ++pass)
    for (RoomIn& r : rooms) {
      if (r.named != (pass == 0)) continue;
      if (!r.named) {
        bool within = false;
        for (const RoomIn& o : rooms)
          within |= o.named && o.room.storey == r.room.storey && inside_polygon(o.poly, *r.room.label);
        if (within) {
          ++inside_named;
          continue;
        }
      }
      const int k = ++seen[{r.room.storey, r.room.name}];
      if (k > 1) r.room.name += " (" + std::to_string(k) + ")";
      plan_.rooms.push_back(r.room);
    }
  if (inside_named > 0)
    plan_.warnings.push_back(file_ + ": " + std::to_string(inside_named) +
                             " unnamed room(s) lie within named ones (floors or ceilings drawn apart): not rooms of their own");
}

// --- furniture, staircases, the camera --------------------------------------------------------

/// A staircase's cut-out (an SVG path in the piece's unit square, x along its width, y along
/// its depth, y down) as a polygon in plan: its largest subpath (curves flattened); a path
/// that does not parse, or encloses nothing, is taken as the whole footprint.
std::vector<Vec2> cut_out_outline(const PieceIn& p) {
  std::vector<Vec2> unit = svg_path_outline(p.cut_out);
  if (std::fabs(signed_area(unit)) < 1e-9) unit = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  // Unit square → piece (screen axes: x along the width, y along the depth, both in the
  // y-down plane the angle turns clockwise in) → plan.
  const Vec2 ax{std::cos(p.angle), std::sin(p.angle)};  // width axis, in plan
  const Vec2 ay{ax.y, -ax.x};                           // depth axis (screen +y), in plan
  std::vector<Vec2> out;
  for (Vec2 u : unit) {
    const double ux = p.mirrored ? 1 - u.x : u.x;
    out.push_back(p.centre + ((ux - 0.5) * p.width) * ax + ((u.y - 0.5) * p.depth) * ay);
  }
  if (signed_area(out) < 0) std::reverse(out.begin(), out.end());
  return out;
}

/// Whether bytes are a Wavefront OBJ file: text whose first statements (up to 4 KB) are
/// OBJ's (v, vt, vn, f, g, o, s, l, p, usemtl, mtllib, comments), with a vertex among them.
bool looks_like_obj(const std::string& bytes) {
  const std::string_view head = std::string_view(bytes).substr(0, 4096);
  if (head.find('\0') != std::string_view::npos) return false;
  bool vertex = false;
  int statements = 0;
  size_t i = 0;
  while (i < head.size()) {
    size_t end = head.find('\n', i);
    const bool last = end == std::string_view::npos;
    if (last) end = head.size();
    std::string_view line = head.substr(i, end - i);
    i = end + 1;
    while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front()))) line.remove_prefix(1);
    if (line.empty() || line.front() == '#') continue;
    if (last && bytes.size() > head.size()) break;  // a line cut by the 4 KB window
    const std::string_view word = line.substr(0, line.find_first_of(" \t\r"));
    static constexpr std::string_view kWords[] = {"v", "vt", "vn", "vp", "f", "g", "o", "s", "l", "p", "usemtl", "mtllib"};
    if (std::find(std::begin(kWords), std::end(kWords), word) == std::end(kWords)) return false;
    vertex |= word == "v";
    ++statements;
  }
  return vertex && statements > 0;
}

/// A piece's modelMaterials as HomePieceOfFurniture3D applies them: a material with an
/// opaque colour (alpha not 0) paints the model's material it names in that colour; one
/// with no colour but a texture, in its image's mean colour; any other (a transparent
/// colour, neither) leaves the model's own material as it is.
std::vector<ModelMaterialIn> HomeReader::model_materials_of(const HomeElement& n, const std::string& element) {
  std::vector<ModelMaterialIn> out;
  for (const HomeElement* mp : tree_.children(n, "material")) {
    const HomeElement& m = *mp;
    ModelMaterialIn in;
    in.names = m.attribute("key") ? m.text("key") : m.text("name");
    const std::string what = element + ", material '" + m.text("name") + "'";
    in.where = loc(m, what);
    if (const std::string* hex = m.attribute("color")) {
      const std::optional<std::array<double, 3>> c = colour_of(*hex);
      if (!c) {
        warn(m, what, "color \"" + *hex + "\" is not a colour (AARRGGBB): the model's own material stays");
      } else if (!(hex->size() == 8 && hex->compare(0, 2, "00") == 0)) {
        in.colour = c;
        in.what = "#" + hex->substr(hex->size() - 6);
      }
    } else {
      for (const HomeElement* tp : tree_.children(m, "texture")) {
        const std::string image = tp->text("image");
        if (image.empty()) break;
        bool first = false;
        const MaterialFiles::Image& mean = files_.image(image, &first);
        if (!mean.at_hand) warn(*tp, what, "texture image " + image + " is not at hand: the model's own material stays");
        if (first && !mean.problem.empty())
          warn(*tp, what, mean.problem + ": the material keeps its colour without it");
        if ((in.colour = mean.colour)) in.what = "texture " + image;
        break;
      }
    }
    out.push_back(std::move(in));
  }
  return out;
}

/// A model's own materials coloured as its MTL libraries say (plans/obj_materials.h,
/// colour_obj_materials: map_Kd's image mean, else Kd as sRGB), the libraries found beside
/// the model (its folder in the .sh3d, in a zipped model, or under a bare Home.xml's
/// folder), their images beside them. A material no library at hand defines takes Java 3D's
/// built-in material of its name, as Sweet Home's OBJLoader does; one neither defines keeps
/// Avenues' default colour (one warning for the home lists them). `libraries`: the OBJ's mtllib
/// arguments, as read_mesh_bytes found them.
void HomeReader::colour_model(Mesh& m, const std::vector<std::string>& libraries, const PieceIn& p) {
  const ObjColouring c =
      colour_obj_materials(m, libraries, p.model, files_, p.where.str() + ": model " + p.model + ": ", plan_.warnings);
  undefined_materials_.insert(c.undefined.begin(), c.undefined.end());
}

/// The piece's model fitted to it as Sweet Home fits it: turned by modelRotation, its
/// bounds scaled to the piece's width (x), height (y, up) and depth (z, towards the front),
/// mirrored if asked, in the piece's own axes (base centred on the origin, z up, the front
/// towards −y in plan). nullptr when the piece names no model or it is not at hand: a box
/// of its size stands in.
std::shared_ptr<const Mesh> HomeReader::model_of(const PieceIn& p) {
  if (p.model.empty() || p.width <= 0 || p.depth <= 0 || p.height <= 0) return nullptr;
  auto [it, fresh] = models_read_.try_emplace(p.model);
  if (fresh) {
    std::string ext = lower_extension(p.model);
    std::optional<std::string> bytes = models_ ? models_(p.model) : std::nullopt;
    // Sweet Home tells a model by its content: an entry "28" may well be an OBJ file.
    if (bytes && ext != ".obj" && looks_like_obj(*bytes)) ext = ".obj";
    if (!bytes) {
      plan_.warnings.push_back(p.where.str() + ": model " + p.model + " is not at hand: a box of the piece's size stands in");
    } else if (ext != ".obj") {
      plan_.warnings.push_back(p.where.str() + ": model " + p.model + " is not an OBJ file (only those are read): a box stands in");
    } else {
      try {
        std::vector<std::string> warnings, libraries;
        Mesh read = read_mesh_bytes(*bytes, ext, path_ + ":" + p.model, &warnings, &libraries);
        for (const std::string& w : warnings) plan_.warnings.push_back(p.where.str() + ": " + w);
        colour_model(read, libraries, p);
        it->second = std::make_shared<const Mesh>(std::move(read));
      } catch (const std::runtime_error& e) {
        plan_.warnings.push_back(p.where.str() + ": " + e.what() + ": a box of the piece's size stands in");
      }
    }
  }
  if (!it->second) {
    ++models_missing_;
    return nullptr;
  }
  const Mesh& raw = *it->second;
  const auto& r = p.model_rotation;
  std::vector<Vec3> turned;
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Vec3& v : raw.vertices) {
    const Vec3 t{r[0] * v.x + r[1] * v.y + r[2] * v.z, r[3] * v.x + r[4] * v.y + r[5] * v.z,
                 r[6] * v.x + r[7] * v.y + r[8] * v.z};
    lo = {std::min(lo.x, t.x), std::min(lo.y, t.y), std::min(lo.z, t.z)};
    hi = {std::max(hi.x, t.x), std::max(hi.y, t.y), std::max(hi.z, t.z)};
    turned.push_back(t);
  }
  auto fit = [](double v, double a, double b, double size, bool from_base) {
    const double extent = b - a;
    const double k = extent > 0 ? size / extent : 0;
    return from_base ? (v - a) * k : (v - 0.5 * (a + b)) * k;
  };
  Mesh m = raw;
  // The piece's modelMaterials, each in place of the model's material it names (the first
  // that names it); the path, which tells meshes apart (mesh_key), says what they changed.
  std::string coloured;
  for (Material& mat : m.materials)
    for (const ModelMaterialIn& in : p.model_materials) {
      if (in.names != mat.name) continue;
      if (in.colour) {
        mat.colour = *in.colour;
        mat.where = in.where;
        coloured += (coloured.empty() ? ", materials " : ", ") + mat.name + " " + in.what;
      }
      break;
    }
  m.path = path_ + ":" + p.model + " as " + format_number(p.width * 100) + " x " + format_number(p.depth * 100) + " x " + format_number(p.height * 100) +
           " cm" + (p.mirrored ? ", mirrored" : "") + coloured;
  for (size_t i = 0; i < turned.size(); ++i) {
    const Vec3 t = turned[i];
    const double x = fit(t.x, lo.x, hi.x, p.width, false) * (p.mirrored ? -1 : 1);
    const double up = fit(t.y, lo.y, hi.y, p.height, true), front = fit(t.z, lo.z, hi.z, p.depth, false);
    m.vertices[i] = {x, -front, up};  // Sweet Home's z (towards the front) is the plan's −y
  }
  if (p.mirrored) {
    // A mirror turns polygons inside out: each polygon's fan a, b, c, ... is made again as
    // the fan of a, ..., c, b (its triangles in reverse order, each turned).
    for (size_t t = 0; t < m.triangles.size();) {
      size_t end = t + 1;
      while (end < m.triangles.size() && m.polygon_of[end] == m.polygon_of[t]) ++end;
      std::reverse(m.triangles.begin() + std::ptrdiff_t(t), m.triangles.begin() + std::ptrdiff_t(end));
      for (size_t k = t; k < end; ++k) std::swap(m.triangles[k][1], m.triangles[k][2]);
      t = end;
    }
  }
  smooth_corner_normals(m);
  return std::make_shared<const Mesh>(std::move(m));
}

/// Each light piece's sources as the plan's point lights, where Sweet Home's 3D view puts
/// them (HomeComponent3D): a source at fractions (x, y, z) of the piece's box lies
/// (x − ½)·width across and (½ − y)·depth along the piece before its angle turns it, and
/// z·height above its floor. A light of power 0 is off and lights nothing. Sweet Home gives
/// a Java 3D point light the source's colour times the power; Avenues keeps the colour's hue
/// (its brightest channel at 1) and makes its strength the intensity: 2 × power × that
/// channel, so that a white source at the default power of 0.5 is Avenues' full light.
void HomeReader::add_lights() {
  std::set<std::string> names;
  for (const Light& l : plan_.lights) names.insert(l.name);
  for (const PieceIn& p : pieces_) {
    if (p.light_sources.empty() || !(p.power > 0)) continue;
    const double c = std::cos(p.screen_angle), s = std::sin(p.screen_angle);
    const double w = p.width / kCm, d = p.depth / kCm;  // [cm], as the fractions are taken
    const double floor = plan_.storeys[size_t(p.storey)].elevation + p.elevation;
    for (size_t k = 0; k < p.light_sources.size(); ++k) {
      const PieceIn::LightSourceIn& src = p.light_sources[k];
      Light l;
      l.kind = LightKind::Point;
      l.where = src.where;
      std::string name = p.name + (p.light_sources.size() > 1 ? ", source " + std::to_string(k + 1) : "");
      for (int n = 2; !names.insert(name).second; ++n)
        name = p.name + (p.light_sources.size() > 1 ? ", source " + std::to_string(k + 1) : "") + " (" +
               std::to_string(n) + ")";
      l.name = name;
      const double xl = -w / 2 + src.x * w, yl = d / 2 - src.y * d;
      const Vec2 at = plan_point(p.screen_centre.x + xl * c - yl * s, p.screen_centre.y + xl * s + yl * c);
      l.position = {at.x, at.y, floor + src.z * p.height};
      // Sweet Home's colour (ARGB, alpha unused) in linear light: its hue, and its strength.
      std::array<double, 3> rgb{1, 1, 1};
      double strength = 1;
      if (!src.colour.empty()) {
        if (const std::optional<std::array<double, 3>> lin = colour_of(src.colour)) {
          const double top = std::max({(*lin)[0], (*lin)[1], (*lin)[2]});
          if (top > 0) {
            rgb = {(*lin)[0] / top, (*lin)[1] / top, (*lin)[2] / top};
            strength = srgb_from_linear(top);
          } else {
            strength = 0;
          }
        } else {
          plan_.warnings.push_back(src.where.str() + ": colour \"" + src.colour + "\" is not a colour: white used");
        }
      }
      l.colour = rgb;
      l.intensity = 2 * p.power * strength;
      if (!(l.intensity > 0)) continue;  // a black source lights nothing
      plan_.lights.push_back(std::move(l));
    }
  }
}

void HomeReader::add_furniture() {
  for (const PieceIn& p : pieces_) {
    if (p.door_or_window && !p.in_no_wall) continue;  // the opening it cuts stands for it
    Object o;
    o.name = p.name;
    o.storey = p.storey;
    o.position = {p.centre.x, p.centre.y, p.elevation};
    o.rotation_deg = {0, 0, p.angle * 180 / std::numbers::pi};
    o.box = {p.width, p.depth, p.height};
    o.where = p.where;
    o.model = model_of(p);
    o.material = p.material;
    plan_.objects.push_back(o);
    if (p.cut_out.empty() || p.width <= 0 || p.depth <= 0) continue;
    // A staircase cuts the floors of the storeys it climbs into.
    const double base = plan_.storeys[size_t(p.storey)].elevation + p.elevation, top = base + p.height;
    for (size_t s = 1; s < plan_.storeys.size(); ++s) {
      const double e = plan_.storeys[s].elevation;
      if (!(e > base + 1e-6 && e <= top + 1e-6)) continue;
      FloorOpening f;
      f.name = p.name;
      f.storey = StoreyId(s);
      f.outline = cut_out_outline(p);
      f.where = p.where;
      plan_.floor_openings.push_back(std::move(f));
    }
  }
}

void HomeReader::read_camera(const HomeElement& home) {
  for (const HomeElement* np : tree_.children(home, "observerCamera")) {
    const HomeElement& n = *np;
    if (std::string_view(n.text("attribute")) != "observerCamera") continue;
    const std::string element = "observerCamera";
    const double x = need(n, "x", element), y = need(n, "y", element), z = need(n, "z", element);
    const double yaw = need(n, "yaw", element), pitch = need(n, "pitch", element);
    const double fov = number(n, "fieldOfView", element).value_or(63 * std::numbers::pi / 180);
    if (!sane(x) || !sane(y) || !sane(z) || !std::isfinite(yaw) || !std::isfinite(pitch) || !std::isfinite(fov)) {
      warn(n, element, "a coordinate or angle is not a finite number: no viewpoint");
      return;
    }
    // Sweet Home walks forward along (−sin yaw, cos yaw) on screen (HomeController3D's
    // moveCamera), y down; a positive pitch looks down.
    Viewpoint v;
    v.eye = {x * kCm, -y * kCm, z * kCm};
    const Vec3 dir{-std::sin(yaw) * std::cos(pitch), -std::cos(yaw) * std::cos(pitch), -std::sin(pitch)};
    v.look = v.eye + dir;
    v.fov_deg = std::clamp(fov * 180 / std::numbers::pi, 1.0, 179.0);
    plan_.view = v;
    return;
  }
}

// --- the whole home ---------------------------------------------------------------------------

Plan HomeReader::read() {
  const HomeElement& home = tree_.root();
  plan_.source = path_;
  plan_.lenient = true;
  std::string name = home.text("name");
  plan_.name = std::filesystem::path(name.empty() ? path_ : name).stem().string();
  const double wh = number(home, "wallHeight", "home").value_or(250);
  if (sane(wh) && wh > 0) wall_height_ = wh * kCm;

  read_levels(home);
  read_walls(home);
  join_walls();
  stretch_free_ends();
  collect_pieces(home);
  for (PieceIn& p : pieces_)
    if (p.door_or_window) find_wall(p);
  cut_openings();
  finish_walls();
  std::vector<RoomIn> rooms = collect_rooms(home);
  if (plan_.walls.empty() && walls_dropped_ == 0 && !rooms.empty()) open_room_edges(rooms);
  if (plan_.walls.empty()) {
    // Say why: the reasons each wall was dropped (the first few, and how many more).
    std::string why;
    if (walls_dropped_ > 0) {
      constexpr size_t kShown = 5;
      size_t shown = 0;
      for (const std::string& w : plan_.warnings)
        if (w.find("(wall ") != std::string::npos && shown < kShown) why += "\n  " + w, ++shown;
      if (size_t(walls_dropped_) > shown) why += "\n  ... and " + std::to_string(size_t(walls_dropped_) - shown) + " more";
      why = ": all " + std::to_string(walls_dropped_) + " were dropped:" + why;
    } else if (const size_t n = tree_.children(home, "room").size(); n > 0) {
      why = ", and none of its " + std::to_string(n) + " room(s) has an outline with an area";
    }
    throw PlanError(loc(home, "home"), "the home has no walls" + why);
  }
  read_rooms(std::move(rooms));
  add_furniture();
  add_lights();
  read_camera(home);

  if (models_missing_ > 0)
    plan_.warnings.push_back(file_ + ": " + std::to_string(models_missing_) +
                             " piece(s) of furniture drawn as boxes of their size: their models are not at hand");
  if (!undefined_materials_.empty()) {
    // Neither an MTL library at hand nor Java 3D's built-in table defines them.
    plan_.warnings.push_back(file_ + ": " + std::to_string(undefined_materials_.size()) +
                             " material(s) that models use are defined in no MTL library at hand nor among "
                             "Java 3D's built-in materials (" + ObjColouring::listed(undefined_materials_) +
                             "): they keep Avenues' default colour where no piece's modelMaterials colour them");
  }
  if (walls_cut_ > 0)
    plan_.warnings.push_back(file_ + ": " + std::to_string(walls_cut_) +
                             " wall(s) taller than their storey cut to its ceiling");
  if (sloped_ > 0)
    plan_.warnings.push_back(file_ + ": " + std::to_string(sloped_) + " sloped wall(s) of no thickness (heightAtEnd) " +
                             "stepped into " + std::to_string(steps_) + " pieces of constant height, steps of at most " +
                             format_number(kStep * 100) + " cm: a wall of no thickness has no top to slope");
  return std::move(plan_);
}


/// Home.xml as a home tree: every element below <home>, its attributes as they are, its
/// line and column. Iterative (a home may nest groups thousands deep).
HomeTree home_tree_of_xml(const std::string& text, const std::string& file) {
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size(), pugi::parse_default);
  const LineIndex lines(text);
  if (!parsed) {
    auto [line, col] = lines.at(parsed.offset);
    throw PlanError(SourceLoc{file, line, col, ""}, std::string("XML syntax error: ") + parsed.description());
  }
  const pugi::xml_node home = doc.child("home");
  if (!home) {
    const pugi::xml_node root = doc.document_element();
    throw PlanError(SourceLoc{file, root ? lines.at(root.offset_debug()).first : 0, 0, ""},
                    "not a Sweet Home 3D home: the root element is <" + std::string(root ? root.name() : "") +
                        ">, not <home>");
  }
  HomeTree t;
  t.file = file;
  std::vector<std::pair<pugi::xml_node, size_t>> stack{{home, 0}};
  while (!stack.empty()) {
    const auto [n, parent] = stack.back();
    stack.pop_back();
    const size_t e = t.add(parent, n.name());
    // pugixml's offset of an element is that of its name; point at its '<'.
    std::tie(t.elements[e].line, t.elements[e].column) = lines.at(n.offset_debug() - 1);
    for (const pugi::xml_attribute a : n.attributes()) t.elements[e].set(a.name(), a.value());
    std::vector<pugi::xml_node> kids;
    for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling())
      if (c.type() == pugi::node_element) kids.push_back(c);
    for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back({*it, e});
  }
  return t;
}

/// A home whose ContentDigests names entries the archive does not hold is damaged:
/// Sweet Home 3D says so (DefaultHomeInputStream: DamagedHomeIOException) and opens it
/// with that content missing, if the user agrees. Avenues opens it and says so ("" when
/// nothing is missing).
std::string missing_content(const ZipArchive& zip) {
  const std::optional<std::string> digests = zip.entry("ContentDigests");
  if (!digests) return {};
  std::istringstream in(*digests);
  std::vector<std::string> missing;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.starts_with("Name: ")) continue;
    const std::string name = line.substr(6);
    if (!zip.has(name)) missing.push_back(name);
  }
  if (missing.empty()) return {};
  std::string list;
  for (size_t i = 0; i < missing.size() && i < 5; ++i) list += (i ? ", " : "") + missing[i];
  if (missing.size() > 5) list += " and " + std::to_string(missing.size() - 5) + " more";
  return "the home is damaged: its ContentDigests names " + std::to_string(missing.size()) +
         " entr(ies) the archive does not hold (" + list + "): what uses them is drawn without them";
}

}  // namespace

Plan read_sweet_home(const std::string& path, HomeEntry which, const HomeLimits& limits) {
  const std::string bytes = read_bytes(path);
  std::unique_ptr<ZipArchive> zip;
  ModelSource models;
  std::optional<HomeTree> tree;
  std::vector<std::string> damage;  ///< what was wrong with the archive, said first
  if (looks_like_zip(bytes) || has_sh3d_extension(path)) {
    if (!looks_like_zip(bytes))
      throw PlanError(SourceLoc{path, 0, 0, ""}, "not a Sweet Home 3D .sh3d file: not a zip archive");
    zip = std::make_unique<ZipArchive>(path, bytes, limits.max_entry_bytes);
    const bool has_xml = zip->has("Home.xml"), has_home = zip->has("Home");
    if (!has_xml && !has_home && !zip->repaired().empty())
      throw PlanError(SourceLoc{path, 0, 0, ""}, zip->repaired() + ", and neither Home.xml nor Home is among them");
    if (!has_xml && !has_home)
      throw PlanError(SourceLoc{path, 0, 0, ""},
                      "the archive holds neither a Home.xml nor a serialized Home entry: not a Sweet Home 3D home");
    if (!zip->repaired().empty()) damage.push_back(path + ": " + zip->repaired());
    if (std::string missing = missing_content(*zip); !missing.empty()) damage.push_back(path + ": " + missing);
    const bool xml = which == HomeEntry::Xml || (which == HomeEntry::Preferred && has_xml);
    if (xml && !has_xml)
      throw PlanError(SourceLoc{path, 0, 0, ""}, "the archive holds no Home.xml entry (only the serialized Home)");
    if (!xml && !has_home)
      throw PlanError(SourceLoc{path, 0, 0, ""}, "the archive holds no serialized Home entry (only Home.xml)");
    if (xml) tree = home_tree_of_xml(*zip->entry("Home.xml"), path + ":Home.xml");
    else tree = home_tree_of_serialized(*zip->entry("Home"), path + ":Home");
    // A zipped model's files are asked for one after another (its OBJ, its MTL files, their
    // images): the last zipped model's archive stays open.
    struct Zipped {
      std::optional<std::string> name;  ///< the outer entry it came from
      std::string bytes;
      std::unique_ptr<ZipArchive> zip;  ///< over `bytes`; null when that entry is no zip
    };
    auto zipped = std::make_shared<Zipped>();
    models = [&zip, path, limits, zipped](const std::string& model) -> std::optional<std::string> {
      // "1!/tree.obj": the entry "1" is itself a zip holding the model's files.
      const size_t bang = model.find("!/");
      if (bang == std::string::npos) return zip->entry(model);
      const std::string outer_name = model.substr(0, bang);
      if (zipped->name != outer_name) {
        zipped->zip.reset();
        zipped->name = outer_name;
        std::optional<std::string> outer = zip->entry(outer_name);
        zipped->bytes = outer ? std::move(*outer) : std::string();
        if (looks_like_zip(zipped->bytes))
          zipped->zip = std::make_unique<ZipArchive>(path + ":" + outer_name, zipped->bytes, limits.max_entry_bytes);
      }
      if (!zipped->zip) return std::nullopt;
      return zipped->zip->entry(model.substr(bang + 2));
    };
  } else {
    if (which == HomeEntry::Serialized)
      throw PlanError(SourceLoc{path, 0, 0, ""}, "a bare Home.xml holds no serialized Home entry");
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    models = [dir](const std::string& model) -> std::optional<std::string> {
      // Only below the home's folder: a home names no file elsewhere on the machine.
      const std::filesystem::path rel(model);
      if (rel.empty() || rel.is_absolute() || rel.has_root_name()) return std::nullopt;
      for (const auto& part : rel)
        if (part == "..") return std::nullopt;
      for (const std::filesystem::path& f : {dir / model, dir / "models" / std::filesystem::path(model).filename()}) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(f, ec)) continue;
        std::ifstream in(f, std::ios::binary);
        std::ostringstream s;
        s << in.rdbuf();
        if (in.good() || in.eof()) return s.str();
      }
      return std::nullopt;
    };
    tree = home_tree_of_xml(bytes, path);
  }
  Plan plan = HomeReader(path, *tree, std::move(models)).read();
  plan.warnings.insert(plan.warnings.begin(), damage.begin(), damage.end());
  return plan;
}

}  // namespace avenues
