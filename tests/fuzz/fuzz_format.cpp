// Fuzz target: telling a file's format by its content (plans/formats/file_format.h). Any
// bytes, under any of the names a plan argument may have, give some format and never
// crash, hang or read past what they hold.
#include <cstdint>
#include <string>

#include "plans/formats/file_format.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string head(reinterpret_cast<const char*>(data), size);
  for (const char* name : {"plan", "plan.toml", "plan.off", "plan.stl", "plan.xml"})
    (void)avenues::format_name(avenues::detect_format(name, head, size));
  return 0;
}
