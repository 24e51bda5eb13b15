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
extern "C" {
// jemalloc reads this before its first allocation; MALLOC_CONF in the environment adds to it.
// NOLINTNEXTLINE(cppcoreguidelines-avoid-non-const-global-variables): jemalloc's interface
const char* malloc_conf = "dirty_decay_ms:-1,muzzy_decay_ms:-1";
}
