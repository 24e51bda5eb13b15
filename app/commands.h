// Avenues — the subcommands of the `avenues` executable, one file each.
//
// main.cpp declares the command line (CLI11) and calls one of these; each returns
// the process's exit status and may throw PlanError / std::runtime_error, which
// main() reports as "avenues: <message>" with exit status 2.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "app/plan_source.h"

namespace avenues::app {

/// `avenues cells PLAN [--json] [--svg FILE] [--save FILE.cells]`
struct CellsOptions {
  std::string plan;
  bool json = false;
  std::string svg;
  std::string save;
};
int run_cells(const CellsOptions& opt);

/// `avenues export PLAN -o FILE.obj`
struct ExportOptions {
  std::string plan;
  std::string output;
};
int run_export(const ExportOptions& opt);

/// `avenues generate office --rooms ROWSxCOLS -o FILE.toml`
struct GenerateOfficeOptions {
  std::string rooms;  ///< "ROWSxCOLS", validated by run_generate_office
  std::string output;
};
int run_generate_office(const GenerateOfficeOptions& opt);

/// No subcommand: the main job on PLAN (default: the bundled plan).
struct MainJobOptions {
  std::string plan;
  std::string out_dir = "avenues-out";
};
int run_main_job(const MainJobOptions& opt);

/// The text summary `avenues cells` and the main job print.
void print_summary(std::ostream& out, const LoadedPlan& plan);

}  // namespace avenues::app
