// Avenues — the papers' table (see paper_bench.h).
#include "app/paper_bench.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace avenues {

std::vector<PaperBenchRow> bench_papers(int threads, int repeats) {
  HalftoneOptions options;
  options.samples = 1;
  options.shading.model = ShadingModel::Flat;
  options.colour = false;
  options.cull_back_faces = false;  // Bouknight scanned every polygon
  options.threads = threads;
  std::vector<PaperBenchRow> rows;
  for (const PaperScene& s : paper_scenes()) {
    const std::vector<Mesh> meshes{mesh_of(s)};
    PaperBenchRow row;
    row.scene = s.name;
    row.polygons = long(s.polygons.size());
    for (const auto& p : s.polygons) row.edges += long(p.size());
    std::vector<double> times;
    for (int k = 0; k < std::max(1, repeats); ++k) {
      render_meshes(meshes, {s.paint}, s.camera, options, &row.stats);
      times.push_back(row.stats.render_us / 1000);
    }
    std::sort(times.begin(), times.end());
    row.our_ms = times[times.size() / 2];
    row.paper_seconds = s.paper_seconds;
    row.paper_machine = s.paper_machine;
    row.paper_figures = s.paper_figures;
    rows.push_back(row);
  }
  return rows;
}

std::string papers_table(const std::vector<PaperBenchRow>& rows) {
  std::ostringstream o;
  o << "| scene | polygons | edges | ours [ms] | edges scanned | scanlines | intersections | spans | implicit lines "
       "| depth sorts | AL max | AL mean | paper [s] | paper's figures |\n";
  o << "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n";
  auto fixed = [](double v, int digits) {
    std::ostringstream f;
    f << std::fixed << std::setprecision(digits) << v;
    return f.str();
  };
  for (const PaperBenchRow& r : rows) {
    o << "| " << r.scene << " | " << r.polygons << " | " << r.edges << " | " << fixed(r.our_ms, 2) << " | "
      << r.stats.edges << " | " << r.stats.scanlines << " | " << r.stats.intersections << " | " << r.stats.spans << " | "
      << r.stats.implicit_lines << " | " << r.stats.depth_sorts << " | " << r.stats.active_max << " | "
      << fixed(r.stats.active_mean, 1) << " | "
      << (r.paper_seconds >= 0 ? fixed(r.paper_seconds, 1) + " (" + r.paper_machine + ")" : std::string("-"))
      << " | " << (r.paper_figures.empty() ? "-" : r.paper_figures) << " |\n";
  }
  return o.str();
}

}  // namespace avenues
