#pragma once
// The command-line application: argument handling, parameter reading with
// clean error messages, and the run. Returns the process exit code:
// 0 success, 1 bad input or usage, 2 the run stopped early (diverged).

namespace Membrane
{
  int run_application(int argc, char **argv);
}
