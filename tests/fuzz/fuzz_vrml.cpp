// Fuzz target: VRML97 worlds (plans/vrml_scene.h), read by Avenues' own generic parser.
// The input is written as .wrl and read whatever its first line says. A refusal is a
// std::runtime_error naming the file; anything else is a finding.
#include <cstdint>
#include <stdexcept>
#include <string>

#include "fuzz_input.h"
#include "plans/vrml_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = avenues::fuzz::write_input(data, size, ".wrl");
  try {
    (void)avenues::is_vrml(path);
    (void)avenues::read_vrml(path);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).find(path) == std::string::npos) __builtin_trap();  // an error that does not name the file
  }
  return 0;
}
