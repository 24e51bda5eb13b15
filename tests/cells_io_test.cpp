// Avenues — saving and loading the cell complex, exporting OBJ, drawing the plan:
// in-process checks of cells/cells_io.cpp, cells/export_obj.cpp, render/plan_drawing.cpp.

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "cells/build_cells.h"
#include "plans/mesh.h"
#include "plans/plan.h"
#include "render/plan_drawing.h"
#include "tests/avenues_run.h"
#include "tests/test_files.h"

namespace fs = std::filesystem;
using namespace avenues;

using avenues::testing::slurp;

namespace {

const std::string kPlan = std::string(AVENUES_SOURCE_DIR) + "/plans/jones-house.toml";

void spit(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

/// A stool's box with two materials of its own: its top (the polygon facing up) "seat", the
/// rest "legs".
Mesh stool_mesh() {
  Mesh m = box_mesh({0.3, 0.3, 0.45});
  m.materials.resize(2);
  m.materials[0].name = "legs";
  m.materials[0].colour = {0.2, 0.1, 0.05};
  m.materials[0].where = SourceLoc{"stool.mtl", 2, 0, "material 'legs'"};
  m.materials[1].name = "seat";
  m.materials[1].colour = {0.6, 0.05, 0.05};
  m.materials[1].where = SourceLoc{"stool.mtl", 5, 0, "material 'seat'"};
  for (const auto& t : m.triangles) {
    const Vec3 a = m.vertices[size_t(t[0])], b = m.vertices[size_t(t[1])], c = m.vertices[size_t(t[2])];
    m.material_of.push_back(cross(b - a, c - a).z > 0 ? 1 : 0);
  }
  return m;
}

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same(Vec2 a, Vec2 b) { return same(a.x, b.x) && same(a.y, b.y); }
bool same(Vec3 a, Vec3 b) { return same(a.x, b.x) && same(a.y, b.y) && same(a.z, b.z); }
bool same(const Plane& a, const Plane& b) { return same(a.n, b.n) && same(a.d, b.d); }
template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}
bool same(const SourceLoc& a, const SourceLoc& b) {
  return a.file == b.file && a.line == b.line && a.column == b.column && a.element == b.element;
}

/// Field-by-field, bit-for-bit equality of everything save_cells stores.
void expect_same(const CellComplex& a, const CellComplex& b) {
  EXPECT_EQ(a.plan_name, b.plan_name);
  ASSERT_EQ(a.storeys.size(), b.storeys.size());
  for (size_t i = 0; i < a.storeys.size(); ++i) {
    EXPECT_EQ(a.storeys[i].name, b.storeys[i].name);
    EXPECT_TRUE(same(a.storeys[i].elevation, b.storeys[i].elevation));
    EXPECT_TRUE(same(a.storeys[i].height, b.storeys[i].height));
    EXPECT_TRUE(same(a.storeys[i].slab, b.storeys[i].slab));
    EXPECT_TRUE(same(a.storeys[i].where, b.storeys[i].where));
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    EXPECT_EQ(a.materials[i].name, b.materials[i].name);
    EXPECT_TRUE(same(a.materials[i].reflectance, b.materials[i].reflectance));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(same(a.materials[i].colour[k], b.materials[i].colour[k]));
  }
  ASSERT_EQ(a.rooms.size(), b.rooms.size());
  for (size_t i = 0; i < a.rooms.size(); ++i) {
    EXPECT_EQ(a.rooms[i].name, b.rooms[i].name);
    EXPECT_EQ(a.rooms[i].storey, b.rooms[i].storey);
    EXPECT_EQ(a.rooms[i].named, b.rooms[i].named);
    EXPECT_TRUE(same(a.rooms[i].area, b.rooms[i].area));
  }
  ASSERT_EQ(a.cells.size(), b.cells.size());
  for (size_t i = 0; i < a.cells.size(); ++i) {
    const Cell &x = a.cells[i], &y = b.cells[i];
    SCOPED_TRACE("cell " + std::to_string(i));
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.room, y.room);
    EXPECT_EQ(x.storey, y.storey);
    EXPECT_TRUE(same(x.footprint, y.footprint));
    EXPECT_TRUE(same(x.z0, y.z0));
    EXPECT_TRUE(same(x.z1, y.z1));
    ASSERT_EQ(x.faces.size(), y.faces.size());
    for (size_t f = 0; f < x.faces.size(); ++f) {
      EXPECT_TRUE(same(x.faces[f].plane, y.faces[f].plane));
      EXPECT_TRUE(same(x.faces[f].poly, y.faces[f].poly));
      EXPECT_EQ(x.faces[f].portals, y.faces[f].portals);
      ASSERT_EQ(x.faces[f].opaque.size(), y.faces[f].opaque.size());
      for (size_t o = 0; o < x.faces[f].opaque.size(); ++o) {
        EXPECT_TRUE(same(x.faces[f].opaque[o].poly, y.faces[f].opaque[o].poly));
        EXPECT_EQ(x.faces[f].opaque[o].material, y.faces[f].opaque[o].material);
      }
    }
    EXPECT_EQ(x.portals, y.portals);
    ASSERT_EQ(x.lines.size(), y.lines.size());
    for (size_t l = 0; l < x.lines.size(); ++l) {
      EXPECT_EQ(x.lines[l].line, y.lines[l].line);
      EXPECT_TRUE(same(x.lines[l].t0, y.lines[l].t0));
      EXPECT_TRUE(same(x.lines[l].t1, y.lines[l].t1));
    }
    EXPECT_EQ(x.opening, y.opening);
  }
  ASSERT_EQ(a.portals.size(), b.portals.size());
  for (size_t i = 0; i < a.portals.size(); ++i) {
    const Portal &x = a.portals[i], &y = b.portals[i];
    EXPECT_EQ(x.cell[0], y.cell[0]);
    EXPECT_EQ(x.cell[1], y.cell[1]);
    EXPECT_TRUE(same(x.poly, y.poly));
    EXPECT_TRUE(same(x.plane, y.plane));
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.opening, y.opening);
  }
  ASSERT_EQ(a.lines.size(), b.lines.size());
  for (size_t i = 0; i < a.lines.size(); ++i) {
    EXPECT_TRUE(same(a.lines[i].a, b.lines[i].a));
    EXPECT_TRUE(same(a.lines[i].b, b.lines[i].b));
    EXPECT_EQ(a.lines[i].kind, b.lines[i].kind);
  }
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t i = 0; i < a.objects.size(); ++i) {
    EXPECT_EQ(a.objects[i].name, b.objects[i].name);
    EXPECT_EQ(a.objects[i].mesh, b.objects[i].mesh);
    EXPECT_TRUE(same(a.objects[i].position, b.objects[i].position));
    EXPECT_TRUE(same(a.objects[i].rotation_deg, b.objects[i].rotation_deg));
    EXPECT_TRUE(same(a.objects[i].scale, b.objects[i].scale));
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t i = 0; i < a.lights.size(); ++i) {
    EXPECT_EQ(a.lights[i].name, b.lights[i].name);
    EXPECT_TRUE(same(a.lights[i].position, b.lights[i].position));
    EXPECT_TRUE(same(a.lights[i].intensity, b.lights[i].intensity));
    EXPECT_EQ(a.lights[i].kind, b.lights[i].kind);
  }
  EXPECT_TRUE(same(a.far_box.lo, b.far_box.lo));
  EXPECT_TRUE(same(a.far_box.hi, b.far_box.hi));
  ASSERT_EQ(a.view.has_value(), b.view.has_value());
  if (a.view) {
    EXPECT_TRUE(same(a.view->eye, b.view->eye));
    EXPECT_TRUE(same(a.view->look, b.view->look));
    EXPECT_TRUE(same(a.view->fov_deg, b.view->fov_deg));
  }
  ASSERT_EQ(a.timings.size(), b.timings.size());
  for (size_t i = 0; i < a.timings.size(); ++i) EXPECT_EQ(a.timings[i].stage, b.timings[i].stage);
  ASSERT_EQ(a.solids.size(), b.solids.size());
  for (size_t i = 0; i < a.solids.size(); ++i) {
    EXPECT_TRUE(same(a.solids[i].quad, b.solids[i].quad));
    EXPECT_EQ(a.solids[i].what, b.solids[i].what);
  }
}

class CellsIo : public avenues::testing::AvenuesRun {
 protected:
  static void SetUpTestSuite() {
    complex_ = new CellComplex(build_cells(read_plan(kPlan)));
  }
  static void TearDownTestSuite() {
    delete complex_;
    complex_ = nullptr;
  }
  /// load_cells must throw std::runtime_error naming the file.
  void expect_rejected(const std::string& bytes, const std::string& why) {
    const fs::path p = dir() / "bad.cells";
    spit(p, bytes);
    try {
      (void)load_cells(p.string());
      ADD_FAILURE() << why << ": loaded a bad file";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << why << ": " << e.what();
    }
  }

  static CellComplex* complex_;
};
CellComplex* CellsIo::complex_ = nullptr;

}  // namespace

TEST_F(CellsIo, RoundTripKeepsEveryField) {
  const fs::path p = dir() / "house.cells";
  save_cells(*complex_, p.string());
  CellComplex loaded = load_cells(p.string());
  expect_same(*complex_, loaded);
  // Saving what was loaded gives the same bytes.
  const fs::path q = dir() / "again.cells";
  save_cells(loaded, q.string());
  EXPECT_EQ(slurp(p), slurp(q));
}

// What a plan from elsewhere carries: furniture as boxes of a size, furniture with its own
// model (a Sweet Home piece's), an ambient light. All of it survives saving and loading.
TEST_F(CellsIo, BoxesModelsAndAmbientLightSurvive) {
  Plan plan = read_plan(kPlan);
  Object boxed;
  boxed.name = "crate";
  boxed.box = {0.6, 0.4, 0.5};
  boxed.position = {2, 2, 0};
  Object modelled = boxed;
  modelled.name = "stool";
  modelled.position = {2.5, 3, 0};
  modelled.model = std::make_shared<const Mesh>(stool_mesh());
  plan.objects = {boxed, modelled};
  Light ambient;
  ambient.name = "sky light";
  ambient.kind = LightKind::Ambient;
  ambient.intensity = 0.2;
  plan.lights.push_back(ambient);
  const CellComplex c = build_cells(plan);
  const fs::path p = dir() / "furnished.cells";
  save_cells(c, p.string());
  const CellComplex loaded = load_cells(p.string());
  expect_same(c, loaded);
  ASSERT_EQ(loaded.objects.size(), 2u);
  EXPECT_TRUE(same(loaded.objects[0].box, boxed.box));
  EXPECT_FALSE(loaded.objects[0].model);
  ASSERT_TRUE(loaded.objects[1].model);
  const Mesh& m = *loaded.objects[1].model;
  EXPECT_EQ(m.vertices, modelled.model->vertices);
  EXPECT_EQ(m.triangles, modelled.model->triangles);
  EXPECT_EQ(m.polygon_of, modelled.model->polygon_of);
  EXPECT_EQ(m.corner_normals.size(), 3 * m.triangles.size());
  EXPECT_TRUE(m.closed);
  // Its own materials (a Sweet Home model's MTL colours), triangle by triangle.
  ASSERT_EQ(m.materials.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(m.materials[k].name, modelled.model->materials[k].name);
    EXPECT_EQ(m.materials[k].colour, modelled.model->materials[k].colour);
    EXPECT_TRUE(same(m.materials[k].where, modelled.model->materials[k].where));
  }
  EXPECT_EQ(m.material_of, modelled.model->material_of);
  EXPECT_EQ(mesh_key(loaded.objects[1]), mesh_key(modelled));
  EXPECT_EQ(loaded.lights.back().kind, LightKind::Ambient);
}

// A file of version 4 (before models kept their materials) still loads: its models have
// none. Made from a version-5 file by taking out the model's two empty material counts and
// writing the header again (payload size, FNV-1a checksum, version).
TEST_F(CellsIo, VersionFourFilesWithModelsStillLoad) {
  Plan plan = read_plan(kPlan);
  Object modelled;
  modelled.name = "stool";
  modelled.box = {0.3, 0.3, 0.45};
  modelled.position = {2.5, 3, 0};
  Mesh box = box_mesh(modelled.box);
  box.path = "the stool's model";
  modelled.model = std::make_shared<const Mesh>(box);
  plan.objects = {modelled};
  const CellComplex c = build_cells(plan);
  const fs::path p = path("v6.cells");
  save_cells(c, p.string());
  std::string bytes = slurp(p);
  // The model: its path, vertices (24 bytes each), triangles (16 each), closed, boundary edges.
  const size_t path_at = bytes.find(box.path);
  ASSERT_NE(path_at, std::string::npos);
  const size_t counts_at = path_at + box.path.size() + 4 + 24 * box.vertices.size() + 4 + 16 * box.triangles.size() + 1 + 4;
  // After them, what versions 5 and 6 added: no materials, no triangle materials, no
  // polygon lights (three counts).
  ASSERT_EQ(bytes.substr(counts_at, 12), std::string(12, '\0'));
  bytes.erase(counts_at, 12);
  auto put_u32 = [&](size_t at, uint32_t v) { for (int k = 0; k < 4; ++k) bytes[at + size_t(k)] = char(v >> (8 * k)); };
  auto put_u64 = [&](size_t at, uint64_t v) { for (int k = 0; k < 8; ++k) bytes[at + size_t(k)] = char(v >> (8 * k)); };
  const std::string payload = bytes.substr(32);
  uint64_t h = 0xcbf29ce484222325ull;
  size_t i = 0;
  for (; i + 8 <= payload.size(); i += 8) {
    uint64_t word = 0;
    for (int k = 0; k < 8; ++k) word |= uint64_t(static_cast<unsigned char>(payload[i + size_t(k)])) << (8 * k);
    h = (h ^ word) * 0x100000001b3ull;
  }
  for (; i < payload.size(); ++i) h = (h ^ static_cast<unsigned char>(payload[i])) * 0x100000001b3ull;
  put_u32(8, 4);
  put_u64(16, payload.size());
  put_u64(24, h);
  const fs::path old = path("v4.cells");
  spit(old, bytes);
  const CellComplex loaded = load_cells(old.string());
  ASSERT_EQ(loaded.objects.size(), 1u);
  ASSERT_TRUE(loaded.objects[0].model);
  EXPECT_EQ(loaded.objects[0].model->triangles, box.triangles);
  EXPECT_TRUE(loaded.objects[0].model->materials.empty());
  EXPECT_TRUE(loaded.objects[0].model->material_of.empty());
}

// Seams (CellComplex::close_seams) are closed where cells are made, and a file of version 7
// on is written so: it loads as it is. A file of version 6, written before seams were
// closed, has them closed when it loads. Made here by opening a seam of a built complex
// (taking out a corner that lies inside an edge) and saving it as both versions.
TEST_F(CellsIo, FilesWrittenBeforeSeamsWereClosedHaveThemClosedOnLoading) {
  CellComplex c = build_cells(read_plan(kPlan));
  OpaquePoly* opened = nullptr;
  size_t corner = 0;
  for (Cell& cell : c.cells)
    for (Face& face : cell.faces)
      for (OpaquePoly& piece : face.opaque)
        for (size_t i = 0; !opened && i < piece.poly.size(); ++i) {
          const size_t m = piece.poly.size();
          const Vec3 a = piece.poly[(i + m - 1) % m], v = piece.poly[i], b = piece.poly[(i + 1) % m];
          if (m > 3 && length(cross(v - a, b - a)) < 1e-12 && dot(v - a, b - v) > 0) opened = &piece, corner = i;
        }
  ASSERT_NE(opened, nullptr) << "no piece has a corner inside an edge: the plan has no T-junction";
  const std::vector<Vec3> closed = opened->poly;
  opened->poly.erase(opened->poly.begin() + std::ptrdiff_t(corner));
  const std::vector<Vec3> open = opened->poly;
  const fs::path current = path("v8.cells"), p6 = path("v6.cells");
  save_cells(c, current.string());
  std::string bytes = slurp(current);
  ASSERT_EQ(bytes[8], 8);
  bytes[8] = 6;  // the version; the checksum covers the payload only
  spit(p6, bytes);
  auto piece_like = [](const CellComplex& x, const std::vector<Vec3>& poly) {
    for (const Cell& cell : x.cells)
      for (const Face& face : cell.faces)
        for (const OpaquePoly& piece : face.opaque)
          if (piece.poly == poly) return true;
    return false;
  };
  EXPECT_TRUE(piece_like(load_cells(current.string()), open));
  EXPECT_TRUE(piece_like(load_cells(p6.string()), closed));
}

TEST_F(CellsIo, LoadedComplexLocatesLikeTheBuiltOne) {
  const fs::path p = dir() / "house.cells";
  save_cells(*complex_, p.string());
  CellComplex loaded = load_cells(p.string());
  for (size_t i = 0; i < complex_->cells.size(); i += 1 + complex_->cells.size() / 50) {
    const Cell& cell = complex_->cells[i];
    Vec2 m;
    for (Vec2 q : cell.footprint) m = m + q;
    m = (1.0 / static_cast<double>(cell.footprint.size())) * m;
    Vec3 at{m.x, m.y, 0.5 * (cell.z0 + cell.z1)};
    Location a = complex_->locate(at), b = loaded.locate(at);
    EXPECT_EQ(a.what, b.what) << "cell " << i;
    EXPECT_EQ(a.cell, b.cell) << "cell " << i;
  }
}

TEST_F(CellsIo, TruncatedFilesAreRejected) {
  const fs::path p = dir() / "house.cells";
  save_cells(*complex_, p.string());
  const std::string bytes = slurp(p);
  ASSERT_GT(bytes.size(), 64u);
  for (size_t n = 0; n < bytes.size(); n += (n < 256 ? 1 : 1 + bytes.size() / 97))
    expect_rejected(bytes.substr(0, n), "truncated to " + std::to_string(n) + " bytes");
  expect_rejected(bytes + std::string("x"), "one byte too many");
}

TEST_F(CellsIo, CorruptFilesAreRejected) {
  const fs::path p = dir() / "house.cells";
  save_cells(*complex_, p.string());
  const std::string bytes = slurp(p);
  for (size_t at = 0; at < bytes.size(); at += 1 + bytes.size() / 61) {
    std::string bad = bytes;
    bad[at] = static_cast<char>(bad[at] ^ 0x24);
    expect_rejected(bad, "byte " + std::to_string(at) + " flipped");
  }
  std::string version = bytes;
  version[8] = 99;
  expect_rejected(version, "a future version");
  expect_rejected("", "an empty file");
  expect_rejected("# not cells\n", "a text file");
  // A huge count in an otherwise valid header must not allocate: the size check and
  // checksum catch it before any vector is sized.
  std::string huge = bytes.substr(0, 32) + std::string("\xff\xff\xff\xff", 4);
  expect_rejected(huge, "a huge count");
}

TEST_F(CellsIo, MissingFileIsNamed) {
  const std::string p = (dir() / "none.cells").string();
  try {
    (void)load_cells(p);
    FAIL() << "loaded a missing file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

TEST_F(CellsIo, FailedWritesLeaveNoFile) {
  EXPECT_THROW(save_cells(*complex_, (dir() / "missing" / "x.cells").string()), std::runtime_error);
  EXPECT_THROW(export_obj(*complex_, (dir() / "missing" / "x.obj").string()), std::runtime_error);
  EXPECT_THROW(write_plan_svg(*complex_, (dir() / "missing" / "x.svg").string()), std::runtime_error);
  EXPECT_THROW(save_cells(*complex_, dir().string()), std::runtime_error);  // a directory
  EXPECT_TRUE(fs::is_empty(dir()));
}

TEST_F(CellsIo, PlanDrawingShowsEveryStoreyAndRoom) {
  std::string svg = plan_svg(*complex_);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  for (size_t s = 0; s < complex_->storeys.size(); ++s)
    EXPECT_NE(svg.find("id=\"storey-" + std::to_string(s) + "\""), std::string::npos) << "storey " << s;
  for (const RoomInfo& r : complex_->rooms)
    if (r.named) {
      EXPECT_NE(svg.find(">" + r.name + "<"), std::string::npos) << "room " << r.name;
    }
  // The same complex draws the same picture.
  EXPECT_EQ(svg, plan_svg(*complex_));
}
