// Fuzz target: the DXF plan reader (plans/formats/dxf_plan.h) with everything under it:
// dxflib's parser, the reader's blocks, polylines, splines and hatches, the closing of
// wall line ends and the CGAL arrangement of the walls. Any input must either become a
// Plan or be refused with a PlanError; anything else (another exception, a crash, a
// sanitizer report) is a finding. dxflib reads files, so each input is written to the
// process's scratch file first (fuzz_input.h).
#include <cstdint>
#include <string>

#include "plans/formats/dxf_plan.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = avenues::fuzz::write_input(data, size, ".dxf");
  try {
    avenues::read_dxf_plan(path);
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
