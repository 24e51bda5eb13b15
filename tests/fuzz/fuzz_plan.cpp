// Fuzz target: the TOML plan reader. Any input must either parse or be refused with a
// PlanError naming where; anything else (another exception, a crash, a sanitizer report)
// is a finding.
#include <cstdint>
#include <string>

#include "plans/plan.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    avenues::parse_plan(text, "fuzz.toml");
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
