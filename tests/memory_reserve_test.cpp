// core/memory_reserve.h: the reserve a stage leaves the machine, and that asking costs a
// stage nothing while memory is plentiful. (The refusal itself is seen end to end: a soup
// that outgrows the machine ends with "out of memory while decomposing FILE", exit 2.)
#include <gtest/gtest.h>

#include <cstdio>
#include <new>
#include <string>

#include "core/memory_reserve.h"

namespace avenues {
namespace {

unsigned long long meminfo_kib(const char* key) {
  std::FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return 0;
  char line[256];
  unsigned long long kib = 0;
  const std::string prefix = std::string(key) + ": %llu kB";
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, prefix.c_str(), &kib) == 1) break;
  std::fclose(f);
  return kib;
}

TEST(MemoryReserve, IsAtLeastHalfAGibibyteAndAtMostATwentiethOfALargeMachine) {
  const unsigned long long total = meminfo_kib("MemTotal") * 1024;
  if (total == 0) GTEST_SKIP() << "no /proc/meminfo";
  EXPECT_GE(memory_reserve(), 512ull << 20);
  if (total / 20 > (512ull << 20)) {
    EXPECT_EQ(memory_reserve(), total / 20);
  }
}

TEST(MemoryReserve, AskingWhilePlentyIsFreeNeverThrows) {
  const unsigned long long available = meminfo_kib("MemAvailable") * 1024;
  if (available < 2 * memory_reserve()) GTEST_SKIP() << "the machine is short of memory now";
  for (int i = 0; i < 100000; ++i) ASSERT_NO_THROW(check_memory_reserve());
}

}  // namespace
}  // namespace avenues
