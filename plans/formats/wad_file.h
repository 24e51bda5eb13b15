// Avenues — a WAD file ("Where's All the Data?"): the container Doom keeps its maps in.
//
// A WAD is a 12-byte header ("IWAD" or "PWAD", the number of lumps, the offset of the
// directory), the lumps' bytes, and a directory of 16-byte entries (offset, size, an
// 8-character name), all little-endian. A map is a marker lump ("MAP01", "E1M1") followed
// by its lumps (THINGS, LINEDEFS, ...); plans/formats/doom_map.cpp reads those. This file knows
// only the container: it checks the header and directory against the file's size when
// opening, and each lump when it is read, so a damaged file is a PlanError naming the
// file and the lump, never a read past the end.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "plans/plan.h"

namespace avenues {

/// One directory entry.
struct WadLump {
  std::string name;  ///< up to 8 characters, upper case as stored, NULs trimmed
  int64_t offset = 0;  ///< [bytes] from the start of the file
  int64_t size = 0;    ///< [bytes]
};

/// A map's place in the directory: its marker and the lumps that follow it.
struct WadMap {
  std::string name;  ///< the marker's name, "MAP01"
  size_t marker = 0; ///< index of the marker in WadFile::lumps
  size_t end = 0;    ///< one past the map's last lump
};

struct WadFile {
  std::string path;
  bool iwad = false;            ///< "IWAD" (a game's main file) rather than "PWAD" (an add-on)
  int64_t file_size = 0;        ///< [bytes]
  std::vector<WadLump> lumps;   ///< in directory order

  /// The maps, in directory order: every lump followed by THINGS (Doom and Hexen
  /// formats) or TEXTMAP (UDMF), with the map lumps after it.
  std::vector<WadMap> maps() const;
  /// Index of the first lump named `name` in [from, to), or -1.
  long find(const std::string& name, size_t from, size_t to) const;
  /// The bytes of lump i. Throws PlanError naming `where` (file and map) and the lump
  /// when it lies beyond the end of the file or cannot be read.
  std::vector<uint8_t> read(size_t i, const std::string& where) const;
};

/// Opens a WAD: reads its header and directory. Throws PlanError naming the file when
/// it cannot be opened, is not a WAD, or its directory lies beyond the end of the file.
WadFile open_wad(const std::string& path);

}  // namespace avenues
