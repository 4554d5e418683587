#include <membrane/solvers/out_of_core_directory.h>

#include <deal.II/base/exceptions.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <signal.h>
#include <unistd.h>

namespace Membrane
{
  namespace
  {
    namespace fs = std::filesystem;

    const std::string prefix = "membrane-ooc-";

    std::string host_name()
    {
      char name[256] = {};
      if (gethostname(name, sizeof(name) - 1) != 0)
        return "localhost";
      std::string host(name);
      // The host becomes part of a file name: no path separators. (A '-' in it is harmless:
      // directories are matched by the whole prefix "membrane-ooc-<host>-".)
      for (char &c : host)
        if (c == '/')
          c = '_';
      return host;
    }

    // Removes the directories `membrane-ooc-<host>-<pid>` in `base` whose process no longer
    // runs on this host; returns how many were removed.
    unsigned int remove_stale_out_of_core_directories(const std::string &base, const std::string &host)
    {
      const std::string own = prefix + host + "-";
      unsigned int      removed = 0;
      std::error_code   error;
      for (const auto &entry : fs::directory_iterator(base, error))
        {
          const std::string name = entry.path().filename().string();
          if (name.rfind(own, 0) != 0 || !entry.is_directory())
            continue;
          const std::string pid_text = name.substr(own.size());
          if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos)
            continue;
          const long pid = std::strtol(pid_text.c_str(), nullptr, 10);
          // kill(pid, 0) probes without signalling: ESRCH means no such process. A live
          // process (also one that merely reuses the number) keeps its directory.
          if (pid <= 0 || pid == getpid() || kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH)
            continue;
          std::error_code ignored; // another rank may be removing it at the same time
          if (fs::remove_all(entry.path(), ignored) > 0)
            ++removed;
        }
      return removed;
    }

    // The directory exists while the process lives; the destructor removes it after every
    // solver (and with it every MUMPS instance and its files) is gone: a function-local
    // static is destroyed after main returns.
    struct ProcessDirectory
    {
      ProcessDirectory()
      {
        const char       *configured = std::getenv("MUMPS_OOC_TMPDIR");
        const std::string base       = configured != nullptr && *configured != '\0' ? configured : "/tmp";
        const std::string host       = host_name();
        const unsigned int removed   = remove_stale_out_of_core_directories(base, host);
        if (removed > 0)
          std::cout << "Removed " << removed << " out-of-core director" << (removed == 1 ? "y" : "ies")
                    << " of killed runs from " << base << "\n";
        path = (fs::path(base) / (prefix + host + "-" + std::to_string(getpid()))).string();
        std::error_code error;
        fs::create_directories(path, error);
        AssertThrow(!error, dealii::ExcMessage("cannot create the out-of-core directory " + path + " (" +
                                               error.message() + "); set MUMPS_OOC_TMPDIR to a writable directory"));
        setenv("MUMPS_OOC_TMPDIR", path.c_str(), 1);
      }
      ~ProcessDirectory()
      {
        std::error_code ignored;
        fs::remove_all(path, ignored);
      }
      std::string path;
    };
  } // namespace

  const std::string &out_of_core_directory()
  {
    static const ProcessDirectory directory;
    return directory.path;
  }
} // namespace Membrane
