// Avenues — writing a Plan as TOML (see plan_writer.h), with toml++'s own formatter.
#include "plans/plan_writer.h"

#include <cctype>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

#include <toml++/toml.h>

#include "core/atomic_file.h"
#include "plans/mesh.h"
#include "plans/obj_writer.h"

namespace avenues {
namespace {

toml::array point(Vec2 p) { return toml::array{p.x, p.y}; }
toml::array point(Vec3 p) { return toml::array{p.x, p.y, p.z}; }
toml::array rgb(const std::array<double, 3>& c) { return toml::array{c[0], c[1], c[2]}; }

}  // namespace

std::string plan_as_toml(const Plan& plan, const std::vector<std::string>& model_files) {
  std::vector<std::string> left_out;
  toml::table root;
  root.insert("name", plan.name);
  root.insert("units", "m");
  root.insert("arc_tolerance", plan.arc_tolerance);
  root.insert("far_margin", plan.far_margin);
  auto material = [&](MaterialId m) { return plan.materials[size_t(m)].name; };
  if (plan.ground >= 0) root.insert("ground", material(plan.ground));
  if (plan.sky >= 0) root.insert("sky", material(plan.sky));
  if (plan.roof >= 0) root.insert("roof", material(plan.roof));
  if (plan.view) {
    toml::table v;
    v.insert("eye", point(plan.view->eye));
    v.insert("look", point(plan.view->look));
    v.insert("fov", plan.view->fov_deg);
    root.insert("view", std::move(v));
  }
  if (!plan.materials.empty()) {
    toml::table ms;
    for (const Material& m : plan.materials) {
      toml::table t;
      t.insert("reflectance", m.reflectance);
      t.insert("colour", rgb(m.colour));
      ms.insert(m.name, std::move(t));
    }
    root.insert("materials", std::move(ms));
  }
  auto storey = [&](StoreyId s) { return plan.storeys[size_t(s)].name; };
  toml::array storeys;
  for (size_t i = 0; i < plan.storeys.size(); ++i) {
    const Storey& s = plan.storeys[i];
    toml::table t;
    t.insert("name", s.name);
    if (i == 0) t.insert("elevation", s.elevation);
    t.insert("height", s.height);
    t.insert("slab", s.slab);
    storeys.push_back(std::move(t));
  }
  root.insert("storey", std::move(storeys));

  toml::array walls;
  int sided = 0;
  for (const Wall& w : plan.walls) {
    toml::table t;
    t.insert("name", w.name);
    t.insert("storey", storey(w.storey));
    t.insert("thickness", w.thickness);
    if (w.height >= 0) t.insert("height", w.height);
    if (w.height >= 0 && w.height_at_end >= 0) t.insert("height_at_end", w.height_at_end);
    if (w.height >= 0 && w.height_at_end >= 0 && !w.top_bends.empty()) {
      toml::array bends;
      for (Vec2 b : w.top_bends) bends.push_back(point(b));
      t.insert("top_bends", std::move(bends));
    }
    if (w.material >= 0) t.insert("material", material(w.material));
    if (w.right_material >= 0) t.insert("right_material", material(w.right_material));
    toml::array path;
    for (Vec2 p : w.centre) path.push_back(point(p));
    t.insert("path", std::move(path));
    if (!w.footprint.empty()) {
      toml::array footprint;
      for (Vec2 p : w.footprint) footprint.push_back(point(p));
      t.insert("footprint", std::move(footprint));
    }
    if (!w.openings.empty()) {
      toml::array os;
      std::set<std::string> opening_names;  // unique per wall in the format: two of one name get a number
      for (const Opening& o : w.openings) {
        std::string name = o.name;
        for (int k = 2; !opening_names.insert(name).second; ++k) name = o.name + " " + std::to_string(k);
        toml::table ot;
        ot.insert("name", name);
        ot.insert("kind", to_string(o.kind));
        ot.insert("at", o.at);
        ot.insert("width", o.width);
        ot.insert("sill", o.sill);
        ot.insert("head", o.head);
        os.push_back(std::move(ot));
      }
      if (!os.empty()) t.insert("opening", std::move(os));
    }
    sided += w.left_room >= 0 || w.right_room >= 0;
    walls.push_back(std::move(t));
  }
  if (sided > 0) left_out.push_back(std::to_string(sided) + " walls' left and right rooms");
  if (!walls.empty()) root.insert("wall", std::move(walls));

  toml::array fos;
  for (const FloorOpening& f : plan.floor_openings) {
    toml::table t;
    t.insert("name", f.name);
    t.insert("storey", storey(f.storey));
    toml::array outline;
    for (Vec2 p : f.outline) outline.push_back(point(p));
    t.insert("outline", std::move(outline));
    fos.push_back(std::move(t));
  }
  if (!fos.empty()) root.insert("floor_opening", std::move(fos));

  toml::array rooms;
  for (const Room& r : plan.rooms) {
    if (!r.label) {
      left_out.push_back("room '" + r.name + "' (no label point)");
      continue;
    }
    toml::table t;
    t.insert("name", r.name);
    t.insert("storey", storey(r.storey));
    t.insert("at", point(*r.label));
    if (r.floor_at != 0) t.insert("floor_at", r.floor_at);
    if (r.ceiling_at >= 0) t.insert("ceiling_at", r.ceiling_at);
    if (r.floor >= 0) t.insert("floor", material(r.floor));
    if (r.ceiling >= 0) t.insert("ceiling", material(r.ceiling));
    if (r.walls >= 0) t.insert("walls", material(r.walls));
    if (r.sky) left_out.push_back("room '" + r.name + "' is open to the sky");
    rooms.push_back(std::move(t));
  }
  if (!rooms.empty()) root.insert("room", std::move(rooms));

  toml::array objects;
  int boxes = 0;
  // Names are unique per storey in the format; two pieces of one name get a number.
  std::vector<std::set<std::string>> names(plan.storeys.size());
  for (size_t i = 0; i < plan.objects.size(); ++i) {
    const Object& o = plan.objects[i];
    const std::string* model_file = i < model_files.size() && !model_files[i].empty() ? &model_files[i] : nullptr;
    if ((o.model || o.mesh.empty()) && !model_file) {
      ++boxes;
      continue;
    }
    toml::table t;
    std::string name = o.name;
    if (o.storey >= 0 && size_t(o.storey) < names.size())
      for (int k = 2; !names[size_t(o.storey)].insert(name).second; ++k) name = o.name + " " + std::to_string(k);
    t.insert("name", name);
    t.insert("mesh", model_file ? *model_file : o.mesh);
    t.insert("storey", storey(o.storey));
    // A file's axes; a model or box is written in z-up metres.
    if (!model_file && o.axes.up) t.insert("up", std::string(1, *o.axes.up));
    if (!model_file && o.axes.metres_per_unit) {
      for (const char* unit : {"m", "cm", "mm", "in", "ft"})
        if (metres_per_unit_named(unit) == o.axes.metres_per_unit) t.insert("unit", unit);
      if (!t.contains("unit")) left_out.push_back("object '" + o.name + "''s unit " + std::to_string(*o.axes.metres_per_unit) + " m");
    }
    t.insert("position", point(o.position));
    t.insert("rotation", point(o.rotation_deg));
    t.insert("scale", point(o.scale));
    if (o.material >= 0) t.insert("material", material(o.material));
    objects.push_back(std::move(t));
  }
  if (boxes > 0) left_out.push_back(std::to_string(boxes) + " objects that are boxes or came inside the file");
  if (!objects.empty()) root.insert("object", std::move(objects));

  toml::array lights;
  for (const Light& l : plan.lights) {
    toml::table t;
    t.insert("name", l.name);
    if (l.kind == LightKind::Ambient) t.insert("kind", "ambient");
    else t.insert("position", point(l.position));
    t.insert("intensity", l.intensity);
    t.insert("colour", rgb(l.colour));
    lights.push_back(std::move(t));
  }
  if (!lights.empty()) root.insert("light", std::move(lights));
  // The importer's leniency travels with the plan, so that it reads back as it was read.
  if (plan.lenient) root.insert("lenient", true);
  if (plan.unnamed_spaces_solid && !plan.outside_solid) root.insert("unnamed_spaces_solid", true);
  if (plan.outside_solid) left_out.push_back("a solid outside");

  std::ostringstream out;
  out << "# " << plan.name << ", as Avenues understood it" << (plan.source.empty() ? "" : " from " + plan.source)
      << " (docs/PLAN_FORMAT.md).\n";
  for (const std::string& w : plan.warnings) out << "# warning: " << w << "\n";
  for (const std::string& l : left_out) out << "# not expressible here, left out: " << l << "\n";
  out << "\n" << root << "\n";
  return out.str();
}

namespace {

/// A file name from an object's name: letters, digits, '-' and '_' kept (lower case), every
/// other run of characters one '-', at most 48 of them; "object" when none is left.
std::string file_stem_of(const std::string& name) {
  std::string out;
  for (char ch : name) {
    const auto c = static_cast<unsigned char>(ch);
    if (std::isalnum(c) || c == '_' || c == '-') out += char(std::tolower(c));
    else if (!out.empty() && out.back() != '-') out += '-';
    if (out.size() >= 48) break;
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out.empty() ? "object" : out;
}

}  // namespace

void write_plan(const Plan& plan, const std::string& path) {
  namespace fs = std::filesystem;
  check_output_path(path);
  // The objects that carry their own mesh (a model that came inside the file, or a box):
  // each mesh once, as an OBJ and its MTL in FILE.models/ beside the plan, named from the
  // first object that uses it.
  const fs::path target(path);
  const std::string folder = target.stem().string() + ".models";
  std::vector<std::string> model_files(plan.objects.size());
  std::vector<std::pair<std::string, std::string>> files;  // name in the folder, bytes
  std::map<std::string, std::string> file_of_key;          // mesh_key -> its OBJ's name
  std::set<std::string> stems;
  for (size_t i = 0; i < plan.objects.size(); ++i) {
    const Object& o = plan.objects[i];
    if (!o.model && !o.mesh.empty()) continue;
    if (!o.model && !(o.box.x > 0 && o.box.y > 0 && o.box.z > 0)) continue;  // nothing to draw
    auto [it, fresh] = file_of_key.try_emplace(mesh_key(o));
    if (fresh) {
      std::string stem = file_stem_of(o.name);
      for (int k = 2; !stems.insert(stem).second; ++k) stem = file_stem_of(o.name) + "-" + std::to_string(k);
      const Mesh mesh = o.model ? *o.model : box_mesh(o.box);
      it->second = stem + ".obj";
      files.push_back({stem + ".obj", obj_of_mesh(mesh, stem + ".mtl")});
      if (std::string mtl = mtl_of_mesh(mesh); !mtl.empty()) files.push_back({stem + ".mtl", std::move(mtl)});
    }
    model_files[i] = folder + "/" + it->second;
  }
  const std::string toml = plan_as_toml(plan, model_files);
  if (files.empty()) {
    write_file_atomically(path, toml);
    return;
  }
  // All or nothing: the models are written into a temporary folder beside the plan, which
  // takes the folder's name only once every file is in it, just before the plan itself is
  // renamed into place; a failure on the way leaves what was there before.
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string tag = std::to_string(::getpid());
  const fs::path models = dir / folder, staged = dir / ("." + folder + ".tmp-" + tag),
                 previous = dir / ("." + folder + ".old-" + tag);
  std::error_code ec;
  if (fs::exists(models, ec) && !fs::is_directory(models, ec))
    throw std::runtime_error("cannot write " + models.string() + " (the plan's models): it exists and is not a folder");
  fs::remove_all(staged, ec);
  if (!fs::create_directory(staged, ec))
    throw std::runtime_error("cannot write " + models.string() + " (the plan's models): " + ec.message());
  bool moved_away = false;
  try {
    for (const auto& [name, bytes] : files) write_file_atomically((staged / name).string(), bytes);
    PendingTempFile plan_file(path);
    for (const char* p = toml.data(), *end = toml.data() + toml.size(); p < end;) {
      const ssize_t n = ::write(plan_file.fd(), p, size_t(end - p));
      if (n <= 0) throw std::runtime_error("cannot write " + path);
      p += n;
    }
    if (fs::exists(models, ec)) {
      fs::rename(models, previous);
      moved_away = true;
    }
    fs::rename(staged, models);
    try {
      plan_file.commit();
    } catch (...) {
      fs::remove_all(models, ec);
      throw;
    }
  } catch (const std::exception& e) {
    fs::remove_all(staged, ec);
    if (moved_away && !fs::exists(models, ec)) fs::rename(previous, models, ec);
    const std::string what = e.what();
    throw std::runtime_error(what.find(path) != std::string::npos ? what : "cannot write " + path + ": " + what);
  }
  if (moved_away) fs::remove_all(previous, ec);
}

}  // namespace avenues
