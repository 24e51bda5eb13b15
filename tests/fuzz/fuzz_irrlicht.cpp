// Fuzz target: Irrlicht's XML scenes and meshes (plans/irrlicht_scene.h), read without
// Assimp. The input is written as .irr and read whatever its root element is (an .irrmesh
// too), from a scratch directory of its own, so a scene naming meshes beside it finds none
// but itself. A refusal is a std::runtime_error naming the file; anything else is a finding.
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_input.h"
#include "plans/irrlicht_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = avenues::fuzz::write_input(data, size, ".irr");
  try {
    (void)avenues::irrlicht_file_kind(path);
    (void)avenues::read_irrlicht(path);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find(path) == std::string::npos) __builtin_trap();  // an error that does not name the file
  }
  return 0;
}
