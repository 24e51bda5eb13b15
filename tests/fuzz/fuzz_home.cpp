// Fuzz target: the Sweet Home 3D reader (plans/formats/sweet_home.h), as a bare Home.xml or, when
// the input starts like a zip, as a .sh3d. A refusal is a PlanError naming the file and
// element; anything else is a finding.
#include <cstdint>
#include <string>

#include "plans/formats/sweet_home.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool zip = size >= 2 && data[0] == 'P' && data[1] == 'K';
  const std::string path = avenues::fuzz::write_input(data, size, zip ? ".sh3d" : ".xml");
  try {
    avenues::read_sweet_home(path);
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
