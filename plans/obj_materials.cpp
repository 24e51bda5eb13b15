// Avenues — a Wavefront OBJ model's own materials (see obj_materials.h).
#include "plans/obj_materials.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>

#include "core/file_name.h"
#include "core/srgb.h"
#include "plans/image_colour.h"
#include "plans/java3d_materials.h"

namespace avenues {
namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

/// The statements of an OBJ or MTL text, one per line, comments ('#' on) cut off: each
/// line's keyword and the rest of it, trimmed; calls f(line number, keyword, rest).
template <class F>
void for_each_statement(std::string_view text, F&& f) {
  int lineno = 0;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(at, end - at);
    at = end + 1;
    ++lineno;
    if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
    line = trimmed(line);
    if (line.empty()) continue;
    size_t word = 0;
    while (word < line.size() && !is_space(line[word])) ++word;
    f(lineno, line.substr(0, word), trimmed(line.substr(word)));
  }
}

/// The words of s, split at blanks.
std::vector<std::string_view> words_of(std::string_view s) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    const size_t start = i;
    while (i < s.size() && !is_space(s[i])) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

}  // namespace

ObjMaterialUse obj_material_use(std::string_view obj) {
  ObjMaterialUse use;
  std::string current(kObjDefaultMaterial);
  long long vertices = 0;
  std::vector<long long> corners;
  for_each_statement(obj, [&](int, std::string_view key, std::string_view rest) {
    if (key == "v") {
      ++vertices;
    } else if (key == "usemtl") {
      // Sweet Home takes the rest of the line, spaces and all, as the name.
      if (!rest.empty()) {
        current = std::string(rest);
        use.uses_materials = true;
      }
    } else if (key == "mtllib") {
      if (!rest.empty()) use.libraries.emplace_back(rest);
    } else if (key == "f") {
      // OpenMesh keeps a face of three corners or more, no vertex named twice; corners
      // counted back (negative) are taken from the vertices so far, as readable_obj does.
      corners.clear();
      bool readable = true;
      for (std::string_view w : words_of(rest)) {
        const std::string_view index = w.substr(0, w.find('/'));
        long long v = 0;
        const auto [end, ec] = std::from_chars(index.data(), index.data() + index.size(), v);
        if (ec != std::errc() || end != index.data() + index.size() || v == 0) {
          readable = false;
          break;
        }
        corners.push_back(v < 0 ? vertices + v + 1 : v);
      }
      std::sort(corners.begin(), corners.end());
      if (readable && corners.size() >= 3 && std::adjacent_find(corners.begin(), corners.end()) == corners.end())
        use.face_material.push_back(current);
    }
  });
  return use;
}

std::string name_obj_materials(Mesh& m, const ObjMaterialUse& use, size_t faces_read) {
  if (!use.uses_materials) return "";
  std::map<std::string, MaterialId> index;
  std::vector<MaterialId> of_face;
  of_face.reserve(use.face_material.size());
  std::vector<size_t> faces_of;
  m.materials.clear();
  for (const std::string& name : use.face_material) {
    auto [it, fresh] = index.try_emplace(name, MaterialId(m.materials.size()));
    if (fresh) {
      Material mat;
      mat.name = name;
      mat.where = SourceLoc{m.path, 0, 0, "material '" + name + "'"};
      m.materials.push_back(std::move(mat));
      faces_of.push_back(0);
    }
    of_face.push_back(it->second);
    ++faces_of[size_t(it->second)];
  }
  if (m.materials.empty()) return "";
  std::string why;
  if (faces_read != of_face.size()) {
    // A face OpenMesh refused shifts every name after it: one material for the whole mesh,
    // the one most faces use.
    const size_t most = size_t(std::max_element(faces_of.begin(), faces_of.end()) - faces_of.begin());
    if (m.materials.size() > 1)
      why = "OpenMesh kept " + std::to_string(faces_read) + " of its faces where its text has " +
            std::to_string(of_face.size()) + ": its " + std::to_string(m.materials.size()) +
            " materials cannot be told apart, the whole model is material '" + m.materials[most].name + "'";
    Material only = m.materials[most];
    m.materials = {std::move(only)};
    m.material_of.assign(m.triangles.size(), 0);
    return why;
  }
  m.material_of.resize(m.triangles.size());
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    const int polygon = t < m.polygon_of.size() ? m.polygon_of[t] : int(t);
    m.material_of[t] = polygon >= 0 && size_t(polygon) < of_face.size() ? of_face[size_t(polygon)] : -1;
  }
  return why;
}

const MtlMaterial* MtlLibrary::find(std::string_view name) const {
  for (auto it = materials.rbegin(); it != materials.rend(); ++it)
    if (it->name == name) return &*it;
  return nullptr;
}

MtlLibrary read_mtl(std::string_view text) {
  MtlLibrary lib;
  size_t current = 0;  // 1 + the index of the material being defined; 0 before any newmtl
  for_each_statement(text, [&](int lineno, std::string_view key, std::string_view rest) {
    auto problem = [&](const std::string& what) {
      lib.problems.push_back("line " + std::to_string(lineno) + ": " + what);
    };
    if (key == "newmtl") {
      if (rest.empty()) return problem("newmtl names no material");
      lib.materials.push_back({std::string(rest), std::nullopt, "", lineno});
      current = lib.materials.size();
    } else if (key == "Kd") {
      if (!current) return problem("Kd before any newmtl");
      MtlMaterial& mat = lib.materials[current - 1];
      const std::vector<std::string_view> w = words_of(rest);
      std::array<double, 3> kd{};
      bool ok = w.size() == 1 || w.size() == 3;
      for (size_t k = 0; ok && k < w.size(); ++k) {
        const auto [end, ec] = std::from_chars(w[k].data(), w[k].data() + w[k].size(), kd[k]);
        ok = ec == std::errc() && end == w[k].data() + w[k].size() && std::isfinite(kd[k]);
      }
      if (!ok) return problem("Kd of material '" + mat.name + "' is not one or three numbers: \"" +
                              std::string(rest) + "\"");
      if (w.size() == 1) kd[1] = kd[2] = kd[0];  // one number: a grey (the MTL specification's r, with g = b = r)
      for (double& c : kd) c = std::clamp(c, 0.0, 1.0);
      mat.diffuse = kd;
    } else if (key == "map_Kd") {
      if (!current) return problem("map_Kd before any newmtl");
      MtlMaterial& mat = lib.materials[current - 1];
      if (rest.empty()) return problem("map_Kd of material '" + mat.name + "' names no image");
      mat.diffuse_map = std::string(rest);
    }
  });
  return lib;
}

std::vector<std::string> mtllib_candidates(const std::string& argument) {
  std::vector<std::string> out;
  for (std::string_view w : words_of(argument)) out.emplace_back(w);
  if (out.size() > 1) out.push_back(std::string(trimmed(argument)));
  return out;
}

std::vector<std::string> map_kd_candidates(const std::string& argument) {
  const std::vector<std::string_view> w = words_of(argument);
  std::vector<std::string> out;
  if (w.empty()) return out;
  out.emplace_back(w.back());
  if (w.size() > 1) out.push_back(std::string(trimmed(argument)));
  return out;
}

std::string path_beside(const std::string& file, const std::string& name) {
  if (!name.empty() && name.front() == '/') return name;
  const size_t slash = file.rfind('/');
  return (slash == std::string::npos ? std::string() : file.substr(0, slash + 1)) + name;
}

std::vector<std::string> paths_beside(const std::string& file, const std::string& name) {
  std::vector<std::string> out{path_beside(file, name)};
  std::string slashed = name;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  auto add = [&](const std::string& n) {
    const std::string p = path_beside(file, n);
    if (!n.empty() && std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  };
  add(slashed);
  if (const size_t last = slashed.rfind('/'); last != std::string::npos) add(slashed.substr(last + 1));
  return out;
}

std::string file_beside(const std::string& model, const std::string& name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const std::string& beside : paths_beside(model, name))
    if (fs::is_regular_file(beside, ec)) return beside;
  std::string slashed = name;
  std::replace(slashed.begin(), slashed.end(), '\\', '/');
  const fs::path dir = fs::path(model).parent_path();
  auto in_any_case = [&ec](const fs::path& from, const fs::path& relative) {
    fs::path at = from.empty() ? fs::path(".") : from;
    for (const fs::path& part : relative) {
      fs::path next = at / part;
      if (!fs::exists(next, ec) && part != "." && part != "..")
        for (fs::directory_iterator it(at, ec), end; !ec && it != end; it.increment(ec))
          if (ascii_lower(it->path().filename().string()) == ascii_lower(part.string())) {
            next = it->path();
            break;
          }
      at = next;
    }
    return at;
  };
  const fs::path written(slashed);
  if (written.is_relative())
    if (const fs::path p = in_any_case(dir, written); fs::is_regular_file(p, ec)) return p.string();
  if (const fs::path p = in_any_case(dir, written.filename()); fs::is_regular_file(p, ec)) return p.string();
  return "";
}

std::optional<std::string> read_material_file(const std::string& path) {
  constexpr std::uintmax_t kMaxBytes = std::uintmax_t(1) << 28;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxBytes) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) return std::nullopt;
  return bytes;
}

const MaterialFiles::Image& MaterialFiles::image(const std::string& path, bool* first) {
  auto [it, fresh] = images_.try_emplace(path);
  if (first) *first = fresh;
  if (!fresh) return it->second;
  const std::optional<std::string> bytes = read_ ? read_(path) : std::nullopt;
  if (!bytes) return it->second;
  it->second.at_hand = true;
  try {
    it->second.colour = mean_image_colour(*bytes, name(path));
  } catch (const std::runtime_error& e) {
    it->second.problem = e.what();
  }
  return it->second;
}

const MtlLibrary* MaterialFiles::library(const std::string& path, bool* first) {
  auto [it, fresh] = libraries_.try_emplace(path);
  if (first) *first = fresh;
  if (fresh)
    if (const std::optional<std::string> bytes = read_ ? read_(path) : std::nullopt) it->second = read_mtl(*bytes);
  return it->second ? &*it->second : nullptr;
}

std::string ObjColouring::listed(const std::set<std::string>& names) {
  std::string out;
  size_t shown = 0;
  for (const std::string& n : names)
    if (shown++ < 5) out += (out.empty() ? "'" : ", '") + n + "'";
  if (names.size() > shown) out += ", ...";
  return out;
}

ObjColouring colour_obj_materials(Mesh& m, const std::vector<std::string>& libraries, const std::string& obj,
                                  MaterialFiles& files, const std::string& who, std::vector<std::string>& warnings) {
  ObjColouring out;
  if (m.materials.empty()) return out;
  struct Defined {
    MtlMaterial material;
    std::string library;  ///< the path of the library that defines it
  };
  std::map<std::string, Defined> defined;
  std::set<std::string> arguments_seen;  // a library named twice is read once
  for (const std::string& argument : libraries) {
    if (!arguments_seen.insert(argument).second) continue;
    // Each word a library; the whole argument (last, when there are several words) only
    // when no word named one.
    const std::vector<std::string> names = mtllib_candidates(argument);
    const size_t words = names.size() > 1 ? names.size() - 1 : names.size();
    bool found = false;
    for (size_t i = 0; i < names.size(); ++i) {
      if (i == words && found) break;
      std::string path;
      bool first = false;
      const MtlLibrary* lib = nullptr;
      for (const std::string& form : paths_beside(obj, names[i]))
        if ((lib = files.library(path = form, &first))) break;
      if (!lib) continue;
      found = true;
      if (first)
        for (const std::string& problem : lib->problems)
          warnings.push_back(who + "material library " + files.name(path) + ": " + problem + ": left out");
      for (const MtlMaterial& mat : lib->materials) defined.insert_or_assign(mat.name, Defined{mat, path});
    }
    if (!found) {
      ++out.libraries_missing;
      warnings.push_back(who + "its material library '" + argument + "' is not at hand (" +
                         files.name(path_beside(obj, names.empty() ? argument : names.front())) +
                         "): its materials keep Avenues' default colour");
    }
  }
  for (Material& mat : m.materials) {
    const auto it = defined.find(mat.name);
    if (it == defined.end()) {
      // No library at hand defines it: Java 3D's built-in table, as Sweet Home's OBJLoader
      // starts from it (java3d_materials.h).
      if (const std::optional<std::array<double, 3>> kd = java3d_material_colour(mat.name)) {
        mat.colour = linear_from_srgb(*kd);
        mat.where = SourceLoc{"Java 3D's built-in materials", 0, 0, "material '" + mat.name + "'"};
        ++out.builtin;
      } else {
        out.undefined.insert(mat.name);
      }
      continue;
    }
    const MtlMaterial& d = it->second.material;
    std::optional<std::array<double, 3>> colour;
    if (!d.diffuse_map.empty()) {
      bool found = false;
      for (const std::string& file : map_kd_candidates(d.diffuse_map)) {
        bool first = false;
        const MaterialFiles::Image* at = nullptr;
        for (const std::string& form : paths_beside(it->second.library, file))
          if ((at = &files.image(form, &first))->at_hand) break;
        const MaterialFiles::Image& image = *at;
        if (!image.at_hand) continue;
        found = true;
        colour = image.colour;
        if (first && !image.problem.empty())
          warnings.push_back(who + "material '" + mat.name + "': " + image.problem +
                             ": the material keeps its colour without it");
        break;
      }
      if (!found)
        warnings.push_back(who + "material '" + mat.name + "': its image " + d.diffuse_map +
                           " (map_Kd) is not at hand: its Kd colour is used instead");
    }
    if (!colour && d.diffuse) colour = linear_from_srgb(*d.diffuse);
    if (colour) mat.colour = *colour;
    mat.where = SourceLoc{files.name(it->second.library), d.line, 0, "material '" + mat.name + "'"};
  }
  return out;
}

}  // namespace avenues
