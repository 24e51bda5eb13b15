// Avenues — GMP's memory exhaustion as a C++ exception (cells/gmp_memory.h).
#include "cells/gmp_memory.h"

#include <cstdlib>
#include <new>

#include <gmp.h>

namespace avenues {
namespace {

/// As operator new does: while the allocation fails, the new-handler (the executables'
/// gives back the room they hold for unwinding, app/allocator.cpp) and once more; no handler: bad_alloc.
template <class Try>
void* as_operator_new(Try attempt) {
  for (void* p = attempt();; p = attempt()) {
    if (p) return p;
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void* allocate(size_t n) {
  return as_operator_new([n] { return std::malloc(n); });
}

void* reallocate(void* old, size_t, size_t n) {
  // On failure the old block stays valid (and owned by its number), as realloc leaves it.
  return as_operator_new([old, n] { return std::realloc(old, n); });
}

void release(void* p, size_t) { std::free(p); }

}  // namespace

void use_throwing_gmp_allocator() {
  static const bool installed = [] {
    mp_set_memory_functions(allocate, reallocate, release);
    return true;
  }();
  (void)installed;
}

}  // namespace avenues
