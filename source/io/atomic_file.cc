#include <membrane/io/atomic_file.h>

#include <deal.II/base/exceptions.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace Membrane
{
  std::string temporary_name(const std::string &path)
  {
    return path + ".partial";
  }

  void commit_temporary(const std::string &path)
  {
    AssertThrow(std::rename(temporary_name(path).c_str(), path.c_str()) == 0,
                dealii::ExcMessage("Cannot rename <" + temporary_name(path) + "> to <" + path + ">"));
  }

  void write_file_atomically(const std::string &path, const std::string &content)
  {
    {
      std::ofstream out(temporary_name(path), std::ios::binary | std::ios::trunc);
      AssertThrow(out, dealii::ExcMessage("Cannot write <" + temporary_name(path) + ">"));
      out << content;
      out.flush();
      AssertThrow(out, dealii::ExcMessage("Writing <" + temporary_name(path) + "> failed: " + std::strerror(errno) +
                                          " (the file under its final name is unchanged)"));
    }
    commit_temporary(path);
  }
} // namespace Membrane
