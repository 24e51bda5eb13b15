// Avenues — the command line: every subcommand's options and what runs them.
#pragma once

namespace avenues::app {

/// Parses argv and runs the chosen subcommand (or the main job). Returns the process's
/// exit status: 0 on success, 2 for a bad command line or bad input, with
/// "avenues: <message>" on stderr.
int run_cli(int argc, char** argv);

}  // namespace avenues::app
