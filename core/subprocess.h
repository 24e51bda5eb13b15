// Avenues — running another program by its argument vector, never through a shell.
//
// No user text may reach a shell (a file name with a quote in it would otherwise run
// commands). run_program() starts the program with posix_spawnp: the arguments go to it
// exactly as given, one string each; PATH finds the program. Part of core/.
#pragma once

#include <string>
#include <vector>

namespace avenues {

/// What a finished program left.
struct ProgramResult {
  int status = -1;      ///< its exit status; -1 when it was killed by a signal
  std::string output;   ///< what it wrote to stdout and stderr, interleaved
};

/// Runs argv[0] (looked up on PATH) with the arguments argv[1..], in `working_dir` when not
/// empty, stdin from /dev/null, and waits for it. Throws std::runtime_error naming the
/// program when it cannot be started (not installed, not executable).
ProgramResult run_program(const std::vector<std::string>& argv, const std::string& working_dir = {});

}  // namespace avenues
