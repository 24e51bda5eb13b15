// Fuzz target: the DXF plan reader (plans/formats/dxf_plan.h) with everything under it:
// dxflib's parser, the reader's blocks, polylines, splines and hatches, the closing of
// wall line ends and the CGAL arrangement of the walls. Any input must either become a
// Plan or be refused with a PlanError; anything else (another exception, a crash, a
// sanitizer report) is a finding. dxflib reads files, so each input is written to one
// scratch file of this process first.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "plans/formats/dxf_plan.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = "/tmp/avenues-fuzz-dxf-" + std::to_string(::getpid()) + ".dxf";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  try {
    avenues::read_dxf_plan(path);
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
