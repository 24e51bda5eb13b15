// Fuzz target: the reader of Crow's tables (cells/crow.h): line lists (table 1a) and
// polygons (table 1b), then the mesh and the lines made of what was read. A refusal is a
// PlanError naming where; anything else is a finding.
#include <cstdint>
#include <string>

#include "cells/crow.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const avenues::CrowObject o = avenues::parse_crow(text, "fuzz.crow");
    avenues::crow_lines(o);
    if (o.table == avenues::CrowObject::Table::Polygons) avenues::crow_mesh(o);
  } catch (const avenues::PlanError&) {
  }
  return 0;
}
