#pragma once
// A run owns its output directory (Output/Directory): it never mixes its files with
// those of another run or with files that are not a run's, and it deletes nothing
// unless told to (--overwrite), and then only a run's own files.
//
// The entries of the directory are of three kinds:
//  - output files, written by membrane-flow: summary.json, statistics.txt, checkpoint.txt,
//    run_info.json, parameters.prm, surface*.pvd, surface*.vtu, surface*.pvtu, and any of
//    these with the suffix ".partial" (the temporary name of an atomic write);
//  - the log, log.txt: written by the run (appended) and often created before it starts
//    by whoever launched it (`membrane-flow ... > dir/log.txt`, a sweep's case log). Alone
//    it does not block a run; --overwrite deletes it with the output files, unless it is
//    the file this process's stdout or stderr goes to;
//  - launcher files, written next to a run by whoever started it: case.json and
//    status.json (a sweep's case records, membrane_flow/workflow/sweep.py). They
//    neither block a run nor are ever deleted;
//  - foreign: everything else (other files, subdirectories, symbolic links, an output
//    file's name that is not a regular file).
//
// Decision before the run starts (plan_run_directory; no side effects):
//  - the directory is missing, empty, or holds the log and launcher files only: the run
//    starts (with --overwrite the log is deleted first);
//  - it exists but is not a directory: refused;
//  - resumed run (Checkpoint/Resume from set) whose checkpoint file is this directory's
//    checkpoint.txt: the files belong to the run; all are kept and it continues
//    (--overwrite is ignored; foreign files the user added are left alone);
//  - foreign entries (fresh or resumed run): refused, with or without --overwrite, and
//    nothing is deleted; --overwrite never deletes what membrane-flow did not write;
//  - output files of a run (fresh run, or a resumed run from a checkpoint elsewhere):
//    refused unless --overwrite, which deletes exactly those files and the log (never
//    the input parameter file, the checkpoint to resume from, or the log when it is this
//    process's stdout / stderr) before the run starts.
//
// claim_run_directory() carries out the decision on rank 0 (creating the directory,
// deleting with --overwrite), broadcasts it, and throws dealii::ExcMessage on every
// rank when refused. Rank 0 also holds an exclusive advisory lock (flock) on the
// directory for the life of the returned object, so that two runs started at the same
// time into the same directory cannot both write into it (the lock ends with the
// process, even when it is killed). On file systems without flock the lock is skipped.

#include <mpi.h>

#include <string>
#include <vector>

namespace Membrane
{
  enum class RunFileKind
  {
    output,
    log,
    launcher,
    foreign
  };

  /// The kind of a directory entry by its file name (no path) and whether it is a
  /// regular file (not a directory, symbolic link, ...).
  RunFileKind classify_run_file(const std::string &name, bool is_regular_file);

  struct RunDirectoryRequest
  {
    std::string directory;   ///< Output/Directory
    bool        overwrite = false;
    std::string resume_from; ///< Checkpoint/Resume from (empty: a fresh run)
    /// Files that are never deleted (the input parameter file); the checkpoint to
    /// resume from is never deleted either, nor (in claim_run_directory) the files that
    /// this process's stdout and stderr go to.
    std::vector<std::string> keep;
  };

  struct RunDirectoryPlan
  {
    bool                     refuse = false;
    std::string              message;         ///< why refused (names Output/Directory and the way out)
    std::vector<std::string> remove;          ///< with --overwrite: the output files and log to delete (paths)
    std::vector<std::string> output_files;    ///< names of the run's output files found
    std::vector<std::string> foreign_entries; ///< names of foreign entries found
    bool                     resumes_own_files = false; ///< resumed run continuing in its own directory
  };

  /// Look at the directory and decide (no side effects).
  RunDirectoryPlan plan_run_directory(const RunDirectoryRequest &request);

  /// Holds the directory's lock (rank 0) until destroyed.
  class RunDirectory
  {
  public:
    RunDirectory() = default;
    ~RunDirectory();
    RunDirectory(RunDirectory &&other) noexcept;
    RunDirectory &operator=(RunDirectory &&other) noexcept;
    RunDirectory(const RunDirectory &)            = delete;
    RunDirectory &operator=(const RunDirectory &) = delete;

    /// What was done, for the user ("deleted 7 output files of an earlier run", or empty).
    const std::string &note() const { return done; }

  private:
    friend RunDirectory claim_run_directory(const RunDirectoryRequest &, MPI_Comm);
    int         lock_fd = -1;
    std::string done;
  };

  /// Collective over `communicator`: rank 0 decides, creates the directory (and with
  /// --overwrite deletes the earlier run's output files), locks it; the decision is
  /// broadcast. Throws dealii::ExcMessage on every rank if the run may not use the
  /// directory.
  RunDirectory claim_run_directory(const RunDirectoryRequest &request, MPI_Comm communicator);
} // namespace Membrane
