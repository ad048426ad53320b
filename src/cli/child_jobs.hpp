#pragma once
// Child processes of this executable, a few at once (`run --jobs N`): each job is an argument
// list run as a process of its own; its stderr is passed on line by line with a "[name] " prefix,
// its stdout is kept for the caller. SIGINT/SIGTERM of the parent (io/stop_signal.hpp) stop the
// launching of new jobs and are passed on to the running ones as SIGTERM, so each writes its
// mid-stage checkpoint and exits; children also get SIGTERM when the parent dies.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace tidalcrust {

/// A program to start: its path (for messages and argv[0]) and, for this process's own
/// executable, a file descriptor on it opened when the program started, so that children run the
/// very binary the parent runs even after the file at `path` is rebuilt, reinstalled or removed.
struct Executable {
  std::string path;
  int fd = -1;  ///< -1: started by path
};

/// How one job ended.
struct ChildOutcome {
  std::size_t job = 0;   ///< index into the job list
  int exit_code = 0;     ///< the child's exit code; 128 + signal number when a signal ended it
  std::string out;       ///< everything it wrote to stdout
};

/// The arguments (after the executable) of job `job` when it runs in slot `slot` (0 .. slots-1;
/// a slot is reused by the next job once its job has finished).
using ChildArguments = std::function<std::vector<std::string>(std::size_t job, std::size_t slot)>;

/// Called once per finished job, in the order they finish; `finished` counts them (1 ..).
using ChildFinished = std::function<void(const ChildOutcome& outcome, std::size_t finished)>;

/// Runs `job_count` jobs of `executable`, at most `slots` at once, each job's stderr lines
/// prefixed with "[names[job]] ". Returns the outcomes of the jobs that ran, in the order they
/// finished; after a stop request (SIGINT/SIGTERM) no new job starts, the running ones get
/// SIGTERM and are waited for. InputError if a process cannot be created; a child whose program
/// cannot be executed writes "cannot start PATH: errno N" to its stderr and exits with 127.
std::vector<ChildOutcome> run_child_jobs(const Executable& executable, const std::vector<std::string>& names,
                                         std::size_t slots, const ChildArguments& arguments,
                                         const ChildFinished& on_finished);

/// This process's executable: /proc/self/exe as opened at program start (fd), and its path.
/// InputError if /proc/self/exe could not be opened then or cannot be resolved now.
Executable own_executable();

/// Threads of each of `slots` slots when `total` threads are shared among them: total/slots, the
/// first total%slots slots one more, and at least 1 each.
std::vector<int> split_threads(int total, std::size_t slots);

}  // namespace tidalcrust
