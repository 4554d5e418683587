#pragma once
// The command-line application: argument handling, parameter reading with
// clean error messages, the checks before a run (memory estimate, ownership of
// the output directory; docs/reliability.md), stop-signal handlers, and the run.
// Returns the process exit code: 0 success, 1 bad input or usage, 2 the run
// stopped early (diverged), 128 + signal when stopped by SIGINT / SIGTERM.
// An error message is always the last thing printed.

#include <exception>
#include <string>

namespace Membrane
{
  int run_application(int argc, char **argv);

  /// The user-facing part of an exception's text on one line (deal.II's "Additional
  /// information", without the stack trace), as the application prints it.
  std::string error_message(const std::exception &e);
}
