// Avenues — `avenues cells PLAN [--json] [--svg FILE] [--save FILE.cells]`:
// decompose a plan (or load a saved complex) and say what came out.
#include <cstdio>
#include <iostream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "core/atomic_file.h"
#include "core/number_format.h"
#include "cells/build_cells.h"
#include "render/plan_drawing.h"

namespace avenues::app {
namespace {

/// Counts over the complex, shared by the text and JSON summaries.
struct Stats {
  int named_rooms = 0, unnamed_rooms = 0;
  std::map<std::string, int> cells_by_kind, portals_by_kind;
  long long opaque_faces = 0;
  int room_cells = 0;
  int max_cells = 0;
  std::string max_room;
  double cells_per_room = 0;
};

Stats count(const CellComplex& c) {
  Stats s;
  for (const RoomInfo& r : c.rooms) (r.named ? s.named_rooms : s.unnamed_rooms)++;
  // Every kind is listed, with 0 where there is none, so the keys are stable.
  for (CellKind k : {CellKind::Room, CellKind::Doorway, CellKind::Stairwell, CellKind::Outside, CellKind::Sky})
    s.cells_by_kind[to_string(k)] = 0;
  for (PortalKind k : {PortalKind::Transparent, PortalKind::Door, PortalKind::Window, PortalKind::Hatch,
                       PortalKind::Gap, PortalKind::Stairwell, PortalKind::Open})
    s.portals_by_kind[to_string(k)] = 0;
  std::vector<int> per_room(c.rooms.size(), 0);
  for (const Cell& cell : c.cells) {
    s.cells_by_kind[to_string(cell.kind)]++;
    for (const Face& f : cell.faces) s.opaque_faces += static_cast<long long>(f.opaque.size());
    if (cell.kind == CellKind::Room && cell.room >= 0 && static_cast<size_t>(cell.room) < per_room.size()) {
      ++s.room_cells;
      ++per_room[static_cast<size_t>(cell.room)];
    }
  }
  for (const Portal& p : c.portals) s.portals_by_kind[to_string(p.kind)]++;
  for (size_t i = 0; i < per_room.size(); ++i)
    if (per_room[i] > s.max_cells) {
      s.max_cells = per_room[i];
      s.max_room = c.rooms[i].name;
    }
  s.cells_per_room = c.rooms.empty() ? 0.0 : static_cast<double>(s.room_cells) / static_cast<double>(c.rooms.size());
  return s;
}

std::string by_kind(const std::map<std::string, int>& m) {
  std::string out;
  for (const auto& [kind, n] : m) {
    if (n == 0) continue;
    out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + kind;
  }
  return out.empty() ? "none" : out;
}

nlohmann::json summary_json(const LoadedPlan& plan) {
  const CellComplex& c = plan.complex;
  Stats s = count(c);
  nlohmann::json j;
  j["plan"] = c.plan_name;
  j["source"] = plan.path;
  j["storeys"] = c.storeys.size();
  j["rooms"] = c.rooms.size();
  j["named_rooms"] = s.named_rooms;
  j["unnamed_rooms"] = s.unnamed_rooms;
  j["cells"] = c.cells.size();
  j["portals"] = c.portals.size();
  j["cells_by_kind"] = s.cells_by_kind;
  j["portals_by_kind"] = s.portals_by_kind;
  j["opaque_faces"] = s.opaque_faces;
  j["lines"] = c.lines.size();
  j["cells_per_room"] = s.cells_per_room;
  nlohmann::json stages = nlohmann::json::object();
  for (const StageTime& t : plan.stages)
    stages[t.stage] = stages.value(t.stage, 0.0) + t.seconds;
  j["stages"] = stages;
  j["seconds"] = plan.seconds();
  j["warnings"] = c.warnings;
  return j;
}

}  // namespace

void print_summary(std::ostream& out, const LoadedPlan& plan) {
  const CellComplex& c = plan.complex;
  Stats s = count(c);
  out << "plan      " << (c.plan_name.empty() ? plan.stem : c.plan_name) << "  (" << plan.path << ")\n";
  out << "storeys   " << c.storeys.size();
  for (size_t i = 0; i < c.storeys.size(); ++i)
    out << (i ? ", " : ": ") << c.storeys[i].name << " at " << format_number("%.2f", c.storeys[i].elevation) << " m";
  out << "\n";
  out << "rooms     " << c.rooms.size() << " (" << s.named_rooms << " named, " << s.unnamed_rooms << " unnamed)\n";
  out << "cells     " << c.cells.size() << " (" << by_kind(s.cells_by_kind) << ")\n";
  out << "portals   " << c.portals.size() << " (" << by_kind(s.portals_by_kind) << ")\n";
  out << "opaque    " << s.opaque_faces << " faces\n";
  out << "lines     " << c.lines.size() << " real lines\n";
  out << "per room  " << format_number("%.2f", s.cells_per_room) << " cells";
  if (s.max_cells > 0) out << " (most: " << s.max_cells << " in '" << s.max_room << "')";
  out << "\n";
  out << "seconds  ";
  for (const StageTime& t : plan.stages) out << " " << t.stage << " " << format_number("%.3f", t.seconds) << ",";
  out << " total " << format_number("%.3f", plan.seconds()) << "\n";
}

int run_cells(const CellsOptions& opt) {
  for (const std::string& f : {opt.save, opt.svg})
    if (!f.empty()) check_output_path(f);  // a device or FIFO there: refused before the work
  LoadedPlan plan = load_plan_source(opt.plan, opt.import);
  // Outputs are written before the summary so that a failure to write shows as an
  // error, not after a summary that looked like success.
  std::ostream& note = opt.json ? std::cerr : std::cout;
  if (!opt.save.empty()) save_cells(plan.complex, opt.save);
  if (!opt.svg.empty()) write_plan_svg(plan.complex, opt.svg, plan.drawing);
  if (opt.json) {
    std::cout << summary_json(plan).dump(2) << "\n";
  } else {
    print_summary(std::cout, plan);
  }
  if (!opt.save.empty()) note << "saved the cells to " << opt.save << "\n";
  if (!opt.svg.empty()) note << "wrote the plan drawing to " << opt.svg << "\n";
  return 0;
}

}  // namespace avenues::app
