#include <membrane/io/log_file.h>

#include <algorithm>
#include <iostream>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace Membrane
{
  namespace
  {
    /// A stream buffer that writes to the original one and to every open log file.
    class TeeBuffer : public std::streambuf
    {
    public:
      std::streambuf              *first = nullptr;
      std::vector<std::streambuf *> others;

    protected:
      int overflow(const int c) override
      {
        if (c == traits_type::eof())
          return traits_type::not_eof(c);
        const auto ch = traits_type::to_char_type(c);
        const bool ok = first->sputc(ch) != traits_type::eof();
        for (auto *other : others)
          other->sputc(ch); // the log is best effort: a full disk must not stop the run
        return ok ? c : traits_type::eof();
      }
      std::streamsize xsputn(const char *s, const std::streamsize n) override
      {
        for (auto *other : others)
          other->sputn(s, n);
        return first->sputn(s, n);
      }
      int sync() override
      {
        for (auto *other : others)
          other->pubsync();
        return first->pubsync();
      }
    };

    /// std::cout and std::cerr go through these while any LogFile is open. Several
    /// may be open at once (simulations of the Python module), closed in any order.
    struct Redirection
    {
      TeeBuffer out, err;
      unsigned int open_logs = 0;
    };
    Redirection &redirection()
    {
      static Redirection r;
      return r;
    }
  } // namespace

  namespace
  {
    /// Whether the standard output already goes to `path` (a sweep that captures
    /// a case's output in its log.txt): then the log needs no second copy.
    bool stdout_is(const std::string &path)
    {
      struct stat out, log;
      return fstat(STDOUT_FILENO, &out) == 0 && stat(path.c_str(), &log) == 0 && out.st_dev == log.st_dev &&
             out.st_ino == log.st_ino;
    }
  } // namespace

  LogFile::LogFile(const std::string &path)
  {
    if (stdout_is(path))
      return;
    file.open(path, std::ios::app);
    if (!file)
      {
        std::cerr << "Warning: cannot write the log file <" << path << ">; output goes to the terminal only\n";
        return;
      }
    Redirection &r = redirection();
    if (r.open_logs++ == 0)
      {
        r.out.first = std::cout.rdbuf(&r.out);
        r.err.first = std::cerr.rdbuf(&r.err);
      }
    r.out.others.push_back(file.rdbuf());
    r.err.others.push_back(file.rdbuf());
    registered = true;
  }

  LogFile::~LogFile()
  {
    if (!registered)
      return;
    std::cout.flush();
    std::cerr.flush();
    Redirection &r = redirection();
    for (auto *tee : {&r.out, &r.err})
      tee->others.erase(std::find(tee->others.begin(), tee->others.end(), file.rdbuf()));
    if (--r.open_logs == 0)
      {
        std::cout.rdbuf(r.out.first);
        std::cerr.rdbuf(r.err.first);
      }
  }
} // namespace Membrane
