// Avenues — stopping a stage before the machine runs out of memory (see memory_reserve.h).
#include "core/memory_reserve.h"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <new>

namespace avenues {
namespace {

/// MemTotal and MemAvailable [bytes] from /proc/meminfo; 0 where it does not say.
void read_meminfo(uint64_t& total, uint64_t& available) {
  total = available = 0;
  std::FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return;
  char line[256];
  while (std::fgets(line, sizeof line, f)) {
    unsigned long long kib = 0;
    if (std::sscanf(line, "MemTotal: %llu kB", &kib) == 1) total = uint64_t(kib) * 1024;
    else if (std::sscanf(line, "MemAvailable: %llu kB", &kib) == 1) available = uint64_t(kib) * 1024;
  }
  std::fclose(f);
}

}  // namespace

uint64_t memory_reserve() {
  static const uint64_t reserve = [] {
    uint64_t total = 0, available = 0;
    read_meminfo(total, available);
    const uint64_t floor = uint64_t(512) << 20;
    return total / 20 > floor ? total / 20 : floor;
  }();
  return reserve;
}

void check_memory_reserve() {
  static std::atomic<int64_t> next_ns{0};
  const int64_t now = std::chrono::duration_cast<std::chrono::nanoseconds>(
                          std::chrono::steady_clock::now().time_since_epoch())
                          .count();
  int64_t due = next_ns.load(std::memory_order_relaxed);
  if (now < due || !next_ns.compare_exchange_strong(due, now + 20'000'000)) return;
  uint64_t total = 0, available = 0;
  read_meminfo(total, available);
  if (total > 0 && available > 0 && available < memory_reserve()) throw std::bad_alloc();
}

}  // namespace avenues
