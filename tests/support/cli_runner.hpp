#pragma once
// Runs the tidalcrust binary as a user would (run_cli: exit code, stdout, stderr; quoted paths;
// BackgroundCli: the same, started in the background for concurrent runs).
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/files.hpp"

namespace tidalcrust::test_support {

struct CliResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// `path` in single quotes, for an argument of run_cli.
inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

/// Runs `tidalcrust ARGS` through the shell (ARGS may quote paths), from the current folder,
/// with stdin from /dev/null; `environment` ("VAR=value ...") is added to its environment.
inline CliResult run_cli(const std::string& args, const std::string& environment = "") {
  const ScratchFolder capture("cli");
  const auto out = capture.path / "out.txt", err = capture.path / "err.txt";
  const std::string command = fmt::format("{}'{}' {} >{} 2>{} </dev/null", environment.empty() ? "" : "env " + environment + " ",
                                          TIDALCRUST_EXE, args, quoted(out), quoted(err));
  const int status = std::system(command.c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = read_file(out);
  result.err = read_file(err);
  return result;
}

/// `tidalcrust ARGS` started in the background (as run_cli runs it, with `exec`, so that its
/// pid is the program's own); finish() waits for it and returns what run_cli would. `prefix` is
/// a command that execs the program in turn (`env VAR=value`, `stdbuf -oL`), so the pid stays
/// the program's.
class BackgroundCli {
 public:
  explicit BackgroundCli(const std::string& args, const std::string& prefix = "") : capture_("cli_background") {
    const std::string command = fmt::format("exec {} '{}' {} >{} 2>{} </dev/null", prefix, TIDALCRUST_EXE, args,
                                            quoted(out_file()), quoted(capture_.path / "err.txt"));
    pid_ = fork();
    if (pid_ == 0) {
      execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    started_ = pid_;
  }
  BackgroundCli(const BackgroundCli&) = delete;
  BackgroundCli& operator=(const BackgroundCli&) = delete;
  ~BackgroundCli() {
    if (pid_ > 0) finish();
  }

  /// The program's pid (also after finish()).
  pid_t pid() const { return started_; }
  /// Where its stdout goes (readable while it runs).
  std::filesystem::path out_file() const { return capture_.path / "out.txt"; }

  CliResult finish() {
    int status = 0;
    if (pid_ > 0) waitpid(pid_, &status, 0);
    pid_ = -1;
    CliResult result;
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.out = read_file(capture_.path / "out.txt");
    result.err = read_file(capture_.path / "err.txt");
    return result;
  }

 private:
  ScratchFolder capture_;
  pid_t pid_ = -1;
  pid_t started_ = -1;
};

/// True while `pid` exists and has not exited (a zombie not yet reaped has exited).
inline bool is_running(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const auto paren = line.rfind(')');  // the state letter follows "pid (name) "
  return paren != std::string::npos && paren + 2 < line.size() && line[paren + 2] != 'Z' && line[paren + 2] != 'X';
}

/// Waits until `ready()` holds, looking every few milliseconds; false if the process `pid` ended
/// first. No deadline: the test waits for an event, however slow the machine (ctest's timeout
/// ends a hang).
template <typename Ready>
bool wait_while_running(pid_t pid, Ready ready) {
  while (!ready()) {
    if (!is_running(pid)) return ready();
    ::usleep(2000);
  }
  return true;
}

/// The command prefix (for BackgroundCli) that holds the program after its N-th step until
/// `hold_file`, which it creates there, is removed or a stop signal arrives (io/test_points.hpp).
inline std::string hold_at_step(long n, const std::filesystem::path& hold_file) {
  return fmt::format("env TIDALCRUST_TEST_HOLD_AT=step:{} TIDALCRUST_TEST_HOLD_FILE={}", n, quoted(hold_file));
}

inline int count_lines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace tidalcrust::test_support
