// Avenues — the serialized Java `Home` entry of a .sh3d as a home tree (see home_tree.h).
//
// java_stream.h reads the bytes into Java objects; this maps Sweet Home 3D's classes
// (com.eteks.sweethome3d.model: Home, Level, Wall, Room, HomePieceOfFurniture,
// HomeDoorOrWindow, HomeLight, HomeFurnitureGroup, ObserverCamera, HomeMaterial,
// HomeTexture, LightSource; their fields as the classes name them) onto the elements and
// attributes HomeXMLExporter writes for the same objects, so Home and Home.xml give one
// tree. As HomeXMLExporter does, levels and walls are named "level<i>" and "wall<i>" by
// their order in the home, and a model is named by its entry in the .sh3d: a content
// saved with the home is a URLContent whose URL is "jar:file:temp!/<entry>"
// (DefaultHomeOutputStream; DefaultHomeInputStream resolves it the same way).
//
// The furniture is Home.furnitureWithGroups (groups kept, version 2.3 on), else
// furnitureWithDoorsAndWindows (1.7 on), else furniture, as Home.readObject picks it.
// Groups are walked with an explicit stack, each group once (a stream may refer to a
// group from inside itself).
#include "plans/formats/home_tree.h"
#include "plans/formats/java_stream.h"
#include "plans/plan.h"

#include <charconv>
#include <cstdio>
#include <unordered_map>
#include <unordered_set>

namespace avenues {
namespace {

using java::Object;
using java::Stream;
using java::Value;

constexpr std::string_view kModel = "com.eteks.sweethome3d.model.";

class Mapper {
 public:
  Mapper(const Stream& s, HomeTree& t) : s_(s), t_(t) {}

  void map(const Object& home) {
    const size_t root = t_.add(0, "home");
    t_.elements[root].offset = home.offset;
    text(root, "name", home, "name");
    number(root, "wallHeight", home, "wallHeight");
    // Ids first: walls name each other and their levels.
    const std::vector<Value> levels = list(home, "levels"), walls = list(home, "walls");
    // A home saved since Sweet Home 3D 6.4 gives each object its id (HomeObject's `id`), as
    // its Home.xml does: walls are named by it either way. Older homes have none, nor a
    // Home.xml: their walls are numbered, as Sweet Home numbers them in Home.xml.
    std::unordered_set<std::string> taken;
    auto name = [&](const Value& v, const char* kind, size_t i) {
      const Object* o = s_.object(v);
      std::string id = o ? s_.string_field(*o, "id") : std::string();
      if (id.empty() || !taken.insert(id).second) id = kind + std::to_string(i);
      ids_.emplace(v.object, id);
    };
    for (size_t i = 0; i < levels.size(); ++i)
      if (levels[i].is_object()) name(levels[i], "level", i);
    for (size_t i = 0; i < walls.size(); ++i)
      if (walls[i].is_object()) name(walls[i], "wall", i);
    for (const Value& v : levels)
      if (const Object* o = instance_of(v, "Level")) level(root, *o);
    for (const Value& v : walls)
      if (const Object* o = instance_of(v, "Wall")) wall(root, *o);
    for (const Value& v : list(home, "rooms"))
      if (const Object* o = instance_of(v, "Room")) room(root, *o);
    furniture(root, home);
    if (const Value* cam = s_.field(home, "observerCamera"))
      if (const Object* o = instance_of(*cam, "ObserverCamera")) camera(root, *o);
  }

 private:
  /// v as an instance of Sweet Home's model class `cls` (or a subclass), else nullptr.
  const Object* instance_of(const Value& v, std::string_view cls) const {
    const Object* o = s_.object(v);
    return o && s_.is_a(*o, std::string(kModel) + std::string(cls)) ? o : nullptr;
  }
  /// The elements of a collection field: an ArrayList's (or any list's or set's)
  /// annotation objects, an array's elements; an unmodifiable or synchronized wrapper
  /// (its field "list" or "c") is looked through.
  std::vector<Value> list(const Object& owner, std::string_view field) const {
    const Value* v = s_.field(owner, field);
    const Object* o = v ? s_.object(*v) : nullptr;
    for (int hops = 0; o && hops < 4; ++hops) {
      if (o->kind == Object::Kind::Array) return o->values;
      if (o->kind != Object::Kind::Instance) return {};
      if (!o->annotations.empty()) return s_.annotation_objects(*o);
      const Value* inner = s_.field(*o, "list");
      if (!inner) inner = s_.field(*o, "c");
      if (!inner) inner = s_.field(*o, "a");  // Arrays.asList's java.util.Arrays$ArrayList: its array
      if (!inner && s_.is_a(*o, "java.util.Collections$SingletonList"))
        if (const Value* one = s_.field(*o, "element")) return {*one};
      o = inner ? s_.object(*inner) : nullptr;
    }
    return {};
  }
  static std::string decimal(const Value& v) {
    char buf[64];
    std::to_chars_result r{};
    if (v.kind == Value::Kind::Float) r = std::to_chars(buf, buf + sizeof buf, float(v.real));
    else if (v.kind == Value::Kind::Double) r = std::to_chars(buf, buf + sizeof buf, v.real);
    else r = std::to_chars(buf, buf + sizeof buf, v.integer);
    return std::string(buf, r.ptr);
  }
  void number(size_t e, const char* attr, const Object& o, std::string_view field) {
    const Value v = s_.unboxed(s_.field(o, field));
    if (v.is_number()) t_.elements[e].set(attr, decimal(v));
  }
  void colour(size_t e, const char* attr, const Object& o, std::string_view field) {
    const Value v = s_.unboxed(s_.field(o, field));
    if (!v.is_number()) return;
    char buf[16];
    std::snprintf(buf, sizeof buf, "%08X", unsigned(uint32_t(v.integer)));
    t_.elements[e].set(attr, buf);
  }
  void text(size_t e, const char* attr, const Object& o, std::string_view field) {
    const Value* v = s_.field(o, field);
    const Object* str = v ? s_.object(*v) : nullptr;
    if (str && str->kind == Object::Kind::String) t_.elements[e].set(attr, str->text);
  }
  void flag(size_t e, const char* attr, const Object& o, std::string_view field, bool written_when) {
    const Value* v = s_.field(o, field);
    if (v && v->kind == Value::Kind::Boolean && (v->integer != 0) == written_when)
      t_.elements[e].set(attr, written_when ? "true" : "false");
  }
  void reference(size_t e, const char* attr, const Object& o, std::string_view field) {
    const Value* v = s_.field(o, field);
    if (!v || !v->is_object()) return;
    if (auto it = ids_.find(v->object); it != ids_.end()) t_.elements[e].set(attr, it->second);
  }
  /// A HomeTexture field as Home.xml's <texture attribute="field" name image/> child (a
  /// piece's own texture has no attribute there).
  void texture(size_t e, const Object& o, std::string_view field, bool named = true) {
    const Value* v = s_.field(o, field);
    if (!v || !instance_of(*v, "HomeTexture")) return;
    const Object& tex = *s_.object(*v);
    const std::string image = content_entry(tex, "image");
    if (image.empty()) return;
    const size_t t = element(e, "texture", tex);
    if (named) t_.elements[t].set("attribute", std::string(field));
    text(t, "name", tex, "name");
    t_.elements[t].set("image", image);
  }
  size_t element(size_t parent, std::string kind, const Object& o) {
    const size_t e = t_.add(parent, std::move(kind));
    t_.elements[e].offset = o.offset;
    return e;
  }

  /// An element with the id given to its object ("level0", "wall3": what others refer to it by).
  size_t identified_element(size_t parent, std::string kind, const Object& o) {
    const size_t e = element(parent, std::move(kind), o);
    t_.elements[e].set("id", ids_.at(uint32_t(&o - s_.objects.data())));
    return e;
  }

  void level(size_t root, const Object& o) {
    const size_t e = identified_element(root, "level", o);
    text(e, "name", o, "name");
    number(e, "elevation", o, "elevation");
    number(e, "floorThickness", o, "floorThickness");
    number(e, "height", o, "height");
    number(e, "elevationIndex", o, "elevationIndex");
    flag(e, "viewable", o, "viewable", false);
  }

  void wall(size_t root, const Object& o) {
    const size_t e = identified_element(root, "wall", o);
    reference(e, "level", o, "level");
    reference(e, "wallAtStart", o, "wallAtStart");
    reference(e, "wallAtEnd", o, "wallAtEnd");
    for (const char* f : {"xStart", "yStart", "xEnd", "yEnd", "height", "heightAtEnd", "thickness", "arcExtent"})
      number(e, f, o, f);
    colour(e, "leftSideColor", o, "leftSideColor");
    colour(e, "rightSideColor", o, "rightSideColor");
    texture(e, o, "leftSideTexture");
    texture(e, o, "rightSideTexture");
  }

  void room(size_t root, const Object& o) {
    const size_t e = element(root, "room", o);
    reference(e, "level", o, "level");
    text(e, "name", o, "name");
    colour(e, "floorColor", o, "floorColor");
    colour(e, "ceilingColor", o, "ceilingColor");
    texture(e, o, "floorTexture");
    texture(e, o, "ceilingTexture");
    for (const Value& p : list(o, "points")) {
      const Object* xy = s_.object(p);
      if (!xy || xy->kind != Object::Kind::Array || xy->values.size() < 2) continue;
      const size_t pt = element(e, "point", *xy);
      t_.elements[pt].set("x", decimal(xy->values[0]));
      t_.elements[pt].set("y", decimal(xy->values[1]));
    }
  }

  /// The entry of the .sh3d a content names ("jar:file:temp!/<entry>"), or its URL as it
  /// is when it is not saved with the home.
  std::string content_entry(const Object& piece, std::string_view field) const {
    const Value* v = s_.field(piece, field);
    const Object* content = v ? s_.object(*v) : nullptr;
    if (!content || content->kind != Object::Kind::Instance) return {};
    const Value* u = s_.field(*content, "url");
    const Object* url = u ? s_.object(*u) : nullptr;
    if (!url || url->kind != Object::Kind::Instance) return {};
    const std::string protocol = s_.string_field(*url, "protocol"), file = s_.string_field(*url, "file");
    const std::string authority = s_.string_field(*url, "authority");
    const std::string whole = protocol + ":" + (authority.empty() ? "" : "//" + authority) + file;
    if (protocol == "jar") {
      const size_t bang = whole.find("!/");
      if (bang != std::string::npos) return whole.substr(bang + 2);
    }
    return whole;
  }

  void furniture(size_t root, const Object& home) {
    std::vector<Value> top = list(home, "furnitureWithGroups");
    if (top.empty()) top = list(home, "furnitureWithDoorsAndWindows");
    if (top.empty()) top = list(home, "furniture");
    struct Pending {
      size_t parent;
      Value piece;
    };
    std::vector<Pending> stack;
    for (auto it = top.rbegin(); it != top.rend(); ++it) stack.push_back({root, *it});
    std::unordered_set<uint32_t> groups_seen;
    while (!stack.empty()) {
      const Pending p = stack.back();
      stack.pop_back();
      const Object* o = instance_of(p.piece, "HomePieceOfFurniture");
      if (!o) continue;
      const char* kind = instance_of(p.piece, "HomeFurnitureGroup") ? "furnitureGroup"
                         : instance_of(p.piece, "HomeDoorOrWindow") ? "doorOrWindow"
                         : instance_of(p.piece, "HomeLight")        ? "light"
                                                                    : "pieceOfFurniture";
      const size_t e = element(p.parent, kind, *o);
      reference(e, "level", *o, "level");
      text(e, "name", *o, "name");
      for (const char* f : {"x", "y", "elevation", "angle", "width", "depth", "height", "power"}) number(e, f, *o, f);
      flag(e, "visible", *o, "visible", false);
      flag(e, "modelMirrored", *o, "modelMirrored", true);
      flag(e, "wallCutOutOnBothSides", *o, "wallCutOutOnBothSides", true);
      text(e, "staircaseCutOutShape", *o, "staircaseCutOutShape");
      text(e, "cutOutShape", *o, "cutOutShape");  // HomeDoorOrWindow's (4.2)
      colour(e, "color", *o, "color");
      texture(e, *o, "texture", false);
      // modelMaterials, a HomeMaterial[]: <material name key color> children, a texture inside.
      for (const Value& mv : list(*o, "modelMaterials"))
        if (const Object* mat = instance_of(mv, "HomeMaterial")) {
          const size_t me = element(e, "material", *mat);
          text(me, "name", *mat, "name");
          text(me, "key", *mat, "key");
          colour(me, "color", *mat, "color");
          texture(me, *mat, "texture", false);
        }
      if (const std::string model = content_entry(*o, "model"); !model.empty()) t_.elements[e].set("model", model);
      const std::vector<Value> rows = list(*o, "modelRotation");
      std::string rotation;
      for (const Value& r : rows)
        if (const Object* row = s_.object(r); row && row->kind == Object::Kind::Array)
          for (const Value& x : row->values) {
            if (!rotation.empty()) rotation += ' ';
            rotation += decimal(x);
          }
      if (rows.size() == 3) t_.elements[e].set("modelRotation", rotation);
      for (const Value& l : list(*o, "lightSources")) {
        const Object* src = s_.object(l);
        if (!src || !s_.is_a(*src, std::string(kModel) + "LightSource")) continue;
        const size_t ls = element(e, "lightSource", *src);
        for (const char* f : {"x", "y", "z", "diameter"}) number(ls, f, *src, f);
        colour(ls, "color", *src, "color");
      }
      if (std::string_view(kind) == "furnitureGroup" && groups_seen.insert(p.piece.object).second) {
        const std::vector<Value> inner = list(*o, "furniture");
        for (auto it = inner.rbegin(); it != inner.rend(); ++it) stack.push_back({e, *it});
      }
    }
  }

  void camera(size_t root, const Object& o) {
    const size_t e = element(root, "observerCamera", o);
    t_.elements[e].set("attribute", "observerCamera");
    for (const char* f : {"x", "y", "z", "yaw", "pitch", "fieldOfView"}) number(e, f, o, f);
  }

  const Stream& s_;
  HomeTree& t_;
  std::unordered_map<uint32_t, std::string> ids_;  ///< level and wall objects → "level<i>", "wall<i>"
};

}  // namespace

HomeTree home_tree_of_serialized(std::string_view bytes, const std::string& file) {
  HomeTree t;
  t.file = file;
  t.serialized = true;
  java::Stream s;
  try {
    s = java::Stream::parse(bytes);
  } catch (const java::JavaStreamError& e) {
    throw PlanError(SourceLoc{file, 0, 0, ""}, std::string("not a readable serialized Java home: ") + e.what());
  }
  for (const java::Value& v : s.contents)
    if (const java::Object* o = s.object(v); o && s.is_a(*o, std::string(kModel) + "Home")) {
      Mapper(s, t).map(*o);
      return t;
    }
  const java::Object* first = s.contents.empty() ? nullptr : s.object(s.contents.front());
  throw PlanError(SourceLoc{file, 0, 0, ""},
                  "the serialized entry holds no Sweet Home 3D home (com.eteks.sweethome3d.model.Home)" +
                      (first && !s.class_name(*first).empty() ? ", but a " + s.class_name(*first) : std::string()));
}

}  // namespace avenues
