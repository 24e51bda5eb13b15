// Avenues — reading a plan file (TOML) into a validated Plan.
//
// The format is described for users in docs/PLAN_FORMAT.md; this file implements it.
// The reader works in three steps, each of which may throw a PlanError naming the
// file, line, column and element a mistake is in:
//
//   1. toml++ (v3) parses the text into a tree whose every node and key remembers its
//      source position; TOML syntax errors become PlanErrors at toml++'s position.
//   2. Reader walks the tree element by element (plan settings, materials, storeys,
//      walls with their openings, floor openings, rooms, objects, lights, the view).
//      Every table is checked for unknown keys (with a "did you mean" for typos),
//      every value for its type, finiteness and plausibility, every length converted
//      from the plan's `units` to metres.
//   3. Geometry that only makes sense as a whole is checked per element: arcs are
//      tessellated (Wall::centre), a wall's centre line must not cross itself, its
//      openings must lie on one straight segment each without overlapping, a floor
//      opening's outline must be a simple polygon.
//
// What needs several elements at once (is a room label inside a wall? is a room
// open to the outside?) is checked later, by cells/, which has the exact geometry.
#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <numbers>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "plans/plan.h"
#include "core/srgb.h"
#include "core/number_format.h"

#include "plans/arc.h"
#include "plans/mesh.h"

namespace avenues {
namespace {

/// Any length beyond this many metres is taken for a typo (a plan of a city is ~1e4 m).
constexpr double kAbsurdLength = 1e8;
/// Slack [m] when comparing lengths the user wrote against lengths we computed.
constexpr double kSlack = 1e-9;
/// An arc needing more pieces than this has a tolerance too fine for its radius.
constexpr long kMaxArcPieces = 100000;

/// Levenshtein distance, for "did you mean" hints on misspelt keys and names.
int edit_distance(std::string_view a, std::string_view b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diag = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

/// " (did you mean 'thickness'?)" when some known word is within edit distance 2.
template <class Words>
std::string did_you_mean(std::string_view word, const Words& known) {
  int best = 3;
  std::string_view pick;
  for (const auto& k : known) {
    const int d = edit_distance(word, k);
    if (d < best) best = d, pick = k;
  }
  return pick.empty() ? std::string() : " (did you mean '" + std::string(pick) + "'?)";
}

/// How TOML calls a node's type, for "must be a number, not a string".
const char* type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

/// The units a plan may be written in, and their length in metres.
struct Unit {
  std::string_view name;
  double metres;
};
constexpr Unit kUnits[] = {{"m", 1}, {"cm", 0.01}, {"mm", 0.001}, {"ft", 0.3048}, {"in", 0.0254}};

/// "#rrggbb" (sRGB, as colour pickers give it) → linear RGB, by the sRGB transfer
/// function of IEC 61966-2-1. Returns false if the string is not of that form.
bool parse_hex_colour(std::string_view s, std::array<double, 3>& out) {
  if (s.size() != 7 || s[0] != '#') return false;
  for (int c = 0; c < 3; ++c) {
    int v = 0;
    for (int k = 0; k < 2; ++k) {
      const char h = s[1 + 2 * c + k];
      int d;
      if (h >= '0' && h <= '9') d = h - '0';
      else if (h >= 'a' && h <= 'f') d = h - 'a' + 10;
      else if (h >= 'A' && h <= 'F') d = h - 'A' + 10;
      else return false;
      v = v * 16 + d;
    }
    const double e = v / 255.0;
    out[c] = linear_from_srgb(e);
  }
  return true;
}

// ---------------------------------------------------------------------------------
// Plane geometry used by the validation: segment crossings for "does this centre
// line / outline cross itself". Plain double predicates: the inputs are what a person
// typed (or a few arc pieces), far from the degenerate cases that need exact maths,
// and cells/ recomputes everything exactly anyway.


// ---------------------------------------------------------------------------------

/// One straight or arc entry of a wall's `path`, as the user wrote it, and where its
/// tessellated pieces landed in Wall::centre. Openings are placed by true length along
/// the path as written (an arc counts its arc length, independent of arc_tolerance),
/// then mapped onto the tessellated centre line.
struct PathPiece {
  bool arc = false;
  double from = 0;       ///< [m] true distance along the wall to the piece's start
  double len = 0;        ///< [m] true length (arc length for arcs)
  double tess_from = 0;  ///< [m] distance along the tessellated centre line to its start
};

class Element;

class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  Plan read(const toml::table& root);

  // --- locations and errors -----------------------------------------------------
  SourceLoc loc(const toml::source_region& r, const std::string& element) const {
    return SourceLoc{file_, static_cast<int>(r.begin.line), static_cast<int>(r.begin.column), element};
  }
  [[noreturn]] void fail(const toml::source_region& r, const std::string& element,
                         const std::string& what) const {
    throw PlanError(loc(r, element), what);
  }

  // --- units ----------------------------------------------------------------------
  double unit() const { return unit_; }
  /// A length in metres, printed back in the plan's units: "4.5 m", "12 ft".
  std::string len(double metres) const { return format_number(metres / unit_) + " " + unit_name_; }

 private:
  friend class Element;
  void read_settings(const toml::table& root);
  void read_materials(const toml::table& root);
  void read_storeys(const toml::table& root);
  void read_walls(const toml::table& root);
  void read_wall(const toml::table& t, int index);
  void read_openings(const Element& we, Wall& wall, const std::vector<PathPiece>& pieces);
  void read_floor_openings(const toml::table& root);
  void read_rooms(const toml::table& root);
  void read_objects(const toml::table& root);
  void read_lights(const toml::table& root);
  void read_view(const toml::table& root);

  /// The tables of an array of tables (`[[wall]]` or `wall = [{...}]`); none if absent.
  std::vector<const toml::table*> tables(const toml::table& parent, std::string_view key,
                                         const std::string& element) const;
  MaterialId material(const Element& e, std::string_view key) const;
  StoreyId storey(const Element& e, bool needed_when_several) const;
  /// Registers `name` in `seen`, failing if an element of that kind already has it.
  void unique(std::unordered_set<std::string>& seen, const std::string& name, const Element& e,
              const std::string& kind) const;

  std::string file_;
  double unit_ = 1;
  std::string unit_name_ = "m";
  Plan plan_;
  std::unordered_map<std::string, MaterialId> material_ids_;
  std::unordered_map<std::string, StoreyId> storey_ids_;
};

/// One TOML table standing for one plan element ("wall 'north'"): typed access to its
/// keys, each error naming the key's line and the element.
class Element {
 public:
  Element(const Reader& r, const toml::table& t, std::string name)
      : r_(r), t_(t), name_(std::move(name)) {}

  const std::string& name() const { return name_; }
  const toml::table& table() const { return t_; }
  SourceLoc loc() const { return r_.loc(t_.source(), name_); }

  /// Fails on the first key not in `known` ("unknown key 'thicknes' in wall 'north'
  /// (did you mean 'thickness'?)").
  void allow(std::initializer_list<std::string_view> known) const {
    // toml++ iterates keys in sorted order; report the unknown key written first.
    const toml::key* first = nullptr;
    for (auto&& [k, v] : t_) {
      if (std::find(known.begin(), known.end(), k.str()) != known.end()) continue;
      const auto& s = k.source().begin;
      if (!first || s.line < first->source().begin.line ||
          (s.line == first->source().begin.line && s.column < first->source().begin.column))
        first = &k;
    }
    if (first)
      r_.fail(first->source(), name_,
              "unknown key '" + std::string(first->str()) + "' in " + name_ + did_you_mean(first->str(), known));
  }

  const toml::node* get(std::string_view key) const { return t_.get(key); }
  bool has(std::string_view key) const { return t_.contains(key); }

  /// Where the key is written (its line), or the element's table when it is absent.
  const toml::source_region& where(std::string_view key) const {
    auto it = t_.find(key);
    return it != t_.end() ? it->first.source() : t_.source();
  }
  [[noreturn]] void fail(std::string_view key, const std::string& what) const {
    r_.fail(where(key), name_, what);
  }
  [[noreturn]] void fail_at(const toml::node& n, const std::string& what) const {
    r_.fail(n.source(), name_, what);
  }
  [[noreturn]] void fail_here(const std::string& what) const { r_.fail(t_.source(), name_, what); }

  // --- plain values (of a key, or of a node inside an array) ------------------------
  std::string string_of(const toml::node& n, const std::string& label) const {
    if (auto* s = n.as_string()) return s->get();
    fail_at(n, label + " must be a string, not " + type_name(n));
  }
  /// A finite number; TOML integers and floats alike.
  double number_of(const toml::node& n, const std::string& label) const {
    double v;
    if (auto* i = n.as_integer()) v = static_cast<double>(i->get());
    else if (auto* f = n.as_floating_point()) v = f->get();
    else fail_at(n, label + " must be a number, not " + type_name(n));
    if (!std::isfinite(v)) fail_at(n, label + " must be a finite number, not " + format_number(v));
    return v;
  }
  /// A number in the plan's units, converted to metres; absurd magnitudes refused.
  double length_of(const toml::node& n, const std::string& label) const {
    const double v = number_of(n, label) * r_.unit();
    if (std::fabs(v) > kAbsurdLength)
      fail_at(n, label + " is " + r_.len(v) + ", beyond the " + format_number(kAbsurdLength) +
                     " m any building could measure");
    return v;
  }
  /// An array of exactly `k` lengths.
  std::vector<double> lengths_of(const toml::node& n, size_t k, const std::string& label) const {
    auto* a = n.as_array();
    if (!a || a->size() != k)
      fail_at(n, label + " must be an array of " + std::to_string(k) + " numbers" +
                     (a ? " (it has " + std::to_string(a->size()) + ")" : ", not " + std::string(type_name(n))));
    std::vector<double> out;
    for (size_t i = 0; i < k; ++i) out.push_back(length_of(*a->get(i), label));
    return out;
  }
  Vec2 point2_of(const toml::node& n, const std::string& label) const {
    auto v = lengths_of(n, 2, label);
    return {v[0], v[1]};
  }
  Vec3 point3_of(const toml::node& n, const std::string& label) const {
    auto v = lengths_of(n, 3, label);
    return {v[0], v[1], v[2]};
  }
  /// Linear RGB from [r, g, b] in [0,1] or an sRGB "#rrggbb".
  std::array<double, 3> colour_of(const toml::node& n, const std::string& label) const {
    std::array<double, 3> c{};
    if (auto* s = n.as_string()) {
      if (!parse_hex_colour(s->get(), c))
        fail_at(n, label + " must be [r, g, b] or \"#rrggbb\", not \"" + s->get() + "\"");
      return c;
    }
    auto* a = n.as_array();
    if (!a || a->size() != 3) fail_at(n, label + " must be [r, g, b] or \"#rrggbb\"");
    for (size_t i = 0; i < 3; ++i) {
      c[i] = number_of(*a->get(i), label);
      if (c[i] < 0 || c[i] > 1) fail_at(*a->get(i), label + " components must be in [0, 1], not " + format_number(c[i]));
    }
    return c;
  }

  // --- keyed values: std::nullopt when the key is absent -----------------------------
  std::optional<std::string> string(std::string_view key) const {
    auto* n = get(key);
    if (!n) return std::nullopt;
    return string_of(*n, quote(key));
  }
  std::optional<double> number(std::string_view key) const {
    auto* n = get(key);
    if (!n) return std::nullopt;
    return number_of(*n, quote(key));
  }
  std::optional<double> length(std::string_view key) const {
    auto* n = get(key);
    if (!n) return std::nullopt;
    return length_of(*n, quote(key));
  }
  std::optional<bool> boolean(std::string_view key) const {
    auto* n = get(key);
    if (!n) return std::nullopt;
    if (!n->is_boolean()) fail(key, quote(key) + " must be true or false, not " + std::string(type_name(*n)));
    return n->as_boolean()->get();
  }
  /// A required key: fails naming it when absent.
  const toml::node& need(std::string_view key) const {
    auto* n = get(key);
    if (!n) fail_here(name_ + " needs '" + std::string(key) + "'");
    return *n;
  }
  /// An optional name, non-empty when given.
  std::optional<std::string> name_key() const {
    auto s = string("name");
    if (s && s->empty()) fail("name", "'name' must not be empty");
    return s;
  }

  static std::string quote(std::string_view key) { return "'" + std::string(key) + "'"; }

 private:
  const Reader& r_;
  const toml::table& t_;
  std::string name_;
};

/// "wall 'north'" when the user named it, "wall 3" (its default name) otherwise.
std::string element_name(const char* kind, const std::optional<std::string>& name, int index) {
  return name ? std::string(kind) + " '" + *name + "'" : std::string(kind) + " " + std::to_string(index + 1);
}

// ---------------------------------------------------------------------------------

std::vector<const toml::table*> Reader::tables(const toml::table& parent, std::string_view key,
                                               const std::string& element) const {
  std::vector<const toml::table*> out;
  auto it = parent.find(key);
  if (it == parent.end()) return out;
  auto* arr = it->second.as_array();
  const std::string what = "'" + std::string(key) + "' must be an array of tables ([[" +
                           std::string(key) + "]] sections)";
  if (!arr) fail(it->first.source(), element, what + ", not " + type_name(it->second));
  for (auto& n : *arr) {
    auto* t = n.as_table();
    if (!t) fail(n.source(), element, what + "; found " + type_name(n));
    out.push_back(t);
  }
  return out;
}

MaterialId Reader::material(const Element& e, std::string_view key) const {
  auto name = e.string(key);
  if (!name) return -1;
  auto it = material_ids_.find(*name);
  if (it != material_ids_.end()) return it->second;
  std::vector<std::string> known;
  for (auto& m : plan_.materials) known.push_back(m.name);
  e.fail(key, "unknown material '" + *name + "'" + did_you_mean(*name, known) +
                  (known.empty() ? " (the plan defines no [materials])" : ""));
}

StoreyId Reader::storey(const Element& e, bool needed_when_several) const {
  auto name = e.string("storey");
  if (!name) {
    if (plan_.storeys.size() > 1 && needed_when_several)
      e.fail_here(e.name() + " needs 'storey' (the plan has " + std::to_string(plan_.storeys.size()) +
                  " storeys)");
    return 0;
  }
  auto it = storey_ids_.find(*name);
  if (it != storey_ids_.end()) return it->second;
  std::vector<std::string> known;
  for (auto& s : plan_.storeys) known.push_back(s.name);
  e.fail("storey", "unknown storey '" + *name + "'" + did_you_mean(*name, known));
}

void Reader::unique(std::unordered_set<std::string>& seen, const std::string& name, const Element& e,
                    const std::string& kind) const {
  if (!seen.insert(name).second)
    e.fail(e.has("name") ? "name" : "", "duplicate " + kind + " name '" + name + "'");
}

// --- the plan's own settings -------------------------------------------------------

void Reader::read_settings(const toml::table& root) {
  Element e(*this, root, "plan");
  e.allow({"name", "units", "arc_tolerance", "far_margin", "lenient", "unnamed_spaces_solid", "ground", "sky", "roof", "view", "materials",
           "storey", "wall", "floor_opening", "room", "object", "light"});
  if (auto u = e.string("units")) {
    auto it = std::find_if(std::begin(kUnits), std::end(kUnits), [&](const Unit& x) { return x.name == *u; });
    if (it == std::end(kUnits)) e.fail("units", "unknown units '" + *u + "' (use m, cm, mm, ft or in)");
    unit_ = it->metres;
    unit_name_ = *u;
  }
  plan_.name = e.name_key().value_or(std::filesystem::path(file_).stem().string());
  if (auto tol = e.length("arc_tolerance")) {
    if (*tol <= 0) e.fail("arc_tolerance", "'arc_tolerance' must be > 0, not " + len(*tol));
    plan_.arc_tolerance = *tol;
  }
  if (auto m = e.length("far_margin")) {
    if (*m <= 0) e.fail("far_margin", "'far_margin' must be > 0, not " + len(*m));
    plan_.far_margin = *m;
  }
  if (auto l = e.boolean("lenient")) plan_.lenient = *l;
  if (auto u = e.boolean("unnamed_spaces_solid")) plan_.unnamed_spaces_solid = *u;
}

// --- [materials.NAME] ----------------------------------------------------------------

void Reader::read_materials(const toml::table& root) {
  auto it = root.find("materials");
  auto* mats = it != root.end() ? it->second.as_table() : nullptr;
  if (it != root.end() && !mats)
    fail(it->first.source(), "plan", "'materials' must be a table of [materials.NAME] tables, not " +
                                         std::string(type_name(it->second)));
  static const toml::table kNone;
  for (auto&& [k, v] : mats ? *mats : kNone) {
    const std::string name(k.str());
    const std::string element = "material '" + name + "'";
    auto* t = v.as_table();
    if (!t) fail(k.source(), element, element + " must be a table ([materials." + name + "])");
    Element e(*this, *t, element);
    e.allow({"reflectance", "colour"});
    Material m;
    m.name = name;
    m.where = loc(k.source(), element);
    if (auto r = e.number("reflectance")) {
      if (*r < 0 || *r > 1) e.fail("reflectance", "'reflectance' must be in [0, 1], not " + format_number(*r));
      m.reflectance = *r;
    }
    if (auto* c = e.get("colour")) m.colour = e.colour_of(*c, "'colour'");
    material_ids_[name] = static_cast<MaterialId>(plan_.materials.size());
    plan_.materials.push_back(std::move(m));
  }
  Element top(*this, root, "plan");
  plan_.ground = material(top, "ground");
  plan_.sky = material(top, "sky");
  plan_.roof = material(top, "roof");
}

// --- [[storey]] --------------------------------------------------------------------

void Reader::read_storeys(const toml::table& root) {
  auto ts = tables(root, "storey", "plan");
  if (ts.empty()) {  // the default: one storey, "ground"
    Storey s;
    s.name = "ground";
    s.where = SourceLoc{file_, 0, 0, "storey 'ground'"};
    storey_ids_[s.name] = 0;
    plan_.storeys.push_back(s);
    return;
  }
  std::unordered_set<std::string> seen;
  for (size_t i = 0; i < ts.size(); ++i) {
    auto given = Element(*this, *ts[i], element_name("storey", {}, static_cast<int>(i))).name_key();
    Element e(*this, *ts[i], element_name("storey", given, static_cast<int>(i)));
    e.allow({"name", "elevation", "height", "slab"});
    Storey s;
    s.name = given.value_or("storey " + std::to_string(i + 1));
    s.where = e.loc();
    unique(seen, s.name, e, "storey");
    if (auto h = e.length("height")) {
      if (*h <= 0) e.fail("height", "'height' (floor to ceiling) must be > 0, not " + len(*h));
      s.height = *h;
    }
    if (auto sl = e.length("slab")) {
      if (*sl < 0) e.fail("slab", "'slab' must be >= 0, not " + len(*sl));
      s.slab = *sl;
    }
    // Storeys stack without gaps: each floor is the slab above the one below.
    const double expected = i == 0 ? 0.0
                                   : plan_.storeys.back().elevation + plan_.storeys.back().height +
                                         plan_.storeys.back().slab;
    s.elevation = expected;
    if (auto el = e.length("elevation")) {
      if (i > 0 && std::fabs(*el - expected) > 1e-6 * std::max(1.0, std::fabs(expected)))
        e.fail("elevation", "'elevation' is " + len(*el) + " but storey '" + plan_.storeys.back().name +
                                "' below ends (elevation + height + slab) at " + len(expected) +
                                "; storeys are listed bottom-up and stack without gaps");
      s.elevation = i == 0 ? *el : expected;
    }
    storey_ids_[s.name] = static_cast<StoreyId>(plan_.storeys.size());
    plan_.storeys.push_back(std::move(s));
  }
}

// --- [[wall]] ----------------------------------------------------------------------

void Reader::read_walls(const toml::table& root) {
  auto ts = tables(root, "wall", "plan");
  for (size_t i = 0; i < ts.size(); ++i) read_wall(*ts[i], static_cast<int>(i));
  // Names are unique per storey (the same "north" may stand on every storey).
  std::vector<std::unordered_set<std::string>> seen(plan_.storeys.size());
  for (size_t i = 0; i < ts.size(); ++i) {
    const Wall& w = plan_.walls[i];
    unique(seen[w.storey], w.name, Element(*this, *ts[i], w.where.element), "wall");
  }
  if (plan_.walls.empty())
    throw PlanError(SourceLoc{file_, 1, 1, "plan"}, "the plan has no walls (add [[wall]] sections)");
}

void Reader::read_wall(const toml::table& t, int index) {
  auto given = Element(*this, t, element_name("wall", {}, index)).name_key();
  Element e(*this, t, element_name("wall", given, index));
  e.allow({"name", "storey", "thickness", "height", "height_at_end", "top_bends", "material", "right_material", "path",
           "footprint", "opening"});
  Wall w;
  w.name = given.value_or("wall " + std::to_string(index + 1));
  w.where = e.loc();
  w.storey = storey(e, true);
  const Storey& st = plan_.storeys[w.storey];
  if (auto th = e.length("thickness")) {
    if (*th < 0) e.fail("thickness", "'thickness' must be >= 0, not " + len(*th));
    w.thickness = *th;
  }
  const auto end_height = e.length("height_at_end");
  if (auto h = e.length("height")) {
    // A sloped wall may rise through the ceiling (a gable under the roof): cut there.
    if (end_height ? *h < 0 : *h <= 0)
      e.fail("height", std::string("'height' must be ") + (end_height ? ">= 0" : "> 0") + ", not " + len(*h));
    if (*h > st.height + kSlack && !end_height)
      e.fail("height", "'height' " + len(*h) + " is above the ceiling of storey '" + st.name + "' (" +
                           len(st.height) + "); leave it out for a wall up to the ceiling");
    w.height = *h;
  }
  if (end_height) {
    if (w.height < 0) e.fail("height_at_end", "'height_at_end' needs 'height', the wall's height at its start");
    if (*end_height < 0) e.fail("height_at_end", "'height_at_end' must be >= 0, not " + len(*end_height));
    if (w.height == 0 && *end_height == 0) e.fail("height_at_end", "a wall of height 0 at both ends is no wall");
    w.height_at_end = *end_height;
  }
  w.material = material(e, "material");
  w.right_material = material(e, "right_material");

  // The centre line: points, and arcs {through = [x, y], to = [x, y]}.
  const toml::node& pn = e.need("path");
  auto* path = pn.as_array();
  if (!path) e.fail("path", "'path' must be an array of points, not " + std::string(type_name(pn)));
  if (path->size() < 2) e.fail("path", "'path' needs at least 2 points");
  std::vector<PathPiece> pieces;
  std::vector<int> seg_entry;  // path entry index per tessellated segment
  double along = 0, tess_along = 0;
  for (size_t i = 0; i < path->size(); ++i) {
    const toml::node& n = *path->get(i);
    const std::string label = "point " + std::to_string(i + 1) + " of 'path'";
    const size_t before = w.centre.size();
    PathPiece piece;
    piece.from = along;
    piece.tess_from = tess_along;
    if (auto* arc = n.as_table()) {
      if (i == 0) e.fail_at(n, "'path' must start with a point [x, y], not an arc");
      Element ae(*this, *arc, e.name());
      ae.allow({"through", "to"});
      const Vec2 m = e.point2_of(ae.need("through"), "'through' of arc " + std::to_string(i + 1));
      const Vec2 b = e.point2_of(ae.need("to"), "'to' of arc " + std::to_string(i + 1));
      const Vec2 a = w.centre.back();
      const std::optional<Arc> arc_of = arc_through(a, m, b);
      if (!arc_of)
        e.fail_at(n, "the arc from (" + format_number(a.x / unit_) + ", " + format_number(a.y / unit_) + ") through (" +
                         format_number(m.x / unit_) + ", " + format_number(m.y / unit_) + ") to (" + format_number(b.x / unit_) + ", " +
                         format_number(b.y / unit_) + ") is degenerate: its 'through' point is collinear with (or " +
                         "equal to an end of) its chord; use a straight segment");
      const double arc_pieces = arc_of->pieces_for(plan_.arc_tolerance);
      if (arc_pieces > kMaxArcPieces)
        e.fail_at(n, "the arc would need more than " + std::to_string(kMaxArcPieces) +
                         " pieces for 'arc_tolerance' " + len(plan_.arc_tolerance));
      arc_of->append(static_cast<long>(arc_pieces), b, w.centre);
      piece.arc = true;
      piece.len = arc_of->length();
    } else {
      const Vec2 p = e.point2_of(n, label);
      if (i > 0 && p == w.centre.back())
        e.fail_at(n, label + " repeats the point before it (a segment of length 0)");
      piece.len = i > 0 ? length(p - w.centre.back()) : 0;
      w.centre.push_back(p);
    }
    if (i == 0) continue;
    for (size_t k = before; k < w.centre.size(); ++k) {
      w.from_arc.push_back(piece.arc);
      seg_entry.push_back(static_cast<int>(i));
      tess_along += length(w.centre[k] - w.centre[k - 1]);
    }
    along += piece.len;
    pieces.push_back(piece);
  }

  // A centre line may close on itself (a loop of walls) but not cross itself.
  const bool closed = w.centre.size() > 3 && w.centre.front() == w.centre.back();
  auto [s1, s2] = find_self_crossing(w.centre, closed);
  if (s1 >= 0) {
    // Where they meet: the crossing point, or for parallel segments a shared point.
    const Vec2 p1 = w.centre[s1], d1 = w.centre[s1 + 1] - p1;
    const Vec2 q1 = w.centre[s2], d2 = w.centre[s2 + 1] - q1;
    const double den = cross(d1, d2);
    const Vec2 p = den != 0 ? p1 + std::clamp(cross(q1 - p1, d2) / den, 0.0, 1.0) * d1 : q1;
    const std::string near = " (near (" + format_number(p.x / unit_) + ", " + format_number(p.y / unit_) + "))";
    if (s2 == s1 + 1 || (closed && s1 == 0 && s2 + 2 == static_cast<int>(w.centre.size())))
      e.fail_at(*path->get(seg_entry[s2]), "the centre line of " + e.name() +
                                               " crosses itself: it doubles back on itself at path entry " +
                                               std::to_string(seg_entry[s2] + 1) + near);
    e.fail_at(*path->get(seg_entry[s2]), "the centre line of " + e.name() + " crosses itself: path entries " +
                                             std::to_string(seg_entry[s1] + 1) + " and " +
                                             std::to_string(seg_entry[s2] + 1) + " meet" + near);
  }

  // A footprint of its own (a piece of a BIM model's curved or L-shaped wall): convex,
  // counter-clockwise, around a straight axis.
  if (t.contains("footprint")) {
    const toml::node& fn = e.need("footprint");
    auto* fp = fn.as_array();
    if (!fp || fp->size() < 3) e.fail("footprint", "'footprint' must be an array of at least 3 points");
    for (size_t i = 0; i < fp->size(); ++i)
      w.footprint.push_back(e.point2_of(*fp->get(i), "point " + std::to_string(i + 1) + " of 'footprint'"));
    if (w.centre.size() != 2) e.fail("footprint", "a wall with a 'footprint' has a 'path' of 2 points (its axis)");
    if (!is_convex_ccw(w.footprint)) e.fail("footprint", "'footprint' must be a convex polygon, counter-clockwise");
  }

  if (w.height_at_end >= 0 && w.thickness == 0)
    e.fail("height_at_end", "a wall of no thickness has no top to slope: give it a 'thickness' or leave out 'height_at_end'");

  // Where a sloped top bends (a gable's ridge): [along, height] pairs, in order along the
  // centre line, strictly inside it.
  if (t.contains("top_bends")) {
    if (w.height_at_end < 0) e.fail("top_bends", "'top_bends' needs 'height' and 'height_at_end', the top's ends");
    const toml::node& bn = e.need("top_bends");
    auto* bends = bn.as_array();
    if (!bends || bends->empty()) e.fail("top_bends", "'top_bends' must be an array of [along, height] pairs");
    const double total = w.length();
    double last = 0;
    for (size_t i = 0; i < bends->size(); ++i) {
      const std::string label = "bend " + std::to_string(i + 1) + " of 'top_bends'";
      const Vec2 b = e.point2_of(*bends->get(i), label);
      if (b.x <= last || b.x >= total)
        e.fail_at(*bends->get(i), label + " lies at " + len(b.x) + " along the wall: it must lie after " +
                                      (i == 0 ? "the start" : "the bend before it") + " (" + len(last) +
                                      ") and before the end (" + len(total) + ")");
      if (b.y < 0) e.fail_at(*bends->get(i), label + ": the height must be >= 0, not " + len(b.y));
      w.top_bends.push_back(b);
      last = b.x;
    }
  }

  plan_.walls.push_back(std::move(w));
  read_openings(e, plan_.walls.back(), pieces);
}

// --- [[wall.opening]] --------------------------------------------------------------

void Reader::read_openings(const Element& we, Wall& wall, const std::vector<PathPiece>& pieces) {
  auto ts = tables(we.table(), "opening", we.name());
  const Storey& st = plan_.storeys[wall.storey];
  const double wall_len = pieces.back().from + pieces.back().len;
  std::unordered_set<std::string> seen;
  std::vector<double> true_at;  // per opening, for the overlap check
  for (size_t i = 0; i < ts.size(); ++i) {
    auto given = Element(*this, *ts[i], element_name("opening", {}, static_cast<int>(i)) + " of " + we.name()).name_key();
    Element e(*this, *ts[i], element_name("opening", given, static_cast<int>(i)) + " of " + we.name());
    e.allow({"name", "kind", "at", "width", "sill", "head"});
    Opening o;
    o.name = given.value_or("opening " + std::to_string(i + 1));
    o.where = e.loc();
    unique(seen, o.name, e, "opening");
    // Kind, and the default heights a builder would use for it [m].
    double sill = 0, head = 2.1;
    const std::string kind = e.string("kind").value_or("door");
    if (kind == "door") o.kind = OpeningKind::Door, sill = 0, head = 2.1;
    else if (kind == "window") o.kind = OpeningKind::Window, sill = 0.9, head = 2.1;
    else if (kind == "hatch") o.kind = OpeningKind::Hatch, sill = 1.0, head = 1.5;
    else if (kind == "gap") o.kind = OpeningKind::Gap, sill = 0, head = 2.1;
    else e.fail("kind", "unknown opening kind '" + kind + "' (use door, window, hatch or gap)" +
                            did_you_mean(kind, std::initializer_list<std::string_view>{"door", "window", "hatch", "gap"}));

    const double at = e.length_of(e.need("at"), "'at'");
    o.width = e.length_of(e.need("width"), "'width'");
    if (o.width <= 0) e.fail("width", "'width' must be > 0, not " + len(o.width));
    if (at < 0) e.fail("at", "'at' must be >= 0 (a distance along the wall), not " + len(at));
    if (at >= wall_len - kSlack)
      e.fail("at", "'at' " + len(at) + " is past the end of " + we.name() + " (" + len(wall_len) + " long)");
    // The path piece the opening starts on: the last one starting at or before `at`.
    auto pit = std::upper_bound(pieces.begin(), pieces.end(), at + kSlack,
                                [](double x, const PathPiece& p) { return x < p.from; });
    const size_t k = static_cast<size_t>(pit - pieces.begin()) - 1;
    const PathPiece& p = pieces[k];
    const std::string span = " (it spans " + len(at) + " to " + len(at + o.width) + " along the wall";
    if (p.arc)
      e.fail("at", "opening lies on an arc of " + we.name() + span +
                       "); openings must lie on straight segments");
    if (o.width > p.len + kSlack)
      e.fail("width", "opening is " + len(o.width) + " wide but its wall segment is only " + len(p.len) +
                          " long");
    if (at + o.width > p.from + p.len + kSlack) {
      std::string where = k + 1 == pieces.size() ? "runs past the end of the wall"
                          : pieces[k + 1].arc    ? "runs onto an arc"
                                                 : "runs across a corner of the wall";
      e.fail("at", "opening " + where + span + "; its segment ends at " + len(p.from + p.len) + ")");
    }
    o.at = at - p.from + p.tess_from;  // onto the tessellated centre line

    o.sill = sill, o.head = head;
    if (auto s = e.length("sill")) o.sill = *s;
    if (auto h = e.length("head")) o.head = *h;
    if (o.sill < 0) e.fail("sill", "'sill' must be >= 0, not " + len(o.sill));
    if (o.sill >= o.head)
      e.fail(e.has("sill") ? "sill" : "head",
             "'sill' (" + len(o.sill) + ") must be below 'head' (" + len(o.head) + ")");
    if (o.head > st.height + kSlack)
      e.fail("head", "'head' " + len(o.head) + " is above the ceiling of storey '" + st.name + "' (" +
                         len(st.height) + ")");
    true_at.push_back(at);
    wall.openings.push_back(std::move(o));
  }

  // Openings of one wall must not overlap (touching is allowed).
  std::vector<size_t> order(wall.openings.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return true_at[a] < true_at[b]; });
  for (size_t i = 1; i < order.size(); ++i) {
    const size_t a = order[i - 1], b = order[i];
    if (true_at[a] + wall.openings[a].width > true_at[b] + kSlack) {
      const size_t later = std::max(a, b), earlier = std::min(a, b);  // report at the later one in the file
      Element e(*this, *ts[later], wall.openings[later].where.element);
      e.fail_here(e.name() + " overlaps " + wall.openings[earlier].where.element + " (" +
                  len(true_at[a]) + " to " + len(true_at[a] + wall.openings[a].width) + " and " +
                  len(true_at[b]) + " to " + len(true_at[b] + wall.openings[b].width) + " along the wall)");
    }
  }
}

// --- [[floor_opening]] -------------------------------------------------------------

void Reader::read_floor_openings(const toml::table& root) {
  auto ts = tables(root, "floor_opening", "plan");
  std::vector<std::unordered_set<std::string>> seen(plan_.storeys.size());
  for (size_t i = 0; i < ts.size(); ++i) {
    auto given = Element(*this, *ts[i], element_name("floor opening", {}, static_cast<int>(i))).name_key();
    Element e(*this, *ts[i], element_name("floor opening", given, static_cast<int>(i)));
    e.allow({"name", "storey", "outline"});
    FloorOpening f;
    f.name = given.value_or("floor opening " + std::to_string(i + 1));
    f.where = e.loc();
    f.storey = storey(e, true);
    unique(seen[f.storey], f.name, e, "floor opening");
    if (f.storey == 0)
      e.fail(e.has("storey") ? "storey" : "",
             "a floor opening joins its storey to the one below, but '" + plan_.storeys[0].name +
                 "' is the lowest storey");
    const toml::node& on = e.need("outline");
    auto* arr = on.as_array();
    if (!arr) e.fail("outline", "'outline' must be an array of points, not " + std::string(type_name(on)));
    for (size_t k = 0; k < arr->size(); ++k) {
      const Vec2 p = e.point2_of(*arr->get(k), "point " + std::to_string(k + 1) + " of 'outline'");
      if (!f.outline.empty() && p == f.outline.back())
        e.fail_at(*arr->get(k), "point " + std::to_string(k + 1) + " of 'outline' repeats the point before it");
      f.outline.push_back(p);
    }
    if (f.outline.size() > 1 && f.outline.front() == f.outline.back()) f.outline.pop_back();  // closing point
    if (f.outline.size() < 3) e.fail("outline", "'outline' needs at least 3 distinct points");
    // Simple polygon: closed, no edge meeting another except its two neighbours at
    // their shared corners, and some area.
    std::vector<Vec2> ring = f.outline;
    ring.push_back(ring.front());
    if (find_self_crossing(ring, true).first >= 0)
      e.fail("outline", "'outline' is not a simple polygon: its edges cross or touch");
    double area2 = 0;
    for (size_t k = 0; k + 1 < ring.size(); ++k) area2 += cross(ring[k], ring[k + 1]);
    if (std::fabs(area2) <= 1e-12) e.fail("outline", "'outline' encloses no area");
    if (area2 < 0) std::reverse(f.outline.begin(), f.outline.end());  // store counter-clockwise
    plan_.floor_openings.push_back(std::move(f));
  }
}

// --- [[room]] ----------------------------------------------------------------------

void Reader::read_rooms(const toml::table& root) {
  auto ts = tables(root, "room", "plan");
  std::vector<std::unordered_set<std::string>> seen(plan_.storeys.size());
  plan_.rooms.reserve(ts.size());
  for (size_t i = 0; i < ts.size(); ++i) {
    auto given = Element(*this, *ts[i], element_name("room", {}, static_cast<int>(i))).name_key();
    Element e(*this, *ts[i], element_name("room", given, static_cast<int>(i)));
    if (!given) e.fail_here("room " + std::to_string(i + 1) + " needs a 'name'");
    e.allow({"name", "storey", "at", "floor", "ceiling", "walls", "floor_at", "ceiling_at"});
    Room r;
    r.name = *given;
    r.where = e.loc();
    r.storey = storey(e, true);
    unique(seen[r.storey], r.name, e, "room");
    r.label = e.point2_of(e.need("at"), "'at'");
    const double h = plan_.storeys[size_t(r.storey)].height;
    if (auto v = e.length("floor_at")) {
      if (!(*v >= 0 && *v < h)) e.fail("floor_at", "'floor_at' must lie from 0 to below the storey's height");
      r.floor_at = *v;
    }
    if (auto v = e.length("ceiling_at")) {
      if (!(*v > r.floor_at && *v <= h))
        e.fail("ceiling_at", "'ceiling_at' must lie above 'floor_at' and at most at the storey's height");
      r.ceiling_at = *v;
    }
    r.floor = material(e, "floor");
    r.ceiling = material(e, "ceiling");
    r.walls = material(e, "walls");
    plan_.rooms.push_back(std::move(r));
  }
}

// --- [[object]] --------------------------------------------------------------------

void Reader::read_objects(const toml::table& root) {
  auto ts = tables(root, "object", "plan");
  const std::filesystem::path dir = std::filesystem::path(file_).parent_path();
  std::vector<std::unordered_set<std::string>> seen(plan_.storeys.size());
  for (size_t i = 0; i < ts.size(); ++i) {
    auto given = Element(*this, *ts[i], element_name("object", {}, static_cast<int>(i))).name_key();
    Element e(*this, *ts[i], element_name("object", given, static_cast<int>(i)));
    e.allow({"name", "mesh", "storey", "position", "rotation", "scale", "material", "up", "unit"});
    Object o;
    o.name = given.value_or("object " + std::to_string(i + 1));
    o.where = e.loc();
    o.storey = storey(e, true);
    unique(seen[o.storey], o.name, e, "object");
    const std::string mesh = e.string_of(e.need("mesh"), "'mesh'");
    if (mesh.empty()) e.fail("mesh", "'mesh' must not be empty");
    const std::filesystem::path mp(mesh);
    o.mesh = (mp.is_absolute() ? mp : (dir / mp).lexically_normal()).string();
    if (auto* p = e.get("position")) o.position = e.point3_of(*p, "'position'");
    if (auto* r = e.get("rotation")) {
      if (r->is_array()) {
        auto* a = r->as_array();
        if (a->size() != 3) e.fail("rotation", "'rotation' must be a number (about z) or [x, y, z] degrees");
        o.rotation_deg = {e.number_of(*a->get(0), "'rotation'"), e.number_of(*a->get(1), "'rotation'"),
                          e.number_of(*a->get(2), "'rotation'")};
      } else {
        o.rotation_deg = {0, 0, e.number_of(*r, "'rotation'")};
      }
    }
    if (auto* s = e.get("scale")) {
      if (s->is_array()) {
        auto* a = s->as_array();
        if (a->size() != 3) e.fail("scale", "'scale' must be a number or [sx, sy, sz]");
        o.scale = {e.number_of(*a->get(0), "'scale'"), e.number_of(*a->get(1), "'scale'"),
                   e.number_of(*a->get(2), "'scale'")};
      } else {
        const double k = e.number_of(*s, "'scale'");
        o.scale = {k, k, k};
      }
      if (!(o.scale.x > 0 && o.scale.y > 0 && o.scale.z > 0) || o.scale.x > kAbsurdLength ||
          o.scale.y > kAbsurdLength || o.scale.z > kAbsurdLength)
        e.fail("scale", "'scale' factors must be > 0 (and not absurd)");
    }
    // The mesh file's axes where its format says none (OBJ, PLY, STL, OFF): plans/mesh.h.
    if (auto* u = e.get("up")) {
      o.axes.up = up_axis_named(e.string_of(*u, "'up'"));
      if (!o.axes.up) e.fail("up", "'up' must be \"x\", \"y\" or \"z\" (the mesh file's up axis)");
    }
    if (auto* u = e.get("unit")) {
      o.axes.metres_per_unit = metres_per_unit_named(e.string_of(*u, "'unit'"));
      if (!o.axes.metres_per_unit) e.fail("unit", "'unit' must be \"m\", \"cm\", \"mm\", \"in\" or \"ft\"");
    }
    o.material = material(e, "material");
    plan_.objects.push_back(std::move(o));
  }
}

// --- [[light]] ---------------------------------------------------------------------

void Reader::read_lights(const toml::table& root) {
  auto ts = tables(root, "light", "plan");
  std::unordered_set<std::string> seen;
  for (size_t i = 0; i < ts.size(); ++i) {
    auto given = Element(*this, *ts[i], element_name("light", {}, static_cast<int>(i))).name_key();
    Element e(*this, *ts[i], element_name("light", given, static_cast<int>(i)));
    e.allow({"name", "kind", "position", "intensity", "colour"});
    Light l;
    l.name = given.value_or("light " + std::to_string(i + 1));
    l.where = e.loc();
    unique(seen, l.name, e, "light");
    const std::string kind = e.string("kind").value_or("point");
    if (kind == "point") l.kind = LightKind::Point;
    else if (kind == "ambient") l.kind = LightKind::Ambient;
    else e.fail("kind", "unknown light kind '" + kind + "' (use point or ambient)" +
                            did_you_mean(kind, std::initializer_list<std::string_view>{"point", "ambient"}));
    if (l.kind == LightKind::Point) {
      l.position = e.point3_of(e.need("position"), "'position'");
    } else if (e.has("position")) {
      e.fail("position", "an ambient light has no 'position': it lights every surface evenly");
    }
    if (l.kind == LightKind::Ambient) l.intensity = 0.1;  // Bouknight's BACK, unless given
    if (auto k = e.number("intensity")) {
      if (*k <= 0) e.fail("intensity", "'intensity' must be > 0, not " + format_number(*k));
      if (l.kind == LightKind::Ambient && *k > 1)
        e.fail("intensity", "an ambient light's 'intensity' is a share of full light, at most 1, not " + format_number(*k));
      l.intensity = *k;
    }
    if (auto* c = e.get("colour")) l.colour = e.colour_of(*c, "'colour'");
    plan_.lights.push_back(std::move(l));
  }
}

// --- [view] ------------------------------------------------------------------------

void Reader::read_view(const toml::table& root) {
  auto it = root.find("view");
  if (it == root.end()) return;
  auto* t = it->second.as_table();
  if (!t) fail(it->first.source(), "view", "'view' must be a table ([view]), not " +
                                               std::string(type_name(it->second)));
  Element e(*this, *t, "view");
  e.allow({"eye", "look", "fov"});
  Viewpoint v;
  v.eye = e.point3_of(e.need("eye"), "'eye'");
  v.look = e.point3_of(e.need("look"), "'look'");
  if (v.eye == v.look) e.fail("look", "'look' must differ from 'eye'");
  if (auto f = e.number("fov")) {
    if (!(*f > 0 && *f <= 179)) e.fail("fov", "'fov' must be in (0, 179] degrees, not " + format_number(*f));
    v.fov_deg = *f;
  }
  plan_.view = v;
}

Plan Reader::read(const toml::table& root) {
  plan_.source = file_;
  read_settings(root);  // first: `units` governs every length after it
  read_materials(root);
  read_storeys(root);
  read_walls(root);
  read_floor_openings(root);
  read_rooms(root);
  read_objects(root);
  read_lights(root);
  read_view(root);
  return std::move(plan_);
}

}  // namespace

Plan parse_plan(const std::string& text, const std::string& name) {
  toml::table root;
  // toml++ reports syntax errors by exception or, built without exceptions, in its
  // parse_result; either way they carry a source position.
#if TOML_EXCEPTIONS
  try {
    root = toml::parse(text, std::string_view(name));
  } catch (const toml::parse_error& err) {
    throw PlanError(SourceLoc{name, static_cast<int>(err.source().begin.line),
                              static_cast<int>(err.source().begin.column), ""},
                    "TOML syntax error: " + std::string(err.description()));
  }
#else
  toml::parse_result result = toml::parse(text, std::string_view(name));
  if (!result) {
    const toml::parse_error& err = result.error();
    throw PlanError(SourceLoc{name, static_cast<int>(err.source().begin.line),
                              static_cast<int>(err.source().begin.column), ""},
                    "TOML syntax error: " + std::string(err.description()));
  }
  root = std::move(result).table();
#endif
  return Reader(name).read(root);
}

bool parses_as_toml(const std::string& text) {
#if TOML_EXCEPTIONS
  try {
    (void)toml::parse(text);
    return true;
  } catch (const toml::parse_error&) {
    return false;
  }
#else
  return bool(toml::parse(text));
#endif
}

Plan read_plan(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw PlanError(SourceLoc{path, 0, 0, ""}, "cannot read plan: it is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PlanError(SourceLoc{path, 0, 0, ""}, std::string("cannot open plan: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw PlanError(SourceLoc{path, 0, 0, ""}, "cannot read plan");
  return parse_plan(text.str(), path);
}

}  // namespace avenues
