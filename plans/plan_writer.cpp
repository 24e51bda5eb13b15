// Avenues — writing a Plan as TOML (see plan_writer.h), with toml++'s own formatter.
#include "plans/plan_writer.h"

#include <sstream>

#include <toml++/toml.h>

#include "core/atomic_file.h"

namespace avenues {
namespace {

toml::array point(Vec2 p) { return toml::array{p.x, p.y}; }
toml::array point(Vec3 p) { return toml::array{p.x, p.y, p.z}; }
toml::array rgb(const std::array<double, 3>& c) { return toml::array{c[0], c[1], c[2]}; }

}  // namespace

std::string plan_as_toml(const Plan& plan) {
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
      for (const Opening& o : w.openings) {
        if (o.kind == OpeningKind::Gap) {
          left_out.push_back("gap '" + o.name + "' of wall '" + w.name + "' (the format has doors, windows, hatches)");
          continue;
        }
        toml::table ot;
        ot.insert("name", o.name);
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
  for (const Object& o : plan.objects) {
    if (o.model || o.mesh.empty()) {
      ++boxes;
      continue;
    }
    toml::table t;
    t.insert("name", o.name);
    t.insert("mesh", o.mesh);
    t.insert("storey", storey(o.storey));
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
  if (plan.lenient) left_out.push_back("the importer's leniency (labels in walls are errors here)");
  if (plan.outside_solid) left_out.push_back("a solid outside");

  std::ostringstream out;
  out << "# " << plan.name << ", as Avenues understood it" << (plan.source.empty() ? "" : " from " + plan.source)
      << " (docs/PLAN_FORMAT.md).\n";
  for (const std::string& w : plan.warnings) out << "# warning: " << w << "\n";
  for (const std::string& l : left_out) out << "# not expressible here, left out: " << l << "\n";
  out << "\n" << root << "\n";
  return out.str();
}

void write_plan(const Plan& plan, const std::string& path) { write_file_atomically(path, plan_as_toml(plan)); }

}  // namespace avenues
