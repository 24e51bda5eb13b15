// Avenues — stopping a stage before the machine runs out of memory.
//
// Linux lets allocations succeed past the memory there is (overcommit) and then ends a
// process with the OOM killer: no message, and other processes on the machine may go
// with it. A stage whose memory can grow without a bound the input sets in advance (the
// soup BSP on a model it slices finely) asks check_memory_reserve() as it goes, which
// throws std::bad_alloc once the memory the kernel says is available (MemAvailable in
// /proc/meminfo) falls below a reserve: the command then reports "out of memory while
// decomposing FILE", exit status 2, and the machine stays usable.
#pragma once

#include <cstdint>

namespace avenues {

/// The reserve [bytes]: 5 % of the machine's memory, at least 512 MiB.
uint64_t memory_reserve();

/// Throws std::bad_alloc when less than memory_reserve() is available. Reads /proc at most
/// once every 20 ms (from any thread), so it may be called often; without /proc it never
/// throws.
void check_memory_reserve();

}  // namespace avenues
