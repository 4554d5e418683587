#pragma once
// log.txt: everything the run prints (progress, warnings, the timer table) also goes
// to a file in its output directory. While a LogFile lives, std::cout and std::cerr
// of this process write to both the terminal and the file (appended, so a resumed
// run's log continues the earlier one). If the standard output already goes to
// that file (a sweep capturing a case's output there), nothing is duplicated. Several
// LogFiles may be open at once and closed in any order; each receives all output.

#include <fstream>
#include <memory>
#include <streambuf>
#include <string>

namespace Membrane
{
  class LogFile
  {
  public:
    explicit LogFile(const std::string &path);
    ~LogFile();
    LogFile(const LogFile &)            = delete;
    LogFile &operator=(const LogFile &) = delete;

  private:
    std::ofstream file;
    bool          registered = false; ///< whether std::cout and std::cerr also go to `file`
  };
} // namespace Membrane
