// Avenues — `avenues export PLAN -o FILE.obj`: the building's opaque surfaces as a
// Wavefront OBJ mesh, one group per cell.
#include <iostream>

#include "app/commands.h"
#include "core/atomic_file.h"
#include "cells/build_cells.h"

namespace avenues::app {

int run_export(const ExportOptions& opt) {
  check_output_path(opt.output);  // a device or FIFO there: refused before the work
  LoadedPlan plan = load_plan_source(opt.plan, opt.import);
  export_obj(plan.complex, opt.output);
  long long triangles = 0;
  for (const Cell& cell : plan.complex.cells)
    for (const Face& f : cell.faces)
      for (const OpaquePoly& op : f.opaque)
        if (op.poly.size() >= 3) triangles += static_cast<long long>(op.poly.size() - 2);
  std::cout << "wrote " << plan.complex.cells.size() << " cells, " << triangles << " triangles to "
            << opt.output << "\n";
  return 0;
}

}  // namespace avenues::app
