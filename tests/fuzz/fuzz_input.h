// Avenues — what the fuzz targets share: the input written to a file of a given
// extension (the importers read paths, and the mesh reader picks its format by the
// extension), one file per process, overwritten on every run.
#pragma once

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace avenues::fuzz {

inline std::string write_input(const uint8_t* data, size_t size, const std::string& ext) {
  const std::string path = "/tmp/avenues-fuzz-" + std::to_string(::getpid()) + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::logic_error("cannot write " + path);
  if (size > 0) std::fwrite(data, 1, size, f);
  std::fclose(f);
  return path;
}

}  // namespace avenues::fuzz
