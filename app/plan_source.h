// Avenues — where the executable's complex comes from.
//
// PLAN on the command line is a plan (.toml: read and decomposed), a saved complex
// (.cells: loaded), or a plan from elsewhere (docs/PLAN_FORMAT.md, "Plans from
// elsewhere"): a Doom map FILE.wad:MAP01, a Sweet Home 3D home (.sh3d, Home.xml), an IFC
// building (.ifc), a mesh as a whole scene (.off .obj .ply .stl, and every format Assimp
// reads: .gltf .glb .dae .fbx .3ds ...), a Crow object (.crow), a DXF drawing (.dxf) or
// floor-plan annotations (.txt, Raster-to-Vector's format). None means the bundled
// default plan, plans/jones-house.toml.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "cells/cell_complex.h"
#include "plans/formats/file_format.h"

namespace avenues::app {

struct LoadedPlan {
  CellComplex complex;
  std::string path;                ///< the file it came from
  std::string stem;                ///< its name without directory and extension
  FileFormat format = FileFormat::Toml;  ///< what the file was read as (by content, else extension)
  std::vector<StageTime> stages;   ///< what this run spent, per stage
  std::vector<std::pair<Vec2, Vec2>> drawing;  ///< [m] a 2D drawing's own lines (DXF), for the plan drawing
  double seconds() const;          ///< total of stages
};

/// How a plan from elsewhere is to be understood (--scale, --layers, --unit, --up,
/// --storey-height) and whether to save what was understood (--save-plan).
struct ImportOptions {
  double scale = 0;           ///< [m per pixel] floor-plan annotations; 0: the reader's default
  std::string layers;         ///< DXF: "walls=A,B;doors=C;windows=D"
  /// The file's length unit where it does not say ("m", "cm", "mm", "in", "ft"; "" the
  /// reader's default): a DXF drawing's (over its $INSUNITS), a mesh scene's in a format
  /// without one (OBJ, PLY, STL, OFF).
  std::string unit;
  std::string up;             ///< mesh scenes in a format without one: the up axis, "x", "y" or "z" ("" z)
  double storey_height = 2.7; ///< [m] of the one storey of a 2D drawing
  std::string save_plan;      ///< write the Plan read to this TOML file ("" none)
  /// `up` and `unit` as a mesh file's axes (unset where they are "").
  MeshAxes mesh_axes() const;
};

/// PLAN taken apart: the file, the map inside it (a WAD's), and its format (by content
/// where the file says, else by extension: plans/formats/file_format.h).
struct PlanSpec {
  std::string file;
  std::string map;   ///< "MAP01" of "doom2.wad:MAP01"; "" for the first map
  FileFormat format = FileFormat::Toml;
  /// A Model told by its content alone: the reader that knows it, as messages name it
  /// ("Assimp's Discreet 3DS Importer", "Avenues' VRML97 reader"; "" otherwise).
  /// Such a guess can be wrong (some importers look only for a keyword in the first lines),
  /// so what it cannot read is reported as a file Avenues does not know, with its reason.
  std::string content_reader;
};
PlanSpec parse_plan_spec(const std::string& plan);

/// The bundled default plan: AVENUES_SOURCE_DIR/plans/jones-house.toml, else
/// <executable>/../share/avenues/plans/jones-house.toml. Throws if neither exists.
std::string default_plan_path();

/// Loads PLAN ("" = the default plan) and prints its warnings to stderr. Throws
/// PlanError for plan mistakes and std::runtime_error naming the file for anything else,
/// among them a file of a format Avenues cannot read ("FILE is a PNG image, which
/// Avenues cannot read").
LoadedPlan load_plan_source(const std::string& plan, const ImportOptions& import = {});

/// Prints what an importer, the decomposition or a mesh reader repaired, dropped or let
/// pass, as "PATH: warning: ...": the first few lines, then how many more (a real Doom
/// map may have dozens).
void print_warnings(const std::string& path, const std::vector<std::string>& warnings);

}  // namespace avenues::app
