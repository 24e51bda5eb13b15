// Fuzz target: the Java object serialization stream reader (plans/formats/java_stream.h) and
// the mapping of Sweet Home's classes onto a home tree (home_tree.h), on the bytes of a
// serialized `Home` entry. A refusal is a JavaStreamError or a PlanError naming the byte;
// anything else (a crash, a hang, memory out of proportion to the input) is a finding.
#include <cstdint>
#include <string_view>

#include "plans/formats/home_tree.h"
#include "plans/formats/java_stream.h"
#include "plans/plan.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const avenues::java::Stream s = avenues::java::Stream::parse(bytes);
    for (const avenues::java::Object& o : s.objects) {  // the accessors on whatever came out
      (void)s.field(o, "x");
      (void)s.unboxed(s.field(o, "value"));
      (void)s.annotation_objects(o);
    }
  } catch (const avenues::java::JavaStreamError&) {
  }
  try {
    avenues::home_tree_of_serialized(bytes, "Home");
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
