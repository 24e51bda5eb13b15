// Avenues tests — reading the files a test made, and quoting paths for a shell.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace avenues::testing {

/// A file's bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// `s` in single quotes for sh, a quote inside it closed, escaped and reopened.
inline std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace avenues::testing
