#pragma once
// The command-line application: argument handling, parameter reading with
// clean error messages, the checks before a run (memory estimate, ownership of
// the output directory; docs/reliability.md), stop-signal handlers, and the run.
// Returns the process exit code: 0 success, 1 bad input or usage, 2 the run
// stopped early (diverged), 128 + signal when stopped by SIGINT / SIGTERM.
// An error message is always the last thing printed.

namespace Membrane
{
  int run_application(int argc, char **argv);
}
