// Avenues — storage a thread writes and no other: a vector whose elements share no cache
// line with anything else on the heap.
//
// A thread's small arrays come from the allocator beside other small arrays, which may be
// another thread's. Two threads writing the same cache line, each its own bytes, pass the
// line back and forth at every write ("false sharing"). The scanline engine writes its
// per-polygon arrays on every row; one such pair sharing a line made a two-thread frame
// 1.6 times as slow in one process as in another with the same work. Rounded out to whole
// pairs of lines (the adjacent-line prefetcher fetches lines in pairs), nothing else lies
// in them.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace avenues {

template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr size_t kLines = 128;  ///< [bytes] two 64-byte lines
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(size_t n) {
    const size_t bytes = (n * sizeof(T) + kLines - 1) / kLines * kLines;
    return static_cast<T*>(::operator new(bytes, std::align_val_t(kLines)));
  }
  void deallocate(T* p, size_t) { ::operator delete(p, std::align_val_t(kLines)); }
  template <class U>
  bool operator==(const CacheLineAllocator<U>&) const { return true; }
};

/// A vector of a thread's own cache lines.
template <class T>
using OwnLines = std::vector<T, CacheLineAllocator<T>>;

}  // namespace avenues
