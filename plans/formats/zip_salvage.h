// Avenues — a zip archive cut short, read as far as it is whole (Sweet Home 3D's way).
//
// A .sh3d file whose writing was interrupted (a full disk, a crash) ends before the zip's
// central directory, so a zip library refuses it. Sweet Home 3D opens it all the same
// (DefaultHomeInputStream: ZipInputStream reads the entries one after another by their
// local headers, and the home is read from those that are whole; what the rest held is
// reported as damaged content). salvage_zip does that walk over the bytes, checks each
// entry's extent against its data descriptor, and writes a central directory for the
// whole ones, so the same zip library reads them (and checks their CRCs).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace avenues {

struct SalvagedZip {
  std::string bytes;               ///< the whole entries, then a central directory for them
  std::vector<std::string> kept;   ///< their names, in order
  std::string first_lost;          ///< the name of the first entry cut short ("" if none was begun)
};

/// The entries of `bytes` that are whole, walked from the first local header; nullopt when
/// not even the first one is.
std::optional<SalvagedZip> salvage_zip(std::string_view bytes);

}  // namespace avenues
