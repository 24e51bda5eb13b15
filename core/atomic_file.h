// Avenues — writing an output file all at once or not at all.
//
// Every file Avenues writes (saved cells, OBJ, SVG, generated plans) goes through
// write_file_atomically(): the bytes go to a temporary file in the same directory,
// which is renamed over the target only once it is complete. A failure (a full disk,
// a missing directory, an exception while producing the bytes) never leaves a partial
// output file behind. Part of core/, below every other module.
#pragma once

#include <string>
#include <string_view>

namespace avenues {

/// Writes `bytes` to `path` via a temporary file in the same directory and a rename.
/// Throws std::runtime_error naming the file on failure; the target is then untouched.
void write_file_atomically(const std::string& path, std::string_view bytes);

}  // namespace avenues
