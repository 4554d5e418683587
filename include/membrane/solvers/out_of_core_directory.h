#pragma once
// Where MUMPS keeps out-of-core LU factors (Linear solver/Out of core). MUMPS writes its
// factor files into $MUMPS_OOC_TMPDIR (default /tmp) and deletes them when its instance is
// destroyed: at the end of a run or on SIGTERM/SIGINT, but not when the process is killed
// (SIGKILL, an out-of-memory kill, a node failure), which leaves files as large as the
// factors behind. So each process gets its own directory
//   <$MUMPS_OOC_TMPDIR or /tmp>/membrane-ooc-<host>-<pid>,
// created before its first out-of-core factorization (and MUMPS pointed at it), removed
// when the process ends normally; and the directories of earlier processes on this host
// that no longer exist are removed then too, so files a killed run left last only until
// the next out-of-core run on the same host.

#include <string>

namespace Membrane
{
  /// This process's out-of-core directory, created (and stale ones of dead processes on
  /// this host removed) on the first call; $MUMPS_OOC_TMPDIR then names it.
  const std::string &out_of_core_directory();
} // namespace Membrane
