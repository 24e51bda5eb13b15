// Avenues — the building's opaque surfaces as a Wavefront OBJ mesh.
//
// Every opaque convex polygon of every face of every cell becomes a triangle fan.
// One group "g cell<id>" per cell (in cell order, every cell, even one without an
// opaque surface) so other tools can pick a cell out; vertices are shared within a
// cell. Coordinates are metres with +z up, exactly as in the complex (no axis swap,
// no materials file). Triangles wind counter-clockwise seen from inside their cell
// (normals point into free space). Written to a temporary file and renamed, so a
// failure leaves no partial file.
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/atomic_file.h"
#include "cells/build_cells.h"
#include "cells/cell_complex.h"

namespace avenues {
namespace {

void append_double(std::string& out, double v) {
  char buf[32];
  auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  if (ec != std::errc()) {
    out += "0";
    return;
  }
  out.append(buf, end);
}

struct VecKey {
  double x, y, z;
  bool operator==(const VecKey& o) const {
    return std::memcmp(this, &o, sizeof *this) == 0;
  }
};
struct VecKeyHash {
  size_t operator()(const VecKey& k) const {
    uint64_t h = 0xcbf29ce484222325ull;
    const auto* p = reinterpret_cast<const unsigned char*>(&k);
    for (size_t i = 0; i < sizeof k; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    return static_cast<size_t>(h);
  }
};

}  // namespace

void export_obj(const CellComplex& complex, const std::string& path) {
  std::string out;
  out.reserve(complex.cells.size() * 512 + 256);
  out += "# Avenues: opaque surfaces of plan '" + complex.plan_name + "'\n";
  out += "# metres, +z up; one group per cell, named cell<id>\n";

  size_t next_vertex = 1;  // OBJ indices are 1-based and global
  std::unordered_map<VecKey, size_t, VecKeyHash> ids;
  std::string faces;
  for (size_t c = 0; c < complex.cells.size(); ++c) {
    const Cell& cell = complex.cells[c];
    out += "g cell";
    out += std::to_string(c);
    out += '\n';
    ids.clear();
    faces.clear();
    auto vertex = [&](Vec3 p) {
      VecKey key{p.x + 0.0, p.y + 0.0, p.z + 0.0};  // + 0.0 folds -0 into +0
      auto [it, inserted] = ids.try_emplace(key, next_vertex);
      if (inserted) {
        ++next_vertex;
        out += "v ";
        append_double(out, key.x);
        out += ' ';
        append_double(out, key.y);
        out += ' ';
        append_double(out, key.z);
        out += '\n';
      }
      return it->second;
    };
    for (const Face& face : cell.faces) {
      for (const OpaquePoly& op : face.opaque) {
        if (op.poly.size() < 3) continue;
        std::vector<size_t> v;
        v.reserve(op.poly.size());
        for (Vec3 p : op.poly) v.push_back(vertex(p));
        for (size_t i = 1; i + 1 < v.size(); ++i) {
          faces += "f ";
          faces += std::to_string(v[0]);
          faces += ' ';
          faces += std::to_string(v[i]);
          faces += ' ';
          faces += std::to_string(v[i + 1]);
          faces += '\n';
        }
      }
    }
    out += faces;
  }
  write_file_atomically(path, out);
}

}  // namespace avenues
