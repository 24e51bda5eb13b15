// Avenues — synthetic plans for scaling tests and benchmarks.
#pragma once

#include <string>

namespace avenues {

/// Plan TOML text for one office floor of `rows` × `cols` rooms (each ≥ 1).
///
/// Rooms are 4 m × 4 m (wall centre to centre) and named "r<row>_<col>", row 0 at the
/// south, column 0 at the west. Rooms face double-loaded corridors 2 m wide running
/// east–west ("corridor <k>", between room rows 2k and 2k+1); a spine corridor
/// ("spine", 2 m wide) along the west side joins every corridor through a door, and
/// an exterior door on the south opens the spine to the outside. Each room has one
/// door onto its corridor, and rooms on the outer walls have windows. Walls are
/// 0.15 m thick, one storey of the default 2.5 m.
///
/// Walls are long where they can be: the perimeter is one closed wall, every corridor
/// side is one wall with a door per room, and a partition separates two neighbouring
/// rooms or two back-to-back pairs of rooms; so 100 × 100 rooms take 5 200 walls and
/// about a megabyte of text (parsed in ~0.2 s).
/// Throws std::invalid_argument if rows or cols is < 1 or > 10 000.
std::string generate_office_toml(int rows, int cols);

}  // namespace avenues
