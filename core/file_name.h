// Avenues — what a file's name says: its extension, compared as systems that ignore case
// do. Every reader and writer tells formats by these (and by content where the name says
// nothing: plans/formats/file_format.h). Part of core/, below every other module.
#pragma once

#include <string>

namespace avenues {

/// s in lower case (ASCII only: a file name's other bytes are left as they are).
std::string ascii_lower(std::string s);

/// The extension of `path`'s last component with its dot, in lower case ("" when none):
/// "Plan.SH3D" gives ".sh3d", "archive.tar.gz" gives ".gz", ".hidden" gives "".
std::string lower_extension(const std::string& path);

}  // namespace avenues
