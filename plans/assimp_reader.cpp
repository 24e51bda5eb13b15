// Avenues — models read with Assimp (see assimp_reader.h). The one translation unit that
// includes Assimp.
#include "plans/assimp_reader.h"

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/commonMetaData.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/file_name.h"
#include "core/stage_timer.h"
#include "core/text_encoding.h"
#include "plans/image_colour.h"
#include "plans/irrlicht_scene.h"
#include "plans/vrml_scene.h"
#include "plans/obj_materials.h"

namespace avenues {

namespace {

/// The axes Assimp's output is in for this file, and what the file itself declared.
struct OutputAxes {
  char up = 'z';
  bool up_negative = false;  ///< FBX's UpAxisSign = -1
  double metres_per_unit = 1;
  bool declares_up = false, declares_unit = false;
  bool dxf_turned = false;  ///< Assimp's DXF reader turned the file's z to y: --up names the file's axes
};

template <class T>
bool meta_number(const aiMetadata* meta, const char* key, T& out) {
  if (!meta) return false;
  for (unsigned i = 0; i < meta->mNumProperties; ++i) {
    if (std::string(meta->mKeys[i].C_Str()) != key) continue;
    const aiMetadataEntry& e = meta->mValues[i];
    if (!e.mData) return false;
    switch (e.mType) {
      case AI_INT32: out = T(*static_cast<const int32_t*>(e.mData)); return true;
      case AI_UINT64: out = T(*static_cast<const uint64_t*>(e.mData)); return true;
      case AI_FLOAT: out = T(*static_cast<const float*>(e.mData)); return true;
      case AI_DOUBLE: out = T(*static_cast<const double*>(e.mData)); return true;
      default: return false;
    }
  }
  return false;
}

OutputAxes output_axes(const aiScene& scene, const std::string& format) {
  OutputAxes a;
  auto has = [&](const char* s) { return format.find(s) != std::string::npos; };
  if (has("glTF") || has("Collada") || has("IFC") || has("Industry Foundation")) {
    // Assimp turns these to Y-up and applies COLLADA's <unit> and IFC's length unit;
    // glTF is Y-up metres by definition.
    a.up = 'y';
    a.declares_up = a.declares_unit = true;
  } else if (has("3DS")) {
    a.up = 'y';  // Assimp turns 3DS's z-up to Y-up; the format has no unit
    a.declares_up = true;
  } else if (has("DXF")) {
    // Assimp turns AutoCAD's z-up to Y-up (the file's z is its y, the file's y its -z);
    // the file does not say, and a model drawn Y-up (LightWave's) is read with --up y.
    a.up = 'y';
    a.dxf_turned = true;
  } else if (has("FBX")) {
    int axis = 1, sign = 1;
    if (meta_number(scene.mMetaData, "UpAxis", axis) && axis >= 0 && axis <= 2) {
      meta_number(scene.mMetaData, "UpAxisSign", sign);
      a.up = char('x' + axis);
      a.up_negative = sign < 0;
      a.declares_up = true;
    }
    double cm = 1;
    if (meta_number(scene.mMetaData, "UnitScaleFactor", cm) && std::isfinite(cm) && cm > 0) {
      a.metres_per_unit = cm / 100;  // FBX's unit: centimetres per file unit
      a.declares_unit = true;
    }
  }
  return a;
}

/// Assimp's frame (after node transforms) to Avenues' z-up, as a rotation.
Vec3 z_up(aiVector3D p, char up, bool negative) {
  const double x = p.x, y = p.y, z = p.z;
  switch (up) {
    case 'x': return negative ? Vec3{y, -z, -x} : Vec3{y, z, x};
    case 'y': return negative ? Vec3{x, z, -y} : Vec3{x, -z, y};
    default: return negative ? Vec3{x, -y, -z} : Vec3{x, y, z};
  }
}

std::array<double, 3> diffuse_of(const aiScene& scene, unsigned material, bool& found) {
  found = false;
  if (material >= scene.mNumMaterials || !scene.mMaterials[material]) return {0.8, 0.8, 0.8};
  const aiMaterial& m = *scene.mMaterials[material];
  aiColor4D c;
  if (m.Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS || m.Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
    auto clamp = [](float v) { return std::isfinite(v) ? std::min(1.0, std::max(0.0, double(v))) : 0.8; };
    found = true;
    return {clamp(c.r), clamp(c.g), clamp(c.b)};
  }
  return {0.8, 0.8, 0.8};
}

/// The mean colour (linear) of a material's diffuse or base colour texture, as a Sweet Home
/// texture or an OBJ's map_Kd gives one: Avenues paints each surface one colour. The image
/// is embedded ("*0", or an FBX's own name for it) or a file beside the model, found as an
/// OBJ's map_Kd is, and in any case (file_beside). std::nullopt when the material has no
/// texture; `problem` says why one that it has gives no colour.
std::optional<std::array<double, 3>> texture_colour(const aiScene& scene, const aiMaterial& m,
                                                    const std::string& model, std::string& problem) {
  aiString where;
  if (m.GetTexture(aiTextureType_BASE_COLOR, 0, &where) != AI_SUCCESS &&
      m.GetTexture(aiTextureType_DIFFUSE, 0, &where) != AI_SUCCESS)
    return std::nullopt;
  const std::string name = where.C_Str();
  if (name.empty()) return std::nullopt;
  try {
    if (const aiTexture* t = scene.GetEmbeddedTexture(name.c_str())) {
      if (!t->pcData) throw std::runtime_error("the embedded image has no data");
      if (t->mHeight == 0)  // compressed: mWidth bytes of a PNG, a JPEG, ...
        return mean_image_colour(std::string_view(reinterpret_cast<const char*>(t->pcData), t->mWidth),
                                 model + ": embedded image " + name);
      // Raw BGRA texels, in RGBA order for mean_pixels_colour.
      const uint64_t n = uint64_t(t->mWidth) * t->mHeight;
      if (n == 0 || n > uint64_t(kMaxImagePixels)) throw std::runtime_error("the embedded image's size is out of range");
      std::vector<unsigned char> rgba;
      rgba.reserve(4 * n);
      for (uint64_t i = 0; i < n; ++i) {
        const aiTexel& x = t->pcData[i];
        rgba.insert(rgba.end(), {x.r, x.g, x.b, x.a});
      }
      return mean_pixels_colour(rgba, model + ": embedded image " + name);
    }
    // Beside the model as an OBJ's map_Kd is, and in any case (file_beside).
    if (const std::string at = file_beside(model, name); !at.empty()) {
      std::ifstream in(at, std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      return mean_image_colour(bytes, at);
    }
    problem = "its image " + name + " is not at hand";
  } catch (const std::runtime_error& e) {
    problem = e.what();
  }
  return std::nullopt;
}

void collect(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent_world, int parent,
             const OutputAxes& axes, double metres, ImportedScene& out, int& dropped, int depth) {
  if (depth > 256) throw std::runtime_error("the node hierarchy is deeper than 256 (a cycle?)");
  const aiMatrix4x4 world = parent_world * node.mTransformation;
  const bool mirrored = world.Determinant() < 0;
  const int self = int(out.nodes.size());
  out.nodes.emplace_back();
  {
    ImportedNode& n = out.nodes.back();
    n.name = node.mName.C_Str();
    n.parent = parent;
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      // Read without Assimp's validation (import_scene's retry), a scene can hold a mesh that
      // is missing or holds no points: such a mesh has nothing to keep.
      if (!node.mMeshes || node.mMeshes[k] >= scene.mNumMeshes || !scene.mMeshes[node.mMeshes[k]]) continue;
      const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
      if (!mesh.mVertices || !mesh.mFaces) continue;
      const int material = mesh.mMaterialIndex < out.materials.size() ? int(mesh.mMaterialIndex) : -1;
      if (!n.coloured && material >= 0) {
        n.colour = out.materials[size_t(material)].colour;
        n.coloured = out.materials[size_t(material)].coloured;
      }
      const int base = int(n.vertices.size());
      std::vector<bool> finite(mesh.mNumVertices);
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const Vec3 p = metres * z_up(world * mesh.mVertices[v], axes.up, axes.up_negative);
        finite[v] = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
        n.vertices.push_back(finite[v] ? p : Vec3{});
      }
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3 || !face.mIndices) continue;  // points and lines have no surface
        const unsigned a = face.mIndices[0], b = face.mIndices[1], c = face.mIndices[2];
        if (a >= mesh.mNumVertices || b >= mesh.mNumVertices || c >= mesh.mNumVertices ||
            !finite[a] || !finite[b] || !finite[c]) {
          ++dropped;
          continue;
        }
        if (mirrored) n.triangles.push_back({base + int(a), base + int(c), base + int(b)});
        else n.triangles.push_back({base + int(a), base + int(b), base + int(c)});
        n.triangle_material.push_back(material);
      }
    }
  }
  for (unsigned c = 0; node.mChildren && c < node.mNumChildren; ++c)
    if (node.mChildren[c]) collect(scene, *node.mChildren[c], world, self, axes, metres, out, dropped, depth + 1);
}

/// Drops what Assimp's check of a scene may fail on and Avenues does not use: lights, cameras
/// and animations (Avenues lights a plan by its own lights), and empty slots among a node's
/// children.
void repair_scene(aiScene& scene) {
  auto drop = [](auto**& items, unsigned& count) {
    for (unsigned k = 0; items && k < count; ++k) delete items[k];
    delete[] items;
    items = nullptr;
    count = 0;
  };
  drop(scene.mLights, scene.mNumLights);
  drop(scene.mCameras, scene.mNumCameras);
  drop(scene.mAnimations, scene.mNumAnimations);
  std::vector<aiNode*> stack;
  if (scene.mRootNode) stack.push_back(scene.mRootNode);
  for (size_t guard = 0; !stack.empty() && guard < 1'000'000; ++guard) {
    aiNode* n = stack.back();
    stack.pop_back();
    if (!n->mChildren) n->mNumChildren = 0;
    unsigned kept = 0;
    for (unsigned c = 0; c < n->mNumChildren; ++c)
      if (n->mChildren[c]) n->mChildren[kept++] = n->mChildren[c];
    n->mNumChildren = kept;
    for (unsigned c = 0; c < kept; ++c) stack.push_back(n->mChildren[c]);
  }
}

/// A binary glTF (its "glTF" magic and version 2) under a name Assimp does not take for one:
/// Assimp's glTF reader goes by the extension alone. `bytes`, when given, gets the file.
bool binary_gltf_by_content_only(const std::string& path, std::string* bytes = nullptr) {
  const std::string ext = lower_extension(path);
  if (ext == ".glb" || ext == ".gltf") return false;
  std::ifstream in(path, std::ios::binary);
  char head[8] = {};
  if (!in.read(head, sizeof head) || std::memcmp(head, "glTF", 4) != 0 || head[4] != 2 || head[5] || head[6] || head[7])
    return false;
  if (bytes) {
    in.seekg(0);
    bytes->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  return true;
}

}  // namespace

bool assimp_reads_extension(const std::string& ext) {
  if (ext.size() < 2 || ext[0] != '.') return false;
  const Assimp::Importer importer;
  return importer.IsExtensionSupported(ext.c_str());
}

std::string assimp_importer_by_content(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return "";
  if (binary_gltf_by_content_only(path)) return "Assimp's glTF 2 (binary)";
  switch (irrlicht_file_kind(path)) {  // UTF-16 text, which Assimp's own tests miss
    case IrrlichtFile::Scene: return "Avenues' Irrlicht scene reader";
    case IrrlichtFile::Mesh: return "Avenues' Irrlicht mesh reader";
    case IrrlichtFile::None: break;
  }
  if (is_vrml(path)) return "Avenues' VRML97 reader";
  const Assimp::Importer importer;
  for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
    const Assimp::BaseImporter* reader = importer.GetImporter(i);
    try {
      if (reader && reader->CanRead(path, importer.GetIOHandler(), true)) {
        std::string name = reader->GetInfo() && reader->GetInfo()->mName ? reader->GetInfo()->mName : "importer";
        if (const size_t web = name.find(" (http"); web != std::string::npos) name.erase(web);  // its home page
        return "Assimp's " + name;
      }
    } catch (const std::exception&) {  // a reader that throws on what it cannot read does not know it
    }
  }
  return "";
}

ImportedScene import_scene(const std::string& path, const ImportOptions& options) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error("cannot read model " + path + ": no such file");
  // Irrlicht's XML, which Debian's Assimp refuses, and VRML97, which it does not read: read
  // by Avenues (irrlicht_scene.h, vrml_scene.h).
  if (options.contents.empty() && irrlicht_file_kind(path) != IrrlichtFile::None) return read_irrlicht(path, options);
  if (options.contents.empty() && is_vrml(path)) return read_vrml(path, options);
  // A second importer, made only to read a file again (below): Assimp's readers keep state
  // from one read to the next (its OpenGEX reader crashes reading a file twice).
  std::optional<Assimp::Importer> importers[2];
  auto fresh_importer = [&](int k) {
    Assimp::Importer& importer = importers[k].emplace();
    importer.SetPropertyBool(AI_CONFIG_IMPORT_IFC_SKIP_SPACE_REPRESENTATIONS, !options.ifc_spaces);
    // Only triangles are kept: drop points and lines at the source.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    return &importer;
  };
  Assimp::Importer* importer = fresh_importer(0);
  ImportedScene out;
  out.path = path;
  const auto t0 = std::chrono::steady_clock::now();
  const aiScene* scene = nullptr;
  constexpr unsigned kSteps = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType;
  std::string bytes;
  // UTF-16 text (with its byte-order mark, as Windows tools save an AC3D or COLLADA file),
  // which Assimp's text readers refuse: read as the UTF-8 it holds, from memory.
  std::string_view contents = options.contents;
  std::string utf8;
  if (contents.empty()) {
    std::ifstream in(path, std::ios::binary);
    char mark[2] = {};
    in.read(mark, 2);
    if (in.gcount() == 2 && utf16_marked(std::string_view(mark, 2)) &&
        std::filesystem::file_size(path, ec) < (std::uintmax_t(1) << 28)) {
      in.seekg(0);
      utf8 = utf8_of_text(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
      contents = utf8;
    }
  }
  auto read = [&](unsigned steps) {
    try {
      if (!contents.empty()) {  // Assimp tells the format by the hint: the extension without its dot
        std::string hint = lower_extension(path);
        if (!hint.empty()) hint.erase(0, 1);
        return importer->ReadFileFromMemory(contents.data(), contents.size(), steps, hint.c_str());
      }
      if (!bytes.empty() || binary_gltf_by_content_only(path, &bytes))  // whole in one file: read from memory, told it is GLB
        return importer->ReadFileFromMemory(bytes.data(), bytes.size(), steps, "glb");
      return importer->ReadFile(path, steps);
    } catch (const std::exception& e) {  // Assimp catches its own; anything else is a reading failure too
      throw std::runtime_error("cannot read model " + path + ": " + e.what());
    }
  };
  scene = read(kSteps | aiProcess_ValidateDataStructure);
  // Assimp's check of the scene it made fails for things Avenues does not use as well as for
  // things it does: a light or a camera with no node (OpenGEX), an empty slot among a node's
  // children (RAW). The format's own tools show such a file. So it is read again as it
  // stands, those parts are dropped, and the rest is checked and processed as before.
  if (!scene && std::string_view(importer->GetErrorString()).starts_with("Validation failed")) {
    const std::string complaint = importer->GetErrorString();
    importer = fresh_importer(1);
    if (const aiScene* raw = read(0)) {
      repair_scene(*const_cast<aiScene*>(raw));  // the importer's own scene, not processed yet
      scene = importer->ApplyPostProcessing(kSteps | aiProcess_ValidateDataStructure);
    }
    if (!scene) {
      std::string again = importer->GetErrorString();
      throw std::runtime_error("cannot read model " + path + ": " + complaint +
                               (again.empty() || again == complaint ? "" : "; without its lights, cameras and animations: " + again));
    }
    out.warnings.push_back("Assimp's check of the scene failed (" + complaint +
                           "): its lights, cameras, animations and empty nodes were dropped");
  }
  out.import_seconds = seconds_since(t0);
  if (!scene) {
    std::string why = importer->GetErrorString();
    if (why.empty()) why = "Assimp gives no reason";
    // Points and lines are dropped as they are read (AI_CONFIG_PP_SBP_REMOVE): a file of
    // nothing else is left with no mesh, which Assimp words for itself.
    if (why == "No meshes remaining") why = "it holds no surfaces, only points or lines (Avenues needs polygons)";
    // An IFC model whose only geometry Assimp cannot make (CSG primitives, NURBS faces).
    if (why.find("mNumMeshes is 0") != std::string::npos)
      why = "Assimp makes no surface of it (" + why + ")";
    throw std::runtime_error("cannot read model " + path + ": " + why);
  }
  if (!scene->mRootNode) throw std::runtime_error("cannot read model " + path + ": it has no nodes");
  aiString format;
  if (scene->mMetaData) scene->mMetaData->Get(AI_METADATA_SOURCE_FORMAT, format);
  out.format = format.C_Str();

  // glTF's base colour multiplies its texture; the other formats' diffuse colour stands
  // beside a texture that replaces it, as an OBJ's Kd beside its map_Kd.
  const bool factor_times_texture = out.format.find("glTF") != std::string::npos;
  std::vector<std::string> untextured;  // materials whose texture gave no colour, and why
  for (unsigned m = 0; scene->mMaterials && m < scene->mNumMaterials; ++m) {
    ImportedMaterial im;
    im.colour = diffuse_of(*scene, m, im.coloured);
    aiString name;
    if (scene->mMaterials[m] && scene->mMaterials[m]->Get(AI_MATKEY_NAME, name) == AI_SUCCESS) im.name = name.C_Str();
    if (im.name.empty()) im.name = "material " + std::to_string(m + 1);
    if (scene->mMaterials[m]) {
      std::string problem;
      if (const auto tex = texture_colour(*scene, *scene->mMaterials[m], path, problem)) {
        for (size_t c = 0; c < 3; ++c) im.colour[c] = factor_times_texture && im.coloured ? im.colour[c] * (*tex)[c] : (*tex)[c];
        im.coloured = true;
      } else if (!problem.empty()) {
        untextured.push_back("'" + im.name + "' (" + problem + ")");
      }
    }
    out.materials.push_back(std::move(im));
  }
  if (!untextured.empty()) {
    std::string said = std::to_string(untextured.size()) + " material(s) keep their colour without their texture: ";
    for (size_t i = 0; i < untextured.size() && i < 3; ++i) said += (i ? ", " : "") + untextured[i];
    if (untextured.size() > 3) said += ", ...";
    out.warnings.push_back(said);
  }
  OutputAxes axes = output_axes(*scene, out.format);
  const std::string named = out.format.empty() ? "the format" : out.format;
  if (options.axes.up) {
    if (axes.declares_up)
      out.warnings.push_back("up axis '" + std::string(1, *options.axes.up) + "' ignored: " + named + " declares the file's own");
    else if (!axes.dxf_turned)
      axes.up = *options.axes.up;
    else if (*options.axes.up == 'z')
      axes.up = 'y';
    else if (*options.axes.up == 'y')
      axes.up = 'z', axes.up_negative = true;
    else
      axes.up = *options.axes.up;
  }
  if (options.axes.metres_per_unit) {
    if (axes.declares_unit) out.warnings.push_back("unit ignored: " + named + " declares the file's own");
    else axes.metres_per_unit = *options.axes.metres_per_unit;
  }
  int dropped = 0;
  try {
    collect(*scene, *scene->mRootNode, aiMatrix4x4(), -1, axes, axes.metres_per_unit, out, dropped, 0);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot read model " + path + ": " + e.what());
  }
  if (dropped > 0)
    out.warnings.push_back(std::to_string(dropped) + " triangles dropped: they name missing or non-finite vertices");
  // The file's first camera (glTF, COLLADA, FBX and 3DS keep them), placed by its node:
  // where the file's own viewer starts. Assimp gives half its horizontal angle.
  if (scene->mNumCameras > 0 && scene->mCameras && scene->mCameras[0] && scene->mRootNode) {
    const aiCamera& cam = *scene->mCameras[0];
    if (const aiNode* node = scene->mRootNode->FindNode(cam.mName)) {
      aiMatrix4x4 world;
      for (int up = 0; node && up < 256; node = node->mParent, ++up) world = node->mTransformation * world;
      const Vec3 eye = axes.metres_per_unit * z_up(world * cam.mPosition, axes.up, axes.up_negative);
      const Vec3 look = axes.metres_per_unit * z_up(world * (cam.mPosition + cam.mLookAt), axes.up, axes.up_negative);
      const double fov = 2 * double(cam.mHorizontalFOV) * 180 / std::numbers::pi;
      if (std::isfinite(eye.x + eye.y + eye.z + look.x + look.y + look.z) && length(look - eye) > 0 && std::isfinite(fov))
        out.viewpoint = Viewpoint{eye, look, std::clamp(fov, 40.0, 120.0)};
    }
  }
  return out;
}

Mesh mesh_of_scene(const ImportedScene& scene) {
  std::vector<Vec3> vertices;
  std::vector<std::vector<int>> polygons;
  std::vector<int> polygon_material;  // per polygon: the scene's material, -1 none
  bool coloured = false;
  for (const ImportedNode& n : scene.nodes) {
    const int base = int(vertices.size());
    vertices.insert(vertices.end(), n.vertices.begin(), n.vertices.end());
    for (size_t t = 0; t < n.triangles.size(); ++t) {
      polygons.push_back({base + n.triangles[t][0], base + n.triangles[t][1], base + n.triangles[t][2]});
      const int m = t < n.triangle_material.size() ? n.triangle_material[t] : -1;
      const bool known = m >= 0 && size_t(m) < scene.materials.size() && scene.materials[size_t(m)].coloured;
      polygon_material.push_back(known ? m : -1);
      coloured = coloured || known;
    }
  }
  if (polygons.empty()) throw std::runtime_error("mesh " + scene.path + " has no faces (no triangles in any node: it holds no surfaces)");
  Mesh mesh = mesh_of_polygons(scene.path, std::move(vertices), std::move(polygons));
  mesh.viewpoint = scene.viewpoint;
  if (coloured) {
    for (const ImportedMaterial& im : scene.materials) {
      Material m;
      m.name = im.name;
      m.colour = im.colour;
      m.where = {scene.path, 0, 0, "material '" + im.name + "'"};
      mesh.materials.push_back(std::move(m));
    }
    mesh.material_of.reserve(mesh.triangles.size());
    for (int p : mesh.polygon_of) mesh.material_of.push_back(polygon_material[size_t(p)]);
  }
  return mesh;
}

Mesh load_assimp_mesh(const std::string& path, const MeshAxes& axes, std::vector<std::string>* warnings) {
  ImportOptions options;
  options.axes = axes;
  const ImportedScene scene = import_scene(path, options);
  if (warnings) warnings->insert(warnings->end(), scene.warnings.begin(), scene.warnings.end());
  return mesh_of_scene(scene);
}

}  // namespace avenues
