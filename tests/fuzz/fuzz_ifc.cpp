// Fuzz target: the IFC building reader (plans/formats/ifc_building.h) — its own STEP
// scanner for the names Assimp drops (ifc_step.h), the rewriting of IFC4's face sets and
// styles for Assimp (ifc4_for_assimp.h), Assimp's STEP and IFC reader behind it, and the
// slicing of what Assimp gives into a plan. Seeded with hand-written rooms, IFC2X3 and
// IFC4 (tests/fuzz/corpus/ifc). A refusal is a PlanError naming the file; anything else
// is a finding.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fuzz_input.h"
#include "plans/formats/ifc4_for_assimp.h"
#include "plans/formats/ifc_building.h"
#include "plans/formats/ifc_step.h"

// Assimp 5.2's STEP reader leaks what it had built when it gives up on a malformed file
// (found by this target at once; its frames lie in libassimp alone). That is Debian's
// library, not a finding of ours: its leaks are suppressed, every other one still fails.
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  (void)avenues::ifc_root_names(text);
  (void)avenues::ifc4_for_assimp(text);
  bool ok = false;
  (void)avenues::decode_step_string(text, ok);
  const std::string path = avenues::fuzz::write_input(data, size, ".ifc");
  try {
    (void)avenues::read_ifc_building(path);
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
