// Avenues — writing an output file all at once or not at all.
//
// Every file Avenues writes (saved cells, OBJ, SVG, generated plans) goes through
// write_file_atomically(): the bytes go to a temporary file in the same directory,
// which is renamed over the target only once it is complete. A failure (a full disk,
// a missing directory, an exception while producing the bytes) never leaves a partial
// output file behind, and neither does SIGINT, SIGTERM or SIGHUP: the temporary files
// still pending are removed before the process dies of the signal (SIGKILL cannot be
// caught: it leaves the temporary file, never a partial target). Only a regular file or
// nothing is written over: a device, FIFO, socket or directory of that name is an error.
// Part of core/, below every other module.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace avenues {

/// Writes `bytes` to `path` via a temporary file in the same directory and a rename.
/// Throws std::runtime_error naming the file on failure (an empty name, a target that
/// exists and is not a regular file, a failed write); the target is then untouched.
void write_file_atomically(const std::string& path, std::string_view bytes);

/// Writes several files all or none: each (path, bytes) goes to a temporary file beside its
/// target, and only when every one is complete are they renamed over their targets. Throws
/// std::runtime_error naming the file on failure (a missing directory, a full disk, two
/// entries of one path); every target is then untouched, unless a rename itself fails
/// (something not a regular file put in a target's place meanwhile) after others were made.
void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files);

/// Throws std::runtime_error naming `path` when a file cannot be written there at all: an
/// empty name, or something other than a regular file (a directory, a device such as
/// /dev/null, a FIFO, a socket) already there. A command checks its outputs with this
/// before spending time on them.
void check_output_path(const std::string& path);

/// Throws std::runtime_error naming the second of two `paths` that name one file
/// ("./a.svg" and "a.svg", or through a link to its folder); empty ones are skipped. A
/// command writing several files checks them all (its outputs, its stats) before the work.
void check_named_once(const std::vector<std::string>& paths);

/// A temporary file beside a target, removed when the process is stopped by SIGINT,
/// SIGTERM or SIGHUP while it exists (a fixed-size registry of pending paths and an
/// async-signal-safe handler that unlinks them, then dies of the signal as it would have).
/// write_file_atomically() uses it; so can a writer that streams its output.
class PendingTempFile {
 public:
  /// Creates ".NAME.tmp-XXXXXX" beside `target` (mode 0600). Throws std::runtime_error
  /// naming `target` when it cannot.
  explicit PendingTempFile(const std::string& target);
  /// Removes the temporary file unless it was committed.
  ~PendingTempFile();
  PendingTempFile(const PendingTempFile&) = delete;
  PendingTempFile& operator=(const PendingTempFile&) = delete;

  int fd() const { return fd_; }
  const std::string& path() const { return path_; }
  /// Closes the file and renames it over the target (mode: the replaced file's, else
  /// rw-r--r--). Throws std::runtime_error naming the target; the temporary is then removed.
  void commit();

 private:
  std::string target_, path_;
  int fd_ = -1;
  int slot_ = -1;  ///< in the signal registry; -1: not registered (registry full)
  bool committed_ = false;
};

}  // namespace avenues
