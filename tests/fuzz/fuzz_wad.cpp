// Fuzz target: the Doom WAD reader (plans/formats/doom_map.h). Any input must be read, repaired
// with warnings, or refused with a PlanError naming the file and lump; anything else is
// a finding. Every map the directory lists is read (at most four, to keep runs short).
#include <cstdint>
#include <string>

#include "plans/formats/doom_map.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = avenues::fuzz::write_input(data, size, ".wad");
  try {
    int n = 0;
    for (const std::string& map : avenues::doom_map_names(path)) {
      try {
        avenues::read_doom_map(path, map);
      } catch (const avenues::PlanError&) {
      }
      if (++n == 4) break;
    }
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
