#include <membrane/io/memory.h>

#include <deal.II/base/mpi.h>

#include <unistd.h>

#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace Membrane
{
  namespace
  {
    /// The value of `key` (in kB) in a /proc file of "Key:  value kB" lines, in bytes.
    double proc_entry(const char *file, const std::string &key)
    {
      std::ifstream in(file);
      std::string   line;
      while (std::getline(in, line))
        if (line.compare(0, key.size(), key) == 0)
          {
            std::istringstream fields(line.substr(key.size()));
            double             value = -1;
            if (fields >> value)
              return value * 1024;
          }
      return -1;
    }
  } // namespace

  double host_available_memory()
  {
    return proc_entry("/proc/meminfo", "MemAvailable:");
  }

  double resident_memory()
  {
    return proc_entry("/proc/self/status", "VmRSS:");
  }

  double available_memory(const MPI_Comm communicator)
  {
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    std::ostringstream mine;
    mine << std::setprecision(17) << host_available_memory() << ' ' << host;
    std::map<std::string, double> per_host;
    for (const std::string &entry : dealii::Utilities::MPI::all_gather(communicator, mine.str()))
      {
        std::istringstream in(entry);
        double             bytes = -1;
        std::string        name;
        in >> bytes;
        std::getline(in, name);
        if (!(bytes >= 0))
          return -1;
        per_host[name] = bytes;
      }
    double total = 0;
    for (const auto &[name, bytes] : per_host)
      total += bytes;
    return total;
  }

  std::string format_bytes(const double bytes)
  {
    std::ostringstream out;
    out << std::fixed << std::setprecision(1);
    if (bytes >= 1e12)
      out << bytes / 1e12 << " TB";
    else if (bytes >= 1e9)
      out << bytes / 1e9 << " GB";
    else
      out << bytes / 1e6 << " MB";
    return out.str();
  }
} // namespace Membrane
