#pragma once
// Files that are either absent, the previous version, or complete: write to a
// temporary name in the same directory, then rename (atomic on POSIX).

#include <string>

namespace Membrane
{
  void write_file_atomically(const std::string &path, const std::string &content);
  /// The temporary name used for `path` (for writers that produce the file themselves).
  std::string temporary_name(const std::string &path);
  /// Rename temporary_name(path) to path; throws on failure.
  void commit_temporary(const std::string &path);
} // namespace Membrane
