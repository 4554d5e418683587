#pragma once
// log.txt: everything the run prints (progress, warnings, the timer table) also goes
// to a file in its output directory. While a LogFile lives, std::cout and std::cerr
// of this process write to both the terminal and the file (appended, so a resumed
// run's log continues the earlier one). If the standard output already goes to
// that file (a sweep capturing a case's output there), nothing is duplicated.

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
    std::ofstream                   file;
    std::unique_ptr<std::streambuf> out_tee, err_tee;
    std::streambuf                 *out_original, *err_original;
  };
} // namespace Membrane
