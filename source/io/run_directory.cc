#include <membrane/io/run_directory.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>
#include <system_error>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

namespace Membrane
{
  namespace fs = std::filesystem;

  namespace
  {
    bool ends_with(const std::string &text, const std::string &suffix)
    {
      return text.size() >= suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
    }

    bool starts_with(const std::string &text, const std::string &prefix)
    {
      return text.compare(0, prefix.size(), prefix) == 0;
    }

    /// "a, b, c, d, e and 3 more"
    std::string list_names(const std::vector<std::string> &names, const std::size_t shown = 5)
    {
      std::string out;
      for (std::size_t i = 0; i < names.size() && i < shown; ++i)
        out += (i ? ", " : "") + names[i];
      if (names.size() > shown)
        out += " and " + std::to_string(names.size() - shown) + " more";
      return out;
    }

    std::string quoted(const std::string &path)
    {
      return "'" + path + "'";
    }

    bool same_file(const fs::path &a, const fs::path &b)
    {
      std::error_code ec;
      const bool      equal = fs::equivalent(a, b, ec);
      return !ec && equal;
    }
  } // namespace

  RunFileKind classify_run_file(const std::string &name, const bool is_regular_file)
  {
    static const std::set<std::string> launcher = {"case.json", "status.json"};
    static const std::set<std::string> outputs  = {"summary.json", "statistics.txt", "checkpoint.txt",
                                                   "run_info.json", "parameters.prm", "paraview_state.py"};
    if (!is_regular_file)
      return RunFileKind::foreign;
    if (launcher.count(name))
      return RunFileKind::launcher;
    if (name == "log.txt")
      return RunFileKind::log;
    const std::string base = ends_with(name, ".partial") ? name.substr(0, name.size() - 8) : name;
    if (outputs.count(base))
      return RunFileKind::output;
    if (starts_with(base, "surface") &&
        (ends_with(base, ".vtu") || ends_with(base, ".pvtu") || ends_with(base, ".pvd")))
      return RunFileKind::output;
    return RunFileKind::foreign;
  }

  RunDirectoryPlan plan_run_directory(const RunDirectoryRequest &request)
  {
    RunDirectoryPlan  plan;
    const std::string where = "<Output/Directory> = " + quoted(request.directory);
    const auto        refuse = [&](const std::string &message) {
      plan.refuse  = true;
      plan.message = message;
      plan.remove.clear();
      return plan;
    };
    if (request.directory.empty())
      return refuse("<Output/Directory> is empty; name a directory for the run's files (e.g. results/run1)");

    const fs::path  directory(request.directory);
    std::error_code ec;
    const auto      status = fs::status(directory, ec);
    if (ec && ec != std::errc::no_such_file_or_directory)
      return refuse(where + ": cannot inspect it (" + ec.message() + ")");
    if (!fs::exists(status))
      return plan; // a new directory
    if (!fs::is_directory(status))
      return refuse(where + " exists and is not a directory; choose another <Output/Directory>");

    std::vector<std::pair<std::string, RunFileKind>> entries;
    for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec))
      {
        std::error_code   type_ec;
        const std::string name    = it->path().filename().string();
        const bool        regular = it->symlink_status(type_ec).type() == fs::file_type::regular;
        entries.emplace_back(name, classify_run_file(name, regular && !type_ec));
      }
    if (ec)
      return refuse(where + ": cannot list it (" + ec.message() + ")");
    std::sort(entries.begin(), entries.end());
    bool has_log = false;
    for (const auto &[name, kind] : entries)
      if (kind == RunFileKind::output)
        plan.output_files.push_back(name);
      else if (kind == RunFileKind::foreign)
        plan.foreign_entries.push_back(name);
      else if (kind == RunFileKind::log)
        has_log = true;

    std::vector<std::string> keep = request.keep;
    if (!request.resume_from.empty())
      keep.push_back(request.resume_from);
    const auto remove_unless_kept = [&](const std::string &name) {
      const fs::path path = directory / name;
      if (std::none_of(keep.begin(), keep.end(), [&](const std::string &k) { return same_file(path, k); }))
        plan.remove.push_back(path.string());
    };

    const bool resume = !request.resume_from.empty();
    if (resume && same_file(directory / "checkpoint.txt", request.resume_from))
      {
        plan.resumes_own_files = true; // continue the run in its own directory, keep everything
        return plan;
      }
    if (plan.output_files.empty() && plan.foreign_entries.empty())
      {
        // empty, or the log and the launcher's files only
        if (request.overwrite && has_log)
          remove_unless_kept("log.txt");
        return plan;
      }

    if (!plan.foreign_entries.empty())
      return refuse(where + " holds files that membrane-flow did not write (" + list_names(plan.foreign_entries) +
                    "). A run never writes its files among foreign ones, and --overwrite never deletes them: "
                    "choose a new or empty <Output/Directory> (e.g. --set 'Output/Directory=" +
                    (directory / "run1").string() + "'), or move those files away");

    const bool        has_checkpoint = std::find(plan.output_files.begin(), plan.output_files.end(),
                                                 "checkpoint.txt") != plan.output_files.end();
    const std::string found          = " (" + list_names(plan.output_files) + "; " +
                                      std::to_string(plan.output_files.size()) + " file" +
                                      (plan.output_files.size() == 1 ? "" : "s") + ")";
    if (!request.overwrite)
      {
        if (resume)
          return refuse("<Checkpoint/Resume from> = " + quoted(request.resume_from) + " is not the checkpoint.txt of " +
                        where + ", which holds the output of another run" + found +
                        ". A resumed run continues only in a new or empty directory or in the directory of its own "
                        "checkpoint: choose another <Output/Directory>, or rerun with --overwrite to delete those "
                        "output files and log.txt first (nothing else is deleted)");
        return refuse(where + " already holds the output of a run" + found +
                      ". A run never overwrites or mixes with another run's files: rerun with --overwrite to delete "
                      "those output files and log.txt first (nothing else is deleted)" +
                      (has_checkpoint ? ", continue that run with --set 'Checkpoint/Resume from=" +
                                          (directory / "checkpoint.txt").string() + "'"
                                      : std::string()) +
                      ", or choose another <Output/Directory>");
      }

    // --overwrite: delete exactly the output files and the log, never the input or the checkpoint to resume from.
    for (const auto &name : plan.output_files)
      remove_unless_kept(name);
    if (has_log)
      remove_unless_kept("log.txt");
    return plan;
  }

  RunDirectory::~RunDirectory()
  {
    if (lock_fd >= 0)
      ::close(lock_fd); // releases the flock
  }

  RunDirectory::RunDirectory(RunDirectory &&other) noexcept
    : lock_fd(other.lock_fd)
    , done(std::move(other.done))
  {
    other.lock_fd = -1;
  }

  RunDirectory &RunDirectory::operator=(RunDirectory &&other) noexcept
  {
    if (this != &other)
      {
        if (lock_fd >= 0)
          ::close(lock_fd);
        lock_fd       = other.lock_fd;
        done          = std::move(other.done);
        other.lock_fd = -1;
      }
    return *this;
  }

  RunDirectory claim_run_directory(const RunDirectoryRequest &request, const MPI_Comm communicator)
  {
    RunDirectory result;
    std::string  refusal;
    if (dealii::Utilities::MPI::this_mpi_process(communicator) == 0)
      {
        const std::string where = "<Output/Directory> = " + quoted(request.directory);
        try
          {
            const fs::path directory(request.directory);
            // Lock first (when the directory exists), so that a run still writing into it is named as such.
            const auto lock = [&]() -> std::string {
              const int fd = ::open(request.directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
              if (fd < 0)
                return where + ": cannot open it (" + std::strerror(errno) + ")";
              if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
                {
                  const int error = errno;
                  ::close(fd);
                  if (error == EWOULDBLOCK)
                    return where + " is in use by another membrane-flow run that is still running; wait until it "
                                   "ends or choose another <Output/Directory>";
                  return ""; // no flock on this file system: go on without the lock
                }
              result.lock_fd = fd;
              return "";
            };
            std::error_code ec;
            if (fs::is_directory(directory, ec))
              refusal = lock();
            // Never delete the file this process's output goes to (`... > dir/log.txt`).
            RunDirectoryRequest checked = request;
            checked.keep.push_back("/proc/self/fd/1");
            checked.keep.push_back("/proc/self/fd/2");
            RunDirectoryPlan plan;
            if (refusal.empty())
              {
                plan = plan_run_directory(checked);
                if (plan.refuse)
                  refusal = plan.message;
              }
            if (refusal.empty() && result.lock_fd < 0)
              {
                fs::create_directories(directory);
                refusal = lock();
              }
            if (refusal.empty() && ::access(request.directory.c_str(), W_OK | X_OK) != 0)
              refusal = where + ": cannot write into it (" + std::strerror(errno) + ")";
            if (refusal.empty() && !plan.remove.empty())
              {
                for (const auto &path : plan.remove)
                  fs::remove(path);
                result.done = "Deleted " + std::to_string(plan.remove.size()) + " file" +
                              (plan.remove.size() == 1 ? "" : "s") + " of an earlier run in " + request.directory +
                              " (--overwrite)";
              }
          }
        catch (const std::exception &e)
          {
            refusal = where + ": cannot create or use it (" + e.what() + ")";
          }
        if (!refusal.empty() && result.lock_fd >= 0)
          {
            ::close(result.lock_fd);
            result.lock_fd = -1;
          }
      }
    // Broadcast the decision: "1" + note on success, "0" + reason when refused.
    const std::string decision = dealii::Utilities::MPI::broadcast(
      communicator, refusal.empty() ? "1" + result.done : "0" + refusal, 0);
    AssertThrow(!decision.empty() && decision[0] == '1', dealii::ExcMessage(decision.substr(1)));
    result.done = decision.substr(1);
    return result;
  }
} // namespace Membrane
