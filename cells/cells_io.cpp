// Avenues — saving and loading a decomposed cell complex.
//
// A compact little-endian binary format, so that a large plan decomposed once loads
// in a fraction of the time it takes to build:
//
//   offset  size  field
//        0     8  magic "AVCELLS\0"
//        8     4  u32 format version (kVersion)
//       12     4  u32 reserved, 0
//       16     8  u64 payload size in bytes
//       24     8  u64 checksum of the payload (FNV-1a, 64-bit, over little-endian
//                 64-bit words, then the trailing bytes one by one)
//       32     …  payload
//
// The payload holds every field of CellComplex in declaration order except the
// spatial index (bands), which load_cells() rebuilds with CellComplex::index(); the
// solids, which come from the plan and not from the cells, are saved last. A
// vector is a u32 count followed by its elements, a string a u32 byte count followed
// by its bytes, a double an IEEE-754 binary64, an enum a u8, an index an i32.
//
// Loading never trusts the file: the checksum catches corruption, every count is
// checked against the bytes that remain before anything is allocated, every index is
// checked against the array it points into, and every failure is a std::runtime_error
// naming the file.
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/atomic_file.h"
#include "cells/build_cells.h"
#include "cells/cell_complex.h"
#include "plans/mesh.h"

namespace avenues {
namespace {

constexpr char kMagic[8] = {'A', 'V', 'C', 'E', 'L', 'L', 'S', '\0'};
// 2: Cell::prism (mesh scenes' general convex cells), Face::portals_overlap;
// 3: Object::box and Object::model (Sweet Home's furniture), Light::kind;
// 4: Object::mesh relative to the folder of the .cells file (3: as the plan gave it, i.e.
//    relative to the folder avenues ran in), so that a saved complex loads from anywhere;
// 5: an Object::model's own materials (Mesh::materials, Mesh::material_of: a Sweet Home
//    model's MTL colours and modelMaterials), after its triangles;
// 6: a model's Mesh::polygon_light, after its triangles' materials; and, only when some
//    object has one, the objects' Object::cell (a large soup's detail, cut to one cell)
//    as (object, cell) pairs after everything else, so that a complex without detail is
//    laid out as in version 5;
// 7: laid out as 6, written with the opaque pieces' seams closed (CellComplex::close_seams);
//    an earlier file has them closed when it is loaded;
// 8: and, only when there are some, CellComplex::detail_solids after the objects in one
//    cell (their count written even when it is 0): each its name and its triangles (nine
//    doubles each), so that a complex without them is laid out as in version 7.
constexpr uint32_t kVersion = 8;
constexpr uint32_t kOldestVersion = 3;

/// An object's mesh file as a .cells file in `cells_dir` stores it: relative to that
/// folder (absolute when there is no relative way, e.g. another root).
std::string mesh_path_for_file(const std::string& mesh, const std::filesystem::path& cells_dir) {
  namespace fs = std::filesystem;
  if (mesh.empty()) return mesh;
  std::error_code ec;
  const fs::path abs_mesh = fs::absolute(mesh, ec).lexically_normal();
  const fs::path abs_dir = fs::absolute(cells_dir, ec).lexically_normal();
  const fs::path rel = abs_mesh.lexically_relative(abs_dir);
  return (rel.empty() ? abs_mesh : rel).generic_string();
}

/// The stored mesh path back as one to open from the current folder.
std::string mesh_path_from_file(const std::string& stored, const std::filesystem::path& cells_dir) {
  namespace fs = std::filesystem;
  const fs::path p(stored);
  if (stored.empty() || p.is_absolute()) return stored;
  return (cells_dir / p).lexically_normal().string();
}
constexpr size_t kHeaderSize = 32;

uint64_t checksum(const unsigned char* p, size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  constexpr uint64_t prime = 0x100000001b3ull;
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    uint64_t w = 0;
    for (int k = 7; k >= 0; --k) w = (w << 8) | p[i + k];
    h = (h ^ w) * prime;
  }
  for (; i < n; ++i) h = (h ^ p[i]) * prime;
  return h;
}

// ---------------------------------------------------------------------------
// Writing

class Writer {
 public:
  std::string buf;

  void u8(uint8_t v) { buf.push_back(static_cast<char>(v)); }
  void u32(uint32_t v) {
    char b[4];
    for (int i = 0; i < 4; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xff);
    buf.append(b, 4);
  }
  void u64(uint64_t v) {
    char b[8];
    for (int i = 0; i < 8; ++i) b[i] = static_cast<char>((v >> (8 * i)) & 0xff);
    buf.append(b, 8);
  }
  void i32(int32_t v) { u32(static_cast<uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<uint64_t>(v)); }
  void count(size_t n, const char* what) {
    if (n > std::numeric_limits<uint32_t>::max())
      throw std::runtime_error(std::string("too many ") + what + " to save");
    u32(static_cast<uint32_t>(n));
  }
  void str(const std::string& s) {
    count(s.size(), "bytes in a string");
    buf.append(s);
  }
  void vec2(Vec2 v) { f64(v.x); f64(v.y); }
  void vec3(Vec3 v) { f64(v.x); f64(v.y); f64(v.z); }
  void plane(const Plane& p) { vec3(p.n); f64(p.d); }
  void loc(const SourceLoc& l) { str(l.file); i32(l.line); i32(l.column); str(l.element); }
  void colour(const std::array<double, 3>& c) { for (double v : c) f64(v); }
  void poly2(const std::vector<Vec2>& p) { count(p.size(), "points"); for (Vec2 v : p) vec2(v); }
  void poly3(const std::vector<Vec3>& p) { count(p.size(), "points"); for (Vec3 v : p) vec3(v); }
  void ids(const std::vector<int32_t>& v) { count(v.size(), "indices"); for (int32_t i : v) i32(i); }
};

/// A material: the complex's, or a model's (read_material).
void write_material(Writer& w, const Material& m) {
  w.str(m.name); w.f64(m.reflectance); w.colour(m.colour); w.loc(m.where);
}

void write_complex(Writer& w, const CellComplex& c, const std::filesystem::path& cells_dir) {
  w.str(c.plan_name);

  w.count(c.storeys.size(), "storeys");
  for (const Storey& s : c.storeys) {
    w.str(s.name); w.f64(s.elevation); w.f64(s.height); w.f64(s.slab); w.loc(s.where);
  }
  w.count(c.materials.size(), "materials");
  for (const Material& m : c.materials) write_material(w, m);
  w.count(c.rooms.size(), "rooms");
  for (const RoomInfo& r : c.rooms) {
    w.str(r.name); w.i32(r.storey); w.u8(r.named ? 1 : 0); w.f64(r.area);
  }
  w.count(c.cells.size(), "cells");
  for (const Cell& cell : c.cells) {
    w.u8(static_cast<uint8_t>(cell.kind));
    w.u8(cell.prism ? 1 : 0);
    w.i32(cell.room);
    w.i32(cell.storey);
    w.poly2(cell.footprint);
    w.f64(cell.z0); w.f64(cell.z1);
    w.count(cell.faces.size(), "faces");
    for (const Face& f : cell.faces) {
      w.plane(f.plane);
      w.u8(f.portals_overlap ? 1 : 0);
      w.poly3(f.poly);
      w.ids(f.portals);
      w.count(f.opaque.size(), "opaque polygons");
      for (const OpaquePoly& o : f.opaque) { w.poly3(o.poly); w.i32(o.material); }
    }
    w.ids(cell.portals);
    w.count(cell.lines.size(), "cell lines");
    for (const CellLine& l : cell.lines) { w.i32(l.line); w.f64(l.t0); w.f64(l.t1); }
    w.i32(cell.opening);
  }
  w.count(c.portals.size(), "portals");
  for (const Portal& p : c.portals) {
    w.i32(p.cell[0]); w.i32(p.cell[1]);
    w.poly3(p.poly);
    w.plane(p.plane);
    w.u8(static_cast<uint8_t>(p.kind));
    w.i32(p.opening);
  }
  w.count(c.lines.size(), "lines");
  for (const RealLine& l : c.lines) { w.vec3(l.a); w.vec3(l.b); w.u8(static_cast<uint8_t>(l.kind)); }
  w.count(c.objects.size(), "objects");
  for (const Object& o : c.objects) {
    w.str(o.name); w.str(mesh_path_for_file(o.mesh, cells_dir)); w.i32(o.storey);
    w.vec3(o.position); w.vec3(o.rotation_deg); w.vec3(o.scale);
    w.i32(o.material); w.loc(o.where);
    w.vec3(o.box);
    // A model that came with the plan is saved with it: its vertices and triangles.
    w.u8(o.model ? 1 : 0);
    if (o.model) {
      const Mesh& m = *o.model;
      w.str(m.path);
      w.count(m.vertices.size(), "model vertices");
      for (const Vec3& v : m.vertices) w.vec3(v);
      w.count(m.triangles.size(), "model triangles");
      for (size_t t = 0; t < m.triangles.size(); ++t) {
        for (int i : m.triangles[t]) w.i32(i);
        w.i32(t < m.polygon_of.size() ? m.polygon_of[t] : int32_t(t));
      }
      w.u8(m.closed ? 1 : 0);
      w.i32(m.boundary_edges);
      w.count(m.materials.size(), "model materials");
      for (const Material& mm : m.materials) write_material(w, mm);
      w.count(m.material_of.size(), "model triangle materials");
      for (MaterialId k : m.material_of) w.i32(k);
      w.count(m.polygon_light.size(), "model polygon lights");
      for (const Vec3& v : m.polygon_light) w.vec3(v);
    }
  }
  w.count(c.lights.size(), "lights");
  for (const Light& l : c.lights) {
    w.str(l.name); w.vec3(l.position); w.f64(l.intensity); w.colour(l.colour); w.loc(l.where);
    w.u8(static_cast<uint8_t>(l.kind));
  }
  w.vec3(c.far_box.lo); w.vec3(c.far_box.hi);
  w.u8(c.view ? 1 : 0);
  if (c.view) { w.vec3(c.view->eye); w.vec3(c.view->look); w.f64(c.view->fov_deg); }
  w.count(c.timings.size(), "timings");
  for (const StageTime& t : c.timings) { w.str(t.stage); w.f64(t.seconds); }
  // Solid regions name what a point is inside; build_cells makes them from the plan
  // (wall names, source lines), so the cells alone cannot rebuild them: saved too.
  w.count(c.solids.size(), "solids");
  for (const CellComplex::SolidBox& s : c.solids) {
    w.poly2(s.quad); w.f64(s.z0); w.f64(s.z1); w.str(s.what);
  }
  size_t in_one_cell = 0;
  for (const Object& o : c.objects) in_one_cell += o.cell >= 0;
  if (in_one_cell > 0 || !c.detail_solids.empty()) {
    w.count(in_one_cell, "objects in one cell");
    for (size_t i = 0; i < c.objects.size(); ++i)
      if (c.objects[i].cell >= 0) { w.i32(int32_t(i)); w.i32(c.objects[i].cell); }
  }
  if (!c.detail_solids.empty()) {
    w.count(c.detail_solids.size(), "detail solids");
    for (const ClosedSurface& s : c.detail_solids) {
      w.str(s.name());
      w.count(s.triangles().size(), "detail solid triangles");
      for (const Triangle3& t : s.triangles())
        for (const Vec3& p : t) w.vec3(p);
    }
  }
}

// ---------------------------------------------------------------------------
// Reading

class Reader {
 public:
  Reader(const std::string& file, const unsigned char* begin, const unsigned char* end)
      : file_(file), begin_(begin), p_(begin), end_(end) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(file_ + ": corrupt cells file: " + what + " (payload byte " +
                             std::to_string(p_ - begin_) + ")");
  }
  size_t remaining() const { return static_cast<size_t>(end_ - p_); }
  bool at_end() const { return p_ == end_; }

  void need(size_t n, const char* what) {
    if (remaining() < n) fail(std::string("truncated in ") + what);
  }
  uint8_t u8(const char* what) {
    need(1, what);
    return *p_++;
  }
  uint32_t u32(const char* what) {
    need(4, what);
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | p_[i];
    p_ += 4;
    return v;
  }
  uint64_t u64(const char* what) {
    need(8, what);
    uint64_t v = 0;
    for (int i = 7; i >= 0; --i) v = (v << 8) | p_[i];
    p_ += 8;
    return v;
  }
  int32_t i32(const char* what) { return static_cast<int32_t>(u32(what)); }
  double f64(const char* what) { return std::bit_cast<double>(u64(what)); }
  double finite(const char* what) {
    double v = f64(what);
    if (!std::isfinite(v)) fail(std::string("non-finite number in ") + what);
    return v;
  }
  /// A count of elements each at least `min_bytes` long: checked against what remains
  /// before the caller allocates anything.
  size_t count(size_t min_bytes, const char* what) {
    uint32_t n = u32(what);
    if (min_bytes > 0 && n > remaining() / min_bytes)
      fail(std::string("count of ") + what + " (" + std::to_string(n) + ") exceeds the file");
    return n;
  }
  std::string str(const char* what) {
    size_t n = count(1, what);
    std::string s(reinterpret_cast<const char*>(p_), n);
    p_ += n;
    return s;
  }
  Vec2 vec2(const char* what) {
    double x = finite(what);
    double y = finite(what);
    return {x, y};
  }
  Vec3 vec3(const char* what) {
    double x = finite(what);
    double y = finite(what);
    double z = finite(what);
    return {x, y, z};
  }
  Plane plane(const char* what) {
    Plane p;
    p.n = vec3(what);
    p.d = finite(what);
    return p;
  }
  SourceLoc loc(const char* what) {
    SourceLoc l;
    l.file = str(what);
    l.line = i32(what);
    l.column = i32(what);
    l.element = str(what);
    return l;
  }
  std::array<double, 3> colour(const char* what) {
    std::array<double, 3> c{};
    for (double& v : c) v = finite(what);
    return c;
  }
  std::vector<Vec2> poly2(const char* what) {
    std::vector<Vec2> v(count(16, what));
    for (Vec2& p : v) p = vec2(what);
    return v;
  }
  std::vector<Vec3> poly3(const char* what) {
    std::vector<Vec3> v(count(24, what));
    for (Vec3& p : v) p = vec3(what);
    return v;
  }
  std::vector<int32_t> ids(const char* what) {
    std::vector<int32_t> v(count(4, what));
    for (int32_t& i : v) i = i32(what);
    return v;
  }
  template <class Enum>
  Enum kind(Enum last, const char* what) {
    uint8_t v = u8(what);
    if (v > static_cast<uint8_t>(last)) fail(std::string("unknown ") + what + " " + std::to_string(v));
    return static_cast<Enum>(v);
  }

 private:
  std::string file_;
  const unsigned char* begin_;
  const unsigned char* p_;
  const unsigned char* end_;
};

// Smallest encoded sizes, for the count checks (each a lower bound).
constexpr size_t kMinLoc = 4 + 4 + 4 + 4;
constexpr size_t kMinStorey = 4 + 3 * 8 + kMinLoc;
constexpr size_t kMinMaterial = 4 + 8 + 3 * 8 + kMinLoc;
constexpr size_t kMinRoom = 4 + 4 + 1 + 8;
constexpr size_t kMinFace = 32 + 4 + 4 + 4;
constexpr size_t kMinOpaque = 4 + 4;
constexpr size_t kMinCellLine = 4 + 8 + 8;
constexpr size_t kMinCell = 1 + 4 + 4 + 4 + 16 + 4 + 4 + 4 + 4;
constexpr size_t kMinPortal = 8 + 4 + 32 + 1 + 4;
constexpr size_t kMinLine = 48 + 1;
constexpr size_t kMinObject = 4 + 4 + 4 + 72 + 4 + kMinLoc + 24 + 1;
constexpr size_t kMinLight = 4 + 24 + 8 + 24 + kMinLoc + 1;
constexpr size_t kMinTiming = 4 + 8;
constexpr size_t kMinSolid = 4 + 16 + 4;

/// A material as write_complex writes one (the complex's, or a model's); `what` names it in errors.
Material read_material(Reader& r, const char* what) {
  Material m;
  m.name = r.str(what);
  m.reflectance = r.finite(what);
  m.colour = r.colour(what);
  m.where = r.loc(what);
  return m;
}

void read_complex(Reader& r, CellComplex& c, uint32_t version, const std::filesystem::path& cells_dir) {
  c.plan_name = r.str("plan name");

  c.storeys.resize(r.count(kMinStorey, "storeys"));
  for (Storey& s : c.storeys) {
    s.name = r.str("storey");
    s.elevation = r.finite("storey");
    s.height = r.finite("storey");
    s.slab = r.finite("storey");
    s.where = r.loc("storey");
  }
  c.materials.resize(r.count(kMinMaterial, "materials"));
  for (Material& m : c.materials) m = read_material(r, "material");
  c.rooms.resize(r.count(kMinRoom, "rooms"));
  for (RoomInfo& room : c.rooms) {
    room.name = r.str("room");
    room.storey = r.i32("room");
    room.named = r.u8("room") != 0;
    room.area = r.finite("room");
  }
  c.cells.resize(r.count(kMinCell, "cells"));
  for (Cell& cell : c.cells) {
    cell.kind = r.kind(CellKind::Sky, "cell kind");
    cell.prism = r.u8("cell") != 0;
    cell.room = r.i32("cell");
    cell.storey = r.i32("cell");
    cell.footprint = r.poly2("cell footprint");
    cell.z0 = r.finite("cell");
    cell.z1 = r.finite("cell");
    cell.faces.resize(r.count(kMinFace, "faces"));
    for (Face& f : cell.faces) {
      f.plane = r.plane("face");
      f.portals_overlap = r.u8("face") != 0;
      f.poly = r.poly3("face polygon");
      f.portals = r.ids("face portals");
      f.opaque.resize(r.count(kMinOpaque, "opaque polygons"));
      for (OpaquePoly& o : f.opaque) {
        o.poly = r.poly3("opaque polygon");
        o.material = r.i32("opaque polygon");
      }
    }
    cell.portals = r.ids("cell portals");
    cell.lines.resize(r.count(kMinCellLine, "cell lines"));
    for (CellLine& l : cell.lines) {
      l.line = r.i32("cell line");
      l.t0 = r.finite("cell line");
      l.t1 = r.finite("cell line");
    }
    cell.opening = r.i32("cell");
  }
  c.portals.resize(r.count(kMinPortal, "portals"));
  for (Portal& p : c.portals) {
    p.cell[0] = r.i32("portal");
    p.cell[1] = r.i32("portal");
    p.poly = r.poly3("portal polygon");
    p.plane = r.plane("portal");
    p.kind = r.kind(PortalKind::Open, "portal kind");
    p.opening = r.i32("portal");
  }
  c.lines.resize(r.count(kMinLine, "lines"));
  for (RealLine& l : c.lines) {
    l.a = r.vec3("line");
    l.b = r.vec3("line");
    l.kind = r.kind(LineKind::Sheet, "line kind");
  }
  c.objects.resize(r.count(kMinObject, "objects"));
  for (Object& o : c.objects) {
    o.name = r.str("object");
    o.mesh = r.str("object");
    if (version >= 4) o.mesh = mesh_path_from_file(o.mesh, cells_dir);
    o.storey = r.i32("object");
    o.position = r.vec3("object");
    o.rotation_deg = r.vec3("object");
    o.scale = r.vec3("object");
    o.material = r.i32("object");
    o.where = r.loc("object");
    o.box = r.vec3("object");
    if (r.u8("object") != 0) {
      Mesh m;
      m.path = r.str("model");
      m.vertices.resize(r.count(24, "model vertices"));
      for (Vec3& v : m.vertices) v = r.vec3("model");
      const size_t triangles = r.count(16, "model triangles");
      m.triangles.resize(triangles);
      m.polygon_of.resize(triangles);
      for (size_t t = 0; t < triangles; ++t) {
        for (int& i : m.triangles[t]) {
          i = r.i32("model");
          if (i < 0 || size_t(i) >= m.vertices.size()) r.fail("a model's triangle names a vertex it does not have");
        }
        m.polygon_of[t] = r.i32("model");
        if (m.polygon_of[t] < 0) r.fail("a model's triangle has a negative polygon number");
      }
      m.closed = r.u8("model") != 0;
      m.boundary_edges = r.i32("model");
      if (version >= 5) {
        m.materials.resize(r.count(kMinMaterial, "model materials"));
        for (Material& mm : m.materials) mm = read_material(r, "model material");
        m.material_of.resize(r.count(4, "model triangle materials"));
        if (!m.material_of.empty() && m.material_of.size() != m.triangles.size())
          r.fail("a model has materials for " + std::to_string(m.material_of.size()) + " triangles, not its " +
                 std::to_string(m.triangles.size()));
        for (MaterialId& k : m.material_of) {
          k = r.i32("model triangle material");
          if (k < -1 || k >= MaterialId(m.materials.size())) r.fail("a model's triangle names a material it does not have");
        }
      }
      if (version >= 6) {
        m.polygon_light.resize(r.count(24, "model polygon lights"));
        for (Vec3& v : m.polygon_light) v = r.vec3("model polygon light");
      }
      smooth_corner_normals(m);
      o.model = std::make_shared<const Mesh>(std::move(m));
    }
  }
  c.lights.resize(r.count(kMinLight, "lights"));
  for (Light& l : c.lights) {
    l.name = r.str("light");
    l.position = r.vec3("light");
    l.intensity = r.finite("light");
    l.colour = r.colour("light");
    l.where = r.loc("light");
    l.kind = r.kind(LightKind::Ambient, "light kind");
  }
  // An empty box is stored as ±infinity: not checked for finiteness.
  c.far_box.lo = {r.f64("far box"), r.f64("far box"), r.f64("far box")};
  c.far_box.hi = {r.f64("far box"), r.f64("far box"), r.f64("far box")};
  if (r.u8("viewpoint") != 0) {
    Viewpoint v;
    v.eye = r.vec3("viewpoint");
    v.look = r.vec3("viewpoint");
    v.fov_deg = r.finite("viewpoint");
    c.view = v;
  }
  c.timings.resize(r.count(kMinTiming, "timings"));
  for (StageTime& t : c.timings) {
    t.stage = r.str("timing");
    t.seconds = r.f64("timing");
  }
  c.solids.resize(r.count(kMinSolid, "solids"));
  for (CellComplex::SolidBox& s : c.solids) {
    s.quad = r.poly2("solid");
    s.z0 = r.finite("solid");
    s.z1 = r.finite("solid");
    s.what = r.str("solid");
  }
  if (version >= 6 && !r.at_end()) {
    const size_t n = r.count(8, "objects in one cell");
    for (size_t k = 0; k < n; ++k) {
      const int32_t i = r.i32("object in one cell"), cell = r.i32("object in one cell");
      if (i < 0 || size_t(i) >= c.objects.size()) r.fail("an object in one cell that the complex does not have");
      if (cell < 0 || size_t(cell) >= c.cells.size()) r.fail("an object names a cell the complex does not have");
      c.objects[size_t(i)].cell = cell;
    }
  }
  if (version >= 8 && !r.at_end()) {
    c.detail_solids.resize(r.count(8, "detail solids"));
    for (ClosedSurface& s : c.detail_solids) {
      std::string name = r.str("detail solid");
      std::vector<Triangle3> triangles(r.count(72, "detail solid triangles"));
      for (Triangle3& t : triangles)
        for (Vec3& p : t) p = r.vec3("detail solid");
      s = ClosedSurface(std::move(name), std::move(triangles));
    }
  }
  if (!r.at_end()) r.fail(std::to_string(r.remaining()) + " unexpected bytes after the complex");
}

/// Every index must point into its array, so that nothing downstream can read out of
/// bounds on a file that passed the checksum but was written by a broken build.
void check_indices(const CellComplex& c, Reader& r) {
  const auto ncells = static_cast<int64_t>(c.cells.size());
  const auto nportals = static_cast<int64_t>(c.portals.size());
  const auto nlines = static_cast<int64_t>(c.lines.size());
  const auto nrooms = static_cast<int64_t>(c.rooms.size());
  const auto nstoreys = static_cast<int64_t>(c.storeys.size());
  const auto nmaterials = static_cast<int64_t>(c.materials.size());
  auto in = [](int64_t i, int64_t lo, int64_t n) { return i >= lo && i < n; };
  for (const RoomInfo& room : c.rooms)
    if (!in(room.storey, 0, nstoreys)) r.fail("room '" + room.name + "' has a bad storey");
  for (size_t i = 0; i < c.cells.size(); ++i) {
    const Cell& cell = c.cells[i];
    std::string name = "cell " + std::to_string(i);
    if (!in(cell.room, -1, nrooms)) r.fail(name + " has a bad room index");
    if (!in(cell.storey, -1, nstoreys)) r.fail(name + " has a bad storey index");
    for (const Face& f : cell.faces) {
      for (PortalId p : f.portals)
        if (!in(p, 0, nportals)) r.fail(name + " has a bad portal index");
      for (const OpaquePoly& o : f.opaque)
        if (!in(o.material, -1, nmaterials)) r.fail(name + " has a bad material index");
    }
    for (PortalId p : cell.portals)
      if (!in(p, 0, nportals)) r.fail(name + " has a bad portal index");
    for (const CellLine& l : cell.lines)
      if (!in(l.line, 0, nlines)) r.fail(name + " has a bad line index");
  }
  for (size_t i = 0; i < c.portals.size(); ++i)
    for (CellId id : c.portals[i].cell)
      if (!in(id, 0, ncells)) r.fail("portal " + std::to_string(i) + " has a bad cell index");
}

/// The file's bytes, mapped read-only (much faster than reading a large file into a
/// fresh buffer); unmapped when it goes out of scope.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec))
      throw std::runtime_error(path + ": is a directory, not a cells file");
    int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw std::runtime_error(path + ": cannot open: " + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0) {
      int err = errno;
      ::close(fd);
      throw std::runtime_error(path + ": cannot read: " + std::strerror(err));
    }
    size_ = static_cast<size_t>(st.st_size);
    if (size_ > 0) {
      void* m = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
      if (m == MAP_FAILED) {
        int err = errno;
        ::close(fd);
        throw std::runtime_error(path + ": cannot read: " + std::strerror(err));
      }
      data_ = static_cast<const unsigned char*>(m);
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_) ::munmap(const_cast<unsigned char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const unsigned char* data() const { return data_; }
  size_t size() const { return size_; }

 private:
  const unsigned char* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace

std::string cells_bytes(const CellComplex& complex, const std::filesystem::path& cells_dir) {
  Writer payload;
  payload.buf.reserve(1 << 16);
  write_complex(payload, complex, cells_dir);
  const auto* data = reinterpret_cast<const unsigned char*>(payload.buf.data());

  Writer file;
  file.buf.reserve(kHeaderSize + payload.buf.size());
  file.buf.append(kMagic, sizeof kMagic);
  file.u32(kVersion);
  file.u32(0);
  file.u64(payload.buf.size());
  file.u64(checksum(data, payload.buf.size()));
  file.buf.append(payload.buf);
  return std::move(file.buf);
}

CellComplex cells_from_bytes(std::string_view bytes, const std::string& name, const std::filesystem::path& cells_dir) {
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  const size_t file_size = bytes.size();

  if (file_size < sizeof kMagic || std::memcmp(data, kMagic, sizeof kMagic) != 0)
    throw std::runtime_error(name + ": not an Avenues cells file (no AVCELLS header)");
  Reader header(name, data, data + file_size);
  header.need(kHeaderSize, "header");
  for (size_t i = 0; i < sizeof kMagic; ++i) header.u8("header");
  uint32_t version = header.u32("header");
  if (version < kOldestVersion || version > kVersion)
    throw std::runtime_error(name + ": cells file format version " + std::to_string(version) +
                             ", this avenues reads versions " + std::to_string(kOldestVersion) + " to " +
                             std::to_string(kVersion) +
                             "; rebuild it from the plan");
  header.u32("header");
  uint64_t size = header.u64("header");
  uint64_t sum = header.u64("header");
  if (size != file_size - kHeaderSize)
    throw std::runtime_error(name + ": corrupt cells file: header announces " + std::to_string(size) +
                             " bytes of cells, the file holds " + std::to_string(file_size - kHeaderSize) +
                             (size > file_size - kHeaderSize ? " (truncated?)" : ""));
  const unsigned char* payload = data + kHeaderSize;
  if (checksum(payload, size) != sum)
    throw std::runtime_error(name + ": corrupt cells file: checksum mismatch");

  Reader r(name, payload, payload + size);
  CellComplex c;
  read_complex(r, c, version, cells_dir);
  check_indices(c, r);
  if (version < 7) c.close_seams();  // written before seams were closed
  c.index();
  check_complex(c, name);
  return c;
}

void save_cells(const CellComplex& complex, const std::string& path) {
  write_file_atomically(path, cells_bytes(complex, std::filesystem::path(path).parent_path()));
}

CellComplex load_cells(const std::string& path) {
  const MappedFile file(path);
  return cells_from_bytes({reinterpret_cast<const char*>(file.data()), file.size()}, path,
                          std::filesystem::path(path).parent_path());
}

}  // namespace avenues
