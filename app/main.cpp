// Avenues — the `avenues` executable: the command line and nothing more (app/cli.h).
#include <execinfo.h>

#include "app/cli.h"

int main(int argc, char** argv) {
  // glibc loads libgcc_s on demand to unwind a thread that ends (pthread_exit, as the
  // thread pool's workers do when an error ends the run). Under a memory limit that load
  // can fail once memory has run out, and glibc then aborts ("libgcc_s.so.1 must be
  // installed for unwinding to work") instead of the clear out-of-memory error. backtrace()
  // loads it through the same path: done once here, while memory is still to be had.
  void* frame = nullptr;
  (void)backtrace(&frame, 1);
  return avenues::app::run_cli(argc, argv);
}
