// Avenues — the main job: what `avenues [PLAN]` does with no subcommand.
//
// Today it is the offline job: decompose the plan, print the summary, draw the plan.
// The walkthrough window arrives with a later issue; it will slot in as
// run_walkthrough(), with run_offline() kept as the fallback when no display can be
// opened (CI, ssh), so run_main_job() stays a small dispatcher.
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "app/commands.h"
#include "render/plan_drawing.h"

namespace avenues::app {
namespace fs = std::filesystem;

namespace {

/// The job without a window: summary on stdout, drawings in the output directory.
int run_offline(const LoadedPlan& plan, const MainJobOptions& opt) {
  std::error_code ec;
  fs::create_directories(opt.out_dir, ec);
  if (ec) throw std::runtime_error("cannot create the output directory " + opt.out_dir + ": " + ec.message());
  const std::string svg = (fs::path(opt.out_dir) / (plan.stem + "-plan.svg")).string();
  write_plan_svg(plan.complex, svg);

  print_summary(std::cout, plan);
  std::cout << "\nplan drawing: " << svg << "\n";
  std::cout << "(open it in a web browser; `avenues --help` lists what else avenues can do)\n";
  return 0;
}

}  // namespace

int run_main_job(const MainJobOptions& opt) {
  LoadedPlan plan = load_plan_source(opt.plan);
  return run_offline(plan, opt);
}

}  // namespace avenues::app
