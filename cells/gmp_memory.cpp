// Avenues — GMP's memory exhaustion as a C++ exception (cells/gmp_memory.h).
#include "cells/gmp_memory.h"

#include <cstdlib>
#include <new>

#include <gmp.h>

namespace avenues {
namespace {

void* allocate(size_t n) {
  void* p = std::malloc(n);
  if (!p) throw std::bad_alloc();
  return p;
}

void* reallocate(void* old, size_t, size_t n) {
  // On failure the old block stays valid (and owned by its number), as realloc leaves it.
  void* p = std::realloc(old, n);
  if (!p) throw std::bad_alloc();
  return p;
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
