// Fuzz target: the floor-plan annotation reader (plans/formats/floorplan_vectors.h). Any
// input must either become a Plan or be refused with a PlanError naming the line; anything
// else (another exception, a crash, a sanitizer report) is a finding.
#include <cstdint>
#include <string>

#include "plans/formats/floorplan_vectors.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    avenues::parse_floorplan_vectors(text, "fuzz.txt");
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
