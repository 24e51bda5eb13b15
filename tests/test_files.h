// Avenues tests — files from outside, reading the files a test made, and a folder of its own.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include <gtest/gtest.h>
#include <unistd.h>

namespace avenues::testing {

/// A file from outside (AVENUES_OUTSIDE_DIR, set by the build: ../shared/outside beside the
/// project's root, README there), e.g. outside_path("ifc/duplex.ifc").
inline std::string outside_path(const std::string& name) {
  return (std::filesystem::path(AVENUES_OUTSIDE_DIR) / name).string();
}

/// A file's bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A folder of the running test's own under the system's temporary folder (named for the
/// prefix, the process and the test; made afresh), removed with everything in it when it
/// goes unless keep() was called.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix = "avenues-test") {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           (prefix + "-" + std::to_string(::getpid()) + "-" + (info ? info->name() : "none"));
    std::filesystem::remove_all(dir_);  // what a failed test of an earlier process of this id kept
    std::filesystem::create_directories(dir_);
  }
  ~TempDir() {
    std::error_code ec;
    if (!keep_) std::filesystem::remove_all(dir_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return dir_; }
  /// Writes `text` to the file `name` in the folder (making the folders it names); returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = dir_ / name;
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << text;
    return p.string();
  }
  /// Leaves the folder where it is when this goes (a failed test's, to look at).
  void keep() { keep_ = true; }

 protected:
  std::filesystem::path dir_;
  bool keep_ = false;
};

}  // namespace avenues::testing
