// Avenues — loading PLAN for the executable (see plan_source.h).
#include "app/plan_source.h"

#include <chrono>
#include <cctype>
#include <cstring>
#include <iostream>
#include <new>
#include <sstream>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "cells/build_cells.h"
#include "cells/crow.h"
#include "core/file_name.h"
#include "plans/formats/doom_map.h"
#include "plans/formats/ifc_building.h"
#include "plans/assimp_reader.h"
#include "plans/mesh.h"
#include "plans/formats/dxf_plan.h"
#include "plans/formats/floorplan_vectors.h"
#include "cells/mesh_scene.h"
#include "plans/formats/sweet_home.h"
#include "plans/plan.h"
#include "plans/plan_writer.h"

#ifndef AVENUES_SOURCE_DIR
#define AVENUES_SOURCE_DIR ""
#endif

namespace avenues::app {
namespace fs = std::filesystem;

namespace {

constexpr const char* kDefaultPlan = "jones-house.toml";

using PlanReader = Plan (*)(const std::string& file);

/// The readers of plans from elsewhere, by format: adding one is one line here (the
/// formats that yield cells directly, and the Doom maps chosen by name, are in
/// load_plan_source's switch).
const std::pair<FileFormat, PlanReader> kPlanReaders[] = {
    {FileFormat::Toml, [](const std::string& file) { return read_plan(file); }},
    {FileFormat::SweetHome, [](const std::string& file) { return read_sweet_home(file); }},
};

PlanReader plan_reader_for(FileFormat f) {
  for (const auto& [format, reader] : kPlanReaders)
    if (format == f) return reader;
  return nullptr;
}

}  // namespace

MeshAxes ImportOptions::mesh_axes() const { return {up_axis_named(up), metres_per_unit_named(unit)}; }

double LoadedPlan::seconds() const {
  double s = 0;
  for (const StageTime& t : stages) s += t.seconds;
  return s;
}

std::string default_plan_path() {
  std::vector<fs::path> candidates;
  if (std::string(AVENUES_SOURCE_DIR).size() > 0)
    candidates.push_back(fs::path(AVENUES_SOURCE_DIR) / "plans" / kDefaultPlan);
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(exe.parent_path().parent_path() / "share" / "avenues" / "plans" / kDefaultPlan);
  std::string looked;
  for (const fs::path& p : candidates) {
    if (fs::is_regular_file(p, ec)) return p.string();
    looked += (looked.empty() ? "" : ", ") + p.string();
  }
  throw std::runtime_error(std::string("cannot find the bundled plan ") + kDefaultPlan + " (looked in " +
                           (looked.empty() ? "nowhere" : looked) + "); name a PLAN");
}

namespace {

/// The bytes of a file ("" when it cannot be read).
std::string whole_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The first `n` bytes of a file (fewer when it is shorter; "" when it cannot be read).
std::string file_head(const std::string& path, size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string head(n, '\0');
  head.resize(size_t(in.read(head.data(), std::streamsize(head.size())).gcount()));
  return head;
}

/// Whether a file is neither a zip archive nor one whose first 64 KiB open a <home>
/// element (a Sweet Home 3D Home.xml, its <home> after its prolog and document type).
bool xml_without_home(const std::string& path) {
  const std::string head = file_head(path, 64 * 1024);
  if (head.compare(0, 4, "PK\x03\x04") == 0) return false;
  for (size_t at = head.find("<home"); at != std::string::npos; at = head.find("<home", at + 1)) {
    const char next = at + 5 < head.size() ? head[at + 5] : '>';
    if (next == '>' || next == '/' || std::isspace(static_cast<unsigned char>(next))) return false;
  }
  return true;
}

}  // namespace

void print_warnings(const std::string& path, const std::vector<std::string>& warnings) {
  constexpr size_t kShown = 12;
  for (size_t i = 0; i < warnings.size() && i < kShown; ++i) {
    const std::string& w = warnings[i];
    // A warning that names its own place in the file ("house.sh3d:Home.xml:26:3 (level
    // 'Attic'): ..." or "house.sh3d: ...") keeps that place in front, once.
    const size_t place = w.compare(0, path.size(), path) == 0 && w.size() > path.size() && w[path.size()] == ':'
                             ? w.find(": ", path.size())
                             : std::string::npos;
    if (place != std::string::npos)
      std::cerr << w.substr(0, place) << ": warning: " << w.substr(place + 2) << "\n";
    else
      std::cerr << path << ": warning: " << w << "\n";
  }
  if (warnings.size() > kShown)
    std::cerr << path << ": " << warnings.size() - kShown << " more warnings (avenues cells PLAN --json lists them all)\n";
}

PlanSpec parse_plan_spec(const std::string& plan) {
  PlanSpec spec;
  spec.file = plan;
  // FILE.wad:MAP01 — the map after the last colon, when what precedes it is a WAD (by
  // name, or by content when PLAN itself names no file).
  const size_t colon = plan.rfind(':');
  std::error_code ec;
  if (colon != std::string::npos && colon > 0) {
    const std::string file = plan.substr(0, colon);
    if ((colon > 4 && ascii_lower(plan.substr(colon - 4, 4)) == ".wad") ||
        (!fs::exists(plan, ec) && detect_format(file) == FileFormat::DoomWad)) {
      spec.file = file;
      spec.map = plan.substr(colon + 1);
    }
  }
  spec.format = detect_format(spec.file);
  // Models other readers know only by extension: glTF is JSON, which would pass for text;
  // a 3MF model is a zip archive, as a Sweet Home home is; a Blender file saved compressed
  // is gzip. Where the content says only that much, an extension Assimp reads decides.
  // So does a mesh told only by the look of its text (OBJ's "v" lines, an OFF header):
  // NFF's text is OBJ-like, and Assimp goes by the extension too.
  const std::string ext = lower_extension(spec.file);
  const bool foreign_zip = spec.format == FileFormat::SweetHome && format_of_extension(spec.file) != FileFormat::SweetHome;
  const bool container = spec.format == FileFormat::Gzip || foreign_zip;
  if ((spec.format == FileFormat::Toml || spec.format == FileFormat::Unknown || container ||
       is_mesh_format(spec.format)) &&
      format_of_extension(spec.file) == FileFormat::Unknown && assimp_reads_extension(ext))
    spec.format = FileFormat::Model;
  // Binary, with no signature of Avenues' own and a name that says nothing: a model Assimp
  // knows by its content (3DS's chunks, LightWave's "FORM", a binary DirectX "xof ").
  // The same for a zip archive that is no Sweet Home home (a 3MF model).
  if (spec.format == FileFormat::Unknown || (foreign_zip && spec.format == FileFormat::SweetHome)) {
    spec.content_reader = assimp_importer_by_content(spec.file);
    if (!spec.content_reader.empty()) spec.format = FileFormat::Model;
  }
  // An .xml file with no <home> in it is no Sweet Home home, whatever its name says: it may
  // be a model in XML that Assimp knows by its root element (COLLADA, XGL, Irrlicht, Ogre).
  // Else the Sweet Home reader names its root element.
  if (spec.format == FileFormat::SweetHome && !foreign_zip && xml_without_home(spec.file)) {
    spec.content_reader = assimp_importer_by_content(spec.file);
    if (!spec.content_reader.empty()) spec.format = FileFormat::Model;
  }
  return spec;
}

LoadedPlan load_plan_source(const std::string& plan, const ImportOptions& import) {
  LoadedPlan out;
  PlanSpec spec = parse_plan_spec(plan.empty() ? default_plan_path() : plan);
  out.path = plan.empty() ? spec.file : plan;
  fs::path p(spec.file);
  out.stem = p.stem().string() + (spec.map.empty() ? "" : "-" + spec.map);
  std::error_code ec;
  if (!fs::exists(p, ec)) throw std::runtime_error(spec.file + ": no such file");
  if (fs::is_directory(p, ec)) throw std::runtime_error(spec.file + ": is a directory, not a plan");
  if (!fs::is_regular_file(p, ec)) throw std::runtime_error(spec.file + ": not a regular file (a device or FIFO?), not a plan");
  out.format = spec.format;
  // Text under an extension no reader has, which is not TOML either (a VRML model, a
  // README): its error says so before TOML's.
  bool foreign_text = false;
  // What the file's name says, for an error about a file Avenues does not know.
  auto what_the_name_says = [&p] {
    if (lower_extension(p.string()) == ".xml") return std::string("it is XML with no <home> element, no Sweet Home 3D home");
    return p.extension().empty() ? std::string("its name has no extension")
                                 : "its extension '" + p.extension().string() + "' names no format Avenues reads";
  };
  if ((spec.format == FileFormat::Toml || spec.format == FileFormat::Unknown) && lower_extension(p.string()) != ".toml") {
    // No telling signature: a few lines of content tell floor-plan annotations.
    if (looks_like_floorplan_vectors(file_head(spec.file, 4096))) spec.format = FileFormat::FloorplanVectors;
    // Text that is not TOML, under a name that says nothing: a model Assimp knows by its
    // first keywords ("AC3Db", "*3DSMAX_ASCIIEXPORT", "xof 0302txt"). TOML text stays a
    // plan, whatever else it might pass for, and text neither knows keeps TOML's message.
    else if (spec.format == FileFormat::Toml && !parses_as_toml(whole_file(spec.file))) {
      spec.content_reader = assimp_importer_by_content(spec.file);
      if (!spec.content_reader.empty()) spec.format = FileFormat::Model;
      else if (!p.extension().empty()) foreign_text = true;
    }
    out.format = spec.format;
  }

  auto t0 = std::chrono::steady_clock::now();
  auto build = [&](const Plan& parsed) {
    if (!import.save_plan.empty()) {
      write_plan(parsed, import.save_plan);
      std::cerr << spec.file << ": the plan as understood is in " << import.save_plan << "\n";
    }
    out.complex = build_cells(parsed);
    for (const StageTime& t : out.complex.timings) out.stages.push_back(t);
  };
  auto decompose = [&](const Plan& parsed, const char* stage) {
    out.stages.push_back({stage, seconds_since(t0)});
    build(parsed);
  };
  // A mesh as a whole scene: OpenMesh or Assimp by its format, turned to z-up metres.
  // `read`: the mesh, when the file's reader has it already (an IFC model without walls).
  auto read_mesh = [&](const std::string& file, const MeshAxes& axes, const Mesh* read = nullptr,
                       std::vector<std::string> said = {}) {  // said: what reading it found (missing files)
    if (!import.save_plan.empty())  // told before the work, and nothing written
      throw std::runtime_error(file + " is read as a mesh scene, which has no plan: --save-plan " +
                               import.save_plan + " cannot be written");
    Mesh loaded;
    const Mesh& mesh = read ? *read : (loaded = load_mesh(file, axes, &said));  // names the file when unreadable
    out.stages.push_back({"read mesh", seconds_since(t0)});
    // A large soup takes a while (issue 16: 5-15 s for the curved and the structural
    // models of a few hundred thousand triangles, split into structure and detail): say so
    // before, not after.
    if (mesh.triangles.size() >= 50'000)
      std::cerr << file << ": " << mesh.triangles.size()
                << " triangles to decompose as a polygon soup: this may take a while\n";
    try {
      out.complex = build_mesh_scene({mesh});
    } catch (const std::bad_alloc&) {
      throw;  // "out of memory while decomposing FILE", below
    } catch (const std::exception& e) {
      throw std::runtime_error(file + ": " + e.what());
    }
    out.complex.warnings.insert(out.complex.warnings.begin(), said.begin(), said.end());
    out.complex.plan_name = out.stem;
    for (const StageTime& t : out.complex.timings) out.stages.push_back(t);
  };
  // Memory running out (an allocation, or GMP's: cells/gmp_memory.h) names the file.
  try {
    switch (spec.format) {
      case FileFormat::Cells:
        out.complex = load_cells(spec.file);
        out.stages.push_back({"load cells", seconds_since(t0)});
        return out;
      case FileFormat::DoomWad: {
        if (spec.map.empty()) {
          const std::vector<std::string> maps = doom_map_names(spec.file);
          if (maps.empty()) throw PlanError({spec.file, 0, 0, ""}, "the WAD holds no maps");
          spec.map = maps.front();
          out.stem += "-" + spec.map;
          std::cerr << spec.file << ": reading " << spec.map << ", the first of its " << maps.size()
                    << " maps (name one as " << spec.file << ":" << maps.back() << ")\n";
        }
        decompose(read_doom_map(spec.file, spec.map), "read map");
        break;
      }
      case FileFormat::Off:
      case FileFormat::Obj:
      case FileFormat::Ply:
      case FileFormat::Stl: {
        // The mesh readers go by the extension; under a name that says nothing, Assimp
        // reads the mesh by its content (parse_plan_spec gave a name Assimp reads to Assimp).
        // Under another format's name, it is named as one.
        if (format_of_extension(spec.file) != spec.format && format_of_extension(spec.file) != FileFormat::Unknown)
          throw std::runtime_error(spec.file + " is " + format_name(spec.format) +
                                   " under another extension: name it as one to read it as a scene");
        if (!import.up.empty()) {
          read_mesh(spec.file, import.mesh_axes());
          break;
        }
        // The format does not say which axis is up, and neither did the user: a model that
        // stands on y = 0 is taken as drawn Y-up (guessed_up_axis), with a warning.
        std::vector<std::string> said;
        Mesh mesh = load_mesh(spec.file, import.mesh_axes(), &said);
        if (guessed_up_axis(mesh) == 'y') {
          orient_z_up(mesh, 'y', 1.0);
          said.insert(said.begin(), spec.file + ": the file does not say which axis is up: taken as y, as the model "
                                                "stands on y = 0 (as Y-up exports from Blender, SketchUp or 3ds Max "
                                                "do); say --up z if it is drawn Z-up");
        }
        read_mesh(spec.file, import.mesh_axes(), &mesh, std::move(said));
        break;
      }
      case FileFormat::Model:
        try {
          read_mesh(spec.file, import.mesh_axes());
        } catch (const std::bad_alloc&) {
          throw;
        } catch (const std::exception& e) {
          if (spec.content_reader.empty()) throw;
          throw std::runtime_error(spec.file + " is not a plan Avenues can read: " + what_the_name_says() +
                                   ", and " + spec.content_reader + " took it by its content but could not read it (" +
                                   e.what() + ")");
        }
        break;
      case FileFormat::Ifc: {
        try {
          build(read_ifc_building(spec.file, &out.stages));  // its reader times its own stages
        } catch (const IfcWithoutWalls& e) {  // thrown by the reader only
          // A structural model, a piece of equipment: its elements' faces are the scene.
          std::cerr << e.what() << ": read as a mesh scene, every element's faces\n";
          read_mesh(spec.file, import.mesh_axes(), e.faces.get());
        }
        break;
      }
      case FileFormat::FloorplanVectors: {
        FloorplanVectorOptions o;
        if (import.scale > 0) o.metres_per_pixel = import.scale;
        o.storey_height = import.storey_height;
        decompose(read_floorplan_vectors(spec.file, o), "read annotations");
        break;
      }
      case FileFormat::Dxf: {
        const DxfPlan d = read_dxf_plan(spec.file, {import.layers, import.unit, import.storey_height});
        if (d.model_faces > 0) {
          // A 3D model in DXF: its faces are the scene, in the unit its $INSUNITS says.
          MeshAxes axes = import.mesh_axes();
          if (!axes.metres_per_unit && d.metres_per_unit > 0) axes.metres_per_unit = d.metres_per_unit;
          std::cerr << spec.file << ": a 3D model (" << d.model_faces
                    << " 3D faces and meshes, no line on a wall layer): read as a mesh scene, z up"
                    << (import.up.empty() ? " (drawn Y-up? say --up y)" : "") << "\n";
          read_mesh(spec.file, axes);
          break;
        }
        for (const std::string& line : d.summary) std::cerr << spec.file << ": " << line << "\n";
        out.drawing = d.drawing;
        decompose(d.plan, "read drawing");
        break;
      }
      case FileFormat::Crow:
        out.complex = read_crow_scene(spec.file);
        for (const StageTime& t : out.complex.timings) out.stages.push_back(t);
        break;
      default: {
        const PlanReader reader = plan_reader_for(spec.format);
        if (!reader) {
          if (spec.format == FileFormat::Unknown)
            throw std::runtime_error(spec.file + " is not a plan Avenues can read: neither TOML text nor a format it " +
                                     "knows by its content or extension (docs/PLAN_FORMAT.md lists them)");
          throw std::runtime_error(spec.file + " is " + format_name(spec.format) + ", which Avenues cannot read yet");
        }
        try {
          decompose(reader(spec.file), "read plan");
        } catch (const PlanError& e) {
          if (!foreign_text) throw;
          throw std::runtime_error(spec.file + " is not a plan Avenues can read: " + what_the_name_says() +
                                   " (docs/PLAN_FORMAT.md lists them), and read as a TOML plan it fails: " + e.what());
        }
        break;
      }
    }
  } catch (const std::bad_alloc&) {
    throw std::runtime_error("out of memory while " +
                             std::string(spec.format == FileFormat::Cells ? "loading " : "decomposing ") + spec.file);
  }
  print_warnings(spec.file, out.complex.warnings);
  return out;
}

}  // namespace avenues::app
