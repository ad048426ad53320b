#include "cli/child_jobs.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>

#include "base/errors.hpp"
#include "io/stop_signal.hpp"

extern char** environ;

namespace tidalcrust {
namespace {

/// /proc/self/exe opened before main (static initialisation): the binary this process started
/// as, whatever later happens to its file. Close-on-exec: fexecve of an ELF file does not need it
/// open in the new image. -1 if it could not be opened.
const int own_executable_fd = ::open("/proc/self/exe", O_RDONLY | O_CLOEXEC);

/// Writes "cannot start <what>: errno <e>\n" to fd 2 with async-signal-safe calls only.
void report_exec_failure(const std::string& what, int e) {
  char digits[16];
  int n = 0;
  do digits[sizeof digits - 1 - n++] = static_cast<char>('0' + e % 10), e /= 10;
  while (e > 0 && n < 15);
  const char prefix[] = "cannot start ";
  const char middle[] = ": errno ";
  [[maybe_unused]] ssize_t ignored = ::write(2, prefix, sizeof prefix - 1);
  ignored = ::write(2, what.data(), what.size());
  ignored = ::write(2, middle, sizeof middle - 1);
  ignored = ::write(2, digits + sizeof digits - n, static_cast<std::size_t>(n));
  ignored = ::write(2, "\n", 1);
}

/// One running child: its pid, the read ends of its stdout and stderr pipes, what came so far.
struct RunningChild {
  std::size_t job = 0;
  std::size_t slot = 0;
  pid_t pid = -1;
  int out_fd = -1;
  int err_fd = -1;
  std::string out;
  std::string err_pending;  ///< stderr after its last complete line
};

/// Passes on the complete lines of `pending` to stderr with the job's prefix; with `flush`
/// also an unterminated rest.
void pass_on_lines(std::string& pending, const std::string& name, bool flush) {
  std::size_t start = 0;
  for (std::size_t end; (end = pending.find('\n', start)) != std::string::npos; start = end + 1)
    fmt::print(stderr, "[{}] {}\n", name, std::string_view(pending).substr(start, end - start));
  pending.erase(0, start);
  if (flush && !pending.empty()) fmt::print(stderr, "[{}] {}\n", name, pending), pending.clear();
}

/// Reads what is available on `fd` into `into`; closes it (and sets it to -1) at end of file.
void drain(int& fd, std::string& into) {
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) {
      into.append(buffer, static_cast<std::size_t>(n));
      if (static_cast<std::size_t>(n) < sizeof buffer) return;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno == EAGAIN) return;
    ::close(fd);
    fd = -1;
    return;
  }
}

RunningChild start_child(const Executable& executable, const std::vector<std::string>& args, std::size_t job,
                         std::size_t slot) {
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0) throw InputError(fmt::format("cannot create a pipe: {}", std::strerror(errno)));
  if (::pipe2(err_pipe, O_CLOEXEC) != 0) {
    ::close(out_pipe[0]), ::close(out_pipe[1]);
    throw InputError(fmt::format("cannot create a pipe: {}", std::strerror(errno)));
  }
  // Everything the child needs is prepared before fork: after it only async-signal-safe calls.
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(executable.path.c_str()));
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid == 0) {
    // A child outliving its parent (SIGKILL) would go on computing unseen: it stops as after
    // SIGTERM instead, with its mid-stage checkpoint.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(130);
    ::dup2(out_pipe[1], 1);
    ::dup2(err_pipe[1], 2);
    if (executable.fd >= 0)
      ::fexecve(executable.fd, argv.data(), environ);
    else
      ::execv(executable.path.c_str(), argv.data());
    report_exec_failure(executable.path, errno);
    ::_exit(127);
  }
  const int fork_errno = errno;
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  if (pid < 0) {
    ::close(out_pipe[0]), ::close(err_pipe[0]);
    throw InputError(fmt::format("cannot start {}: {}", executable.path, std::strerror(fork_errno)));
  }
  ::fcntl(out_pipe[0], F_SETFL, O_NONBLOCK);
  ::fcntl(err_pipe[0], F_SETFL, O_NONBLOCK);
  RunningChild child;
  child.job = job;
  child.slot = slot;
  child.pid = pid;
  child.out_fd = out_pipe[0];
  child.err_fd = err_pipe[0];
  return child;
}

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

}  // namespace

std::vector<ChildOutcome> run_child_jobs(const Executable& executable, const std::vector<std::string>& names,
                                         std::size_t slots, const ChildArguments& arguments,
                                         const ChildFinished& on_finished) {
  install_stop_handlers();
  slots = std::max<std::size_t>(1, slots);
  std::vector<ChildOutcome> outcomes;
  std::vector<RunningChild> running;
  std::vector<bool> slot_busy(slots, false);
  std::size_t next = 0;
  bool stop_passed_on = false;
  for (;;) {
    while (!stop_requested() && next < names.size() && running.size() < slots) {
      const std::size_t slot = static_cast<std::size_t>(std::find(slot_busy.begin(), slot_busy.end(), false) -
                                                         slot_busy.begin());
      running.push_back(start_child(executable, arguments(next, slot), next, slot));
      slot_busy[slot] = true;
      ++next;
    }
    if (running.empty()) break;
    if (stop_requested() && !stop_passed_on) {
      // Ctrl-C reaches the whole process group; SIGTERM (kill, a batch system) only this process.
      for (const auto& c : running) ::kill(c.pid, SIGTERM);
      stop_passed_on = true;
    }
    std::vector<pollfd> fds;
    for (const auto& c : running) {
      if (c.out_fd >= 0) fds.push_back({c.out_fd, POLLIN, 0});
      if (c.err_fd >= 0) fds.push_back({c.err_fd, POLLIN, 0});
    }
    if (!fds.empty()) ::poll(fds.data(), fds.size(), 100);  // EINTR: a signal; looked at above
    for (auto& c : running) {
      if (c.out_fd >= 0) drain(c.out_fd, c.out);
      if (c.err_fd >= 0) drain(c.err_fd, c.err_pending);
      pass_on_lines(c.err_pending, names[c.job], false);
    }
    // A child is done when it closed both pipes (it exited, or nothing more will come) and has
    // been reaped.
    for (auto it = running.begin(); it != running.end();) {
      if (it->out_fd >= 0 || it->err_fd >= 0) {
        ++it;
        continue;
      }
      int status = 0;
      while (::waitpid(it->pid, &status, 0) < 0 && errno == EINTR) {
      }
      pass_on_lines(it->err_pending, names[it->job], true);
      outcomes.push_back({it->job, exit_code_of(status), std::move(it->out)});
      slot_busy[it->slot] = false;
      it = running.erase(it);
      if (on_finished) on_finished(outcomes.back(), outcomes.size());
    }
  }
  return outcomes;
}

Executable own_executable() {
  if (own_executable_fd < 0)
    throw InputError("cannot open this program's executable (/proc/self/exe) to start its child processes");
  std::error_code ec;
  const auto path = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw InputError(fmt::format("cannot find this program's executable (/proc/self/exe): {}", ec.message()));
  return {path.string(), own_executable_fd};
}

std::vector<int> split_threads(int total, std::size_t slots) {
  slots = std::max<std::size_t>(1, slots);
  const int n = static_cast<int>(slots);
  std::vector<int> threads(slots);
  for (int s = 0; s < n; ++s) threads[static_cast<std::size_t>(s)] = std::max(1, total / n + (s < total % n ? 1 : 0));
  return threads;
}

}  // namespace tidalcrust
