// Avenues — `avenues bench accuracy`: what accuracy costs in time, measured and written up.
//
// Its studies, each a table (the first three with a plot: gnuplot, SVG) and the command that
// regenerates it, gathered in one Markdown report (docs/ACCURACY.md):
//   1. visibility kernels — float, double, filtered and exact traversals of the same views
//      (random eyes in the bundled plans, in copies of them moved to (500000, 5400000),
//      and in Freedoom maps): time per view against cells missing or extra, mask vertices
//      off by more than half a pixel, and hidden-line drawings that differ, each measured
//      against the exact kernel;
//   2. the half-tone renderer — resolution, 1, 4 or 16 samples per pixel, flat or smooth
//      shading: time against the error relative to a 64-sample reference (16 samples at
//      twice the resolution, averaged 2 × 2 in linear light);
//   3. the tessellation of curved walls — arc tolerance against decomposition time, cells
//      and the largest sagitta actually left between a wall's pieces and its circle;
//   6. the hull search's pictures — the merged search's masked half-tone against the hull
//      search's, resolved by depth, on the same views: time, and the samples that differ.
// (Sections 4 and 5 of the report are written words: what the tests of parallel views and
// of coarser furniture measured.)
// `quick` runs a small version of each (under a minute on this project's 2-core machines).
#pragma once

#include <string>

namespace avenues::app {

struct AccuracyOptions {
  bool quick = false;
  std::string report = "docs/ACCURACY.md";  ///< the Markdown report; plots go to <its directory>/accuracy/
  unsigned seed = 1971;                     ///< for the random eyes
};

/// Runs the studies and writes the report and its plots. Throws std::runtime_error
/// naming what failed (a plan that cannot be read, gnuplot missing or failing, a file that
/// cannot be written). Prints progress and where it wrote to stdout.
int run_bench_accuracy(const AccuracyOptions& options);

}  // namespace avenues::app
