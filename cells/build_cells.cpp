// Avenues — build_cells: the pipeline of passes (see build_cells.h).
#include "cells/build_cells.h"

#include <optional>

#include "cells/passes.h"

namespace avenues {

CellComplex build_cells(const Plan& plan, const CellParams&) {
  using namespace detail;
  if (plan.walls.empty()) throw PlanError({plan.source, 0, 0, ""}, "the plan has no walls");
  if (plan.storeys.empty()) throw PlanError({plan.source, 0, 0, ""}, "the plan has no storeys");
  CellComplex out;
  out.plan_name = plan.name;
  out.storeys = plan.storeys;
  out.materials = plan.materials;
  out.objects = plan.objects;
  out.lights = plan.lights;
  out.view = plan.view;
  out.warnings = plan.warnings;

  Outline outline;
  {
    ScopedStageTimer t(out.timings, "outline");
    outline = make_outline(plan);
  }
  out.far_box.add({outline.lo.x, outline.lo.y, outline.z_bottom});
  out.far_box.add({outline.hi.x, outline.hi.y, outline.z_top});
  std::vector<Vec2> labels;
  for (const Room& r : plan.rooms) labels.push_back(r.label.value_or(outline.lo - Vec2{1, 1}));  // unlabelled: outside the box
  std::optional<ExactTriangulation> exact;
  {
    ScopedStageTimer t(out.timings, "triangulate");
    exact.emplace(outline, labels);
  }
  Classes cls;
  {
    ScopedStageTimer t(out.timings, "classify");
    cls = classify(plan, outline, exact->rounded());
    out.rooms = cls.rooms;
    out.warnings.insert(out.warnings.end(), cls.warnings.begin(), cls.warnings.end());
  }
  {
    ScopedStageTimer t(out.timings, "cut");
    cut_bands(outline, *exact, cls);
  }
  const Triangulation& tri = exact->rounded();
  Layout layout;
  {
    ScopedStageTimer t(out.timings, "merge+extrude");
    layout = extrude(plan, outline, tri, cls, out);
  }
  {
    ScopedStageTimer t(out.timings, "lines");
    real_lines(outline, tri, cls, layout, out);
  }
  // Solids, for naming what a point is inside; then the spatial index.
  for (const Region& r : outline.regions) {
    if (r.sheet) continue;
    const Wall& w = plan.walls[size_t(r.wall)];
    const Storey& s = plan.storeys[size_t(r.storey)];
    std::string what = "wall '" + w.name + "'";
    if (w.where.line > 0) what += " (" + w.where.file + ":" + std::to_string(w.where.line) + ")";
    out.solids.push_back({r.poly, s.elevation, s.elevation + s.height, what});
  }
  {
    ScopedStageTimer t(out.timings, "seams");
    out.close_seams();
  }
  {
    ScopedStageTimer t(out.timings, "index");
    out.index();
  }
  check_complex(out, "'" + plan.name + "'");
  return out;
}

}  // namespace avenues
