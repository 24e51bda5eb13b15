// Avenues — the papers' table: the papers' scenes (render/scenes.h) rendered by the
// scanline engine at 512 × 512, our counts and times beside the figures the papers give.
#pragma once

#include <string>
#include <vector>

#include "render/halftone.h"
#include "render/scenes.h"

namespace avenues {

/// One row of the papers' table: our render of a scene beside the paper's figures.
struct PaperBenchRow {
  std::string scene;
  long polygons = 0, edges = 0;  ///< the scene's polygons and polygon edges (Bouknight counts them per polygon)
  double our_ms = 0;             ///< [ms] median render time (polygons to picture)
  RenderStats stats;             ///< of one render
  double paper_seconds = -1;
  std::string paper_machine, paper_figures;
};

/// Renders every scene at 512 × 512 as Bouknight did: grey, flat shading (his Appendix 3),
/// no back faces removed, `repeats` times (median time), on `threads` threads (0: all).
std::vector<PaperBenchRow> bench_papers(int threads = 0, int repeats = 5);
/// The rows as a Markdown table, our figures beside the papers'.
std::string papers_table(const std::vector<PaperBenchRow>& rows);

}  // namespace avenues
