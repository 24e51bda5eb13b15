// Fuzz target: the mesh reader (OpenMesh behind plans/mesh.h, with Avenues' own checks
// in front of it). The format is guessed from the first bytes the way a person names a
// file (OFF, PLY, STL, else OBJ), so the seeds are plain mesh files. A refusal is a
// std::runtime_error naming the file; anything else is a finding.
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_input.h"
#include "plans/mesh.h"

namespace {
const char* extension_for(const uint8_t* data, size_t size) {
  const std::string head(reinterpret_cast<const char*>(data), size < 80 ? size : 80);
  const size_t off = head.find("OFF");
  if (off != std::string::npos && off < 8) return ".off";
  if (head.rfind("ply", 0) == 0) return ".ply";
  if (head.rfind("solid", 0) == 0) return ".stl";
  for (char ch : head)
    if (static_cast<unsigned char>(ch) < 9) return ".stl";  // binary: only STL among the four
  return ".obj";
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = avenues::fuzz::write_input(data, size, extension_for(data, size));
  try {
    avenues::load_mesh(path);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
