// Avenues — GMP's memory exhaustion as a C++ exception.
//
// The exact kernels (CGAL's Gmpq, visibility's exact traversal) keep numbers in GMP, whose
// default allocator prints "GNU MP: Cannot allocate memory" and aborts the process when
// memory runs out. use_throwing_gmp_allocator() installs allocation functions
// (mp_set_memory_functions) that throw std::bad_alloc instead, so that exhaustion unwinds
// like any other C++ allocation and the command line reports "out of memory while
// decomposing FILE", exit status 2. GMP's manual leaves the state of a computation a
// throwing allocator abandons undefined: what it held may leak, and the numbers it was
// computing must not be used again — the command gives up the whole decomposition and
// exits, which needs neither. (The unwinding through GMP's frames relies on their unwind
// tables, which x86-64 and AArch64 code always has.)
#pragma once

namespace avenues {

/// Installs the throwing allocation functions; idempotent, call before any GMP number exists.
void use_throwing_gmp_allocator();

}  // namespace avenues
