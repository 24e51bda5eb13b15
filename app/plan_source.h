// Avenues — where the executable's complex comes from.
//
// PLAN on the command line is a plan (.toml: read and decomposed) or a saved complex
// (.cells: loaded); none means the bundled default plan, plans/jones-house.toml.
#pragma once

#include <string>
#include <vector>

#include "cells/cell_complex.h"

namespace avenues::app {

struct LoadedPlan {
  CellComplex complex;
  std::string path;                ///< the file it came from
  std::string stem;                ///< its name without directory and extension
  std::vector<StageTime> stages;   ///< what this run spent, per stage
  double seconds() const;          ///< total of stages
};

/// The bundled default plan: AVENUES_SOURCE_DIR/plans/jones-house.toml, else
/// <executable>/../share/avenues/plans/jones-house.toml. Throws if neither exists.
std::string default_plan_path();

/// Loads PLAN ("" = the default plan). Throws PlanError for plan mistakes and
/// std::runtime_error naming the file for anything else.
LoadedPlan load_plan_source(const std::string& plan);

}  // namespace avenues::app
