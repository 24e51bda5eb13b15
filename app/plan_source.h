// Avenues — where the executable's complex comes from.
//
// PLAN on the command line is a plan (.toml: read and decomposed), a saved complex
// (.cells: loaded), or a plan from elsewhere (docs/PLAN_FORMAT.md, "Plans from
// elsewhere"): a Doom map FILE.wad:MAP01, a Sweet Home 3D home (.sh3d, Home.xml), a mesh
// as a whole scene (.off .obj .ply .stl), a Crow object (.crow), a DXF drawing (.dxf) or
// floor-plan annotations (.txt, Raster-to-Vector's format). None means the
// bundled default plan, plans/jones-house.toml.
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

enum class PlanFormat { Toml, Cells, DoomMap, SweetHome, MeshScene, Crow, FloorplanVectors, Dxf };

/// How a plan from elsewhere is to be understood (--scale, --layers, --unit,
/// --storey-height) and whether to save what was understood (--save-plan).
struct ImportOptions {
  double scale = 0;           ///< [m per pixel] floor-plan annotations; 0: the reader's default
  std::string layers;         ///< DXF: "walls=A,B;doors=C;windows=D"
  std::string unit;           ///< DXF: overrides $INSUNITS ("m", "cm", "mm", "in", "ft")
  double storey_height = 2.7; ///< [m] of the one storey of a 2D drawing
  std::string save_plan;      ///< write the Plan read to this TOML file ("" none)
};

/// PLAN taken apart: the file, the map inside it (a WAD's), and its format by extension.
struct PlanSpec {
  std::string file;
  std::string map;   ///< "MAP01" of "doom2.wad:MAP01"; "" for the first map
  PlanFormat format = PlanFormat::Toml;
};
PlanSpec parse_plan_spec(const std::string& plan);

/// The bundled default plan: AVENUES_SOURCE_DIR/plans/jones-house.toml, else
/// <executable>/../share/avenues/plans/jones-house.toml. Throws if neither exists.
std::string default_plan_path();

/// Loads PLAN ("" = the default plan) and prints its warnings to stderr. Throws
/// PlanError for plan mistakes and std::runtime_error naming the file for anything else.
LoadedPlan load_plan_source(const std::string& plan, const ImportOptions& import = {});

}  // namespace avenues::app
