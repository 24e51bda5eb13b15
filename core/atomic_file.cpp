// Avenues — writing an output file all at once or not at all (core/atomic_file.h).
#include "core/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

namespace avenues {

/// Writes `bytes` to `path` via a temporary file in the same directory and a rename.
/// Throws std::runtime_error naming the file on failure; the target is then untouched.
void write_file_atomically(const std::string& path, std::string_view bytes) {
  namespace fs = std::filesystem;
  auto fail = [&](const std::string& what, int err) {
    throw std::runtime_error("cannot write " + path + ": " + what +
                             (err ? std::string(": ") + std::strerror(err) : std::string()));
  };
  if (path.empty()) fail("empty file name", 0);
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) fail("is a directory", 0);
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  std::string name = ".";  // built by appending: GCC 12 misreports "." + std::string&& (-Wrestrict)
  name += target.filename().string();
  name += ".tmp-XXXXXX";
  std::string tmpl = (dir / name).string();
  int fd = ::mkstemp(tmpl.data());
  if (fd < 0) fail("cannot create a temporary file in " + dir.string(), errno);
  const char* p = bytes.data();
  size_t left = bytes.size();
  while (left > 0) {
    ssize_t n = ::write(fd, p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      int err = errno;
      ::close(fd);
      ::unlink(tmpl.c_str());
      fail("write failed", err);
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
  // mkstemp creates 0600: keep the mode of the file being replaced, else rw-r--r--.
  struct stat old {};
  ::fchmod(fd, ::stat(path.c_str(), &old) == 0 ? (old.st_mode & 07777) : 0644);
  if (::close(fd) != 0) {
    int err = errno;
    ::unlink(tmpl.c_str());
    fail("close failed", err);
  }
  if (::rename(tmpl.c_str(), path.c_str()) != 0) {
    int err = errno;
    ::unlink(tmpl.c_str());
    fail("rename failed", err);
  }
}

}  // namespace avenues
