// Avenues — what the fuzz targets share: the input written to a file of a given
// extension (the importers read paths, and the mesh reader picks its format by the
// extension), one file per process and extension, overwritten on every run and removed
// when the process ends (libFuzzer ends a timed run with exit(), which runs destructors;
// a crash leaves its file, beside the finding).
#pragma once

#include <cstdint>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace avenues::fuzz {

/// The scratch files this process wrote, removed at its end.
struct ScratchFiles {
  std::set<std::string> paths;
  ~ScratchFiles() {
    for (const std::string& p : paths) std::remove(p.c_str());
  }
};

inline std::string write_input(const uint8_t* data, size_t size, const std::string& ext) {
  static ScratchFiles scratch;
  const std::string path = "/tmp/avenues-fuzz-" + std::to_string(::getpid()) + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::logic_error("cannot write " + path);
  scratch.paths.insert(path);
  if (size > 0) std::fwrite(data, 1, size, f);
  std::fclose(f);
  return path;
}

}  // namespace avenues::fuzz
