// Fuzz target: the Sweet Home 3D reader (plans/formats/sweet_home.h), as a bare Home.xml or, when
// the input starts like a zip, as a .sh3d. A refusal is a PlanError naming the file and
// element; anything else is a finding. An entry may inflate to 1 MiB here (512 MiB in use),
// so that a seed of a few kilobytes (corpus/home/inflates-past-the-limit.sh3d) reaches the
// refusal of an entry inflating past the limit.
#include <cstdint>
#include <string>

#include "plans/formats/sweet_home.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool zip = size >= 2 && data[0] == 'P' && data[1] == 'K';
  const std::string path = avenues::fuzz::write_input(data, size, zip ? ".sh3d" : ".xml");
  try {
    avenues::HomeLimits limits;
    limits.max_entry_bytes = size_t(1) << 20;
    avenues::read_sweet_home(path, avenues::HomeEntry::Preferred, limits);
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
