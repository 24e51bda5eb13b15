// Avenues — `avenues bench papers`: the papers' scenes (Bouknight 1969, Wylie 1967,
// Crow 1981) rendered at 512 × 512 by the scanline engine, our counts and times beside
// the figures the papers give (app/paper_bench.h has the table, render/scenes.h the scenes and their sources).
#include <iostream>

#include "app/commands.h"
#include "app/paper_bench.h"

namespace avenues::app {

int run_bench_papers(int threads, int repeats) {
  if (repeats < 1) throw std::runtime_error("--repeats must be at least 1");
  std::cout << papers_table(bench_papers(threads, repeats));
  return 0;
}

}  // namespace avenues::app
