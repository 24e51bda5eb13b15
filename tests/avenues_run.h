// Avenues tests — running programs (the real `avenues` above all) from a test, and the
// fixture that gives each test a folder of its own to run them in.
//
// A program is started by its argument vector (posix_spawnp), never through a shell:
// every argument reaches it as one string, quotes, spaces and `$(...)` included. Its
// stdin is /dev/null, its stdout and stderr are caught apart (in memory files, so that
// nothing appears in the folder it runs in), and DISPLAY and WAYLAND_DISPLAY are taken
// out of its environment unless a test asks for a display: `avenues` then keeps to its
// offline work, whatever session the tests were started from.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_files.h"

namespace avenues::testing {

/// What a finished program left.
struct Outcome {
  int status = -1;       ///< its exit status; 128 + N when signal N killed it; -1 when it did not start
  std::string out, err;  ///< what it wrote to stdout, and to stderr
  /// Its stdout, then its stderr: for a test that asks only whether something was said.
  std::string output() const { return out + err; }
};

/// How a program is run.
struct RunOptions {
  /// Its working folder; when empty, the test's folder for AvenuesRun's calls and the test
  /// process's own for the free functions below.
  std::filesystem::path cwd;
  /// Taken out of its environment: no window opens unless a test asks for one.
  std::vector<std::string> unset_env = {"DISPLAY", "WAYLAND_DISPLAY"};
  /// NAME=VALUE put into its environment (after unset_env), e.g. "DISPLAY=:3".
  std::vector<std::string> set_env;
  /// [s] > 0: run under timeout(1), which stops it after that long (status 124); 0: no limit.
  int timeout_s = 0;
};

/// A program started in the background. finish() waits for it; one never finished is
/// stopped (SIGTERM, then SIGKILL after 5 s) and reaped when its Child goes, so that no
/// test leaves a process behind.
class Child {
 public:
  Child() = default;
  Child(Child&& other) noexcept;
  Child& operator=(Child&& other) noexcept;
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child();
  /// Its process id; -1 when it did not start.
  pid_t pid() const { return pid_; }

 private:
  friend Child start_argv(const std::vector<std::string>& argv, const RunOptions& options);
  friend bool running(Child& child);
  friend Outcome finish(Child& child);
  /// Waits for it (or, with WNOHANG in `flags`, looks whether it has ended); false while it runs.
  bool reap(int flags);
  void release();
  pid_t pid_ = -1;
  int out_fd_ = -1, err_fd_ = -1;  ///< the memory files its stdout and stderr go to
  bool reaped_ = false;
  int status_ = -1;  ///< as Outcome::status, once reaped
};

/// Starts argv[0] (looked up on PATH) with the arguments argv[1..], as `options` say; a
/// program that cannot be started is a test failure (and a Child whose pid() is -1).
Child start_argv(const std::vector<std::string>& argv, const RunOptions& options = {});
/// Whether `child` is still running (false once it has exited: finish() then returns at once).
bool running(Child& child);
/// Waits for `child` to end; its status and what it wrote.
Outcome finish(Child& child);
/// start_argv, then finish.
Outcome run_argv(const std::vector<std::string>& argv, const RunOptions& options = {});
/// `avenues ARGS`: the real executable (AVENUES_BINARY) and the arguments after it.
std::vector<std::string> avenues_argv(const std::vector<std::string>& args);

/// A fresh folder for each test, named for the test (under the system's temporary folder),
/// removed when the test passed and kept when it failed, to look at; `avenues` and other
/// programs run in it by argument vector.
class AvenuesRun : public ::testing::Test {
 protected:
  AvenuesRun();
  ~AvenuesRun() override;

  /// The test's folder.
  const std::filesystem::path& dir() const { return dir_.path(); }
  /// `name` in the test's folder.
  std::filesystem::path path(const std::string& name) const { return dir() / name; }
  /// Writes `bytes` to the file `name` in the test's folder (its folders made); its path.
  std::string write(const std::string& name, const std::string& bytes) const { return dir_.write(name, bytes); }
  /// Everything below the test's folder (hidden temporaries included), relative to it.
  std::set<std::string> files() const;

  /// `avenues ARGS` in the test's folder (unless options.cwd says otherwise), to its end.
  Outcome run(const std::vector<std::string>& args) { return run(args, run_options_); }
  Outcome run(const std::vector<std::string>& args, const RunOptions& options);
  /// `avenues ARGS` started in the background: finish() it.
  Child start(const std::vector<std::string>& args) { return start(args, run_options_); }
  Child start(const std::vector<std::string>& args, const RunOptions& options);
  /// Another program (argv[0] on PATH), in the test's folder unless options.cwd says otherwise.
  Outcome run_argv(const std::vector<std::string>& argv) { return run_argv(argv, run_options_); }
  Outcome run_argv(const std::vector<std::string>& argv, const RunOptions& options);
  Child start_argv(const std::vector<std::string>& argv) { return start_argv(argv, run_options_); }
  Child start_argv(const std::vector<std::string>& argv, const RunOptions& options);

  /// How the calls above given no RunOptions run their programs; a fixture may change it
  /// (a display to show windows on, a time limit).
  RunOptions run_options_;

 private:
  TempDir dir_;
};

}  // namespace avenues::testing
