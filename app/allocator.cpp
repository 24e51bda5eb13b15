// Avenues — the executables' allocator: jemalloc, keeping the pages it frees.
//
// Linked into `avenues` and `avenues_bench` only (app/CMakeLists.txt, bench/CMakeLists.txt),
// it replaces glibc's malloc for the whole process, TBB's threads and CGAL's numbers
// included. Measured in docs/PERFORMANCE.md ("The allocator"): the duplex as a soup
// 12.6 -> 10.3 s, the Viking room 2.97 -> 2.50 s, the office plan drawing 76 -> 62 ms.
// Pages freed are kept for reuse, never handed back: a drawing of the office allocates
// and frees tens of megabytes each time, and handing them back (glibc's mmap threshold,
// or jemalloc's own decay, which made that drawing 104 ms) costs a page fault a page
// when they are touched again. A process's memory stays at its peak until it exits.
#include <sys/mman.h>

#include <atomic>
#include <cstddef>
#include <new>

extern "C" {
// jemalloc reads this before its first allocation; MALLOC_CONF in the environment adds to it.
// NOLINTNEXTLINE(cppcoreguidelines-avoid-non-const-global-variables): jemalloc's interface
const char* malloc_conf = "dirty_decay_ms:-1,muzzy_decay_ms:-1";
}

namespace {

// Room to unwind in. When memory runs out (an address-space limit, a full machine), the
// command reports "out of memory while decomposing FILE" once the exception has unwound;
// but unwinding frees, and jemalloc's free may need a page of its own metadata, which an
// exhausted address space refuses: jemalloc then crashes (SIGSEGV in operator delete, seen
// under `ulimit -v` in Hostile.OutOfMemoryWhileDecomposingNamesThePlan). So 2 MiB of
// address space is held from the start, unused (no access, no memory behind it), and the
// first allocation that fails gives it back before std::bad_alloc is thrown.
constexpr size_t kUnwindRoom = size_t(2) << 20;
std::atomic<void*> unwind_room{nullptr};

[[noreturn]] void out_of_memory() {
  if (void* room = unwind_room.exchange(nullptr)) munmap(room, kUnwindRoom);
  throw std::bad_alloc();
}

const bool unwind_room_held = [] {
  void* p = mmap(nullptr, kUnwindRoom, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (p != MAP_FAILED) unwind_room.store(p);
  std::set_new_handler(out_of_memory);
  return true;
}();

}  // namespace
