#include <membrane/io/log_file.h>

#include <iostream>

#include <sys/stat.h>
#include <unistd.h>

namespace Membrane
{
  namespace
  {
    /// A stream buffer that writes to two others.
    class TeeBuffer : public std::streambuf
    {
    public:
      TeeBuffer(std::streambuf *first, std::streambuf *second)
        : first(first)
        , second(second)
      {}

    protected:
      int overflow(const int c) override
      {
        if (c == traits_type::eof())
          return traits_type::not_eof(c);
        const auto ch = traits_type::to_char_type(c);
        const bool ok = first->sputc(ch) != traits_type::eof();
        second->sputc(ch); // the log is best effort: a full disk must not stop the run
        return ok ? c : traits_type::eof();
      }
      std::streamsize xsputn(const char *s, const std::streamsize n) override
      {
        second->sputn(s, n);
        return first->sputn(s, n);
      }
      int sync() override
      {
        second->pubsync();
        return first->pubsync();
      }

    private:
      std::streambuf *first, *second;
    };
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
    : out_original(std::cout.rdbuf())
    , err_original(std::cerr.rdbuf())
  {
    if (stdout_is(path))
      return;
    file.open(path, std::ios::app);
    if (!file)
      {
        std::cerr << "Warning: cannot write the log file <" << path << ">; output goes to the terminal only\n";
        return;
      }
    out_tee = std::make_unique<TeeBuffer>(out_original, file.rdbuf());
    err_tee = std::make_unique<TeeBuffer>(err_original, file.rdbuf());
    std::cout.rdbuf(out_tee.get());
    std::cerr.rdbuf(err_tee.get());
  }

  LogFile::~LogFile()
  {
    std::cout.flush();
    std::cerr.flush();
    std::cout.rdbuf(out_original);
    std::cerr.rdbuf(err_original);
  }
} // namespace Membrane
