// Avenues — what a file's name says (core/file_name.h).
#include "core/file_name.h"

#include <cctype>
#include <filesystem>

namespace avenues {

std::string ascii_lower(std::string s) {
  for (char& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}

std::string lower_extension(const std::string& path) {
  return ascii_lower(std::filesystem::path(path).extension().string());
}

}  // namespace avenues
