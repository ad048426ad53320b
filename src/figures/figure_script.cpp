#include "figures/figure_script.hpp"

#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

#include "base/errors.hpp"

extern char** environ;

namespace tidalcrust {

namespace fs = std::filesystem;

fs::path figure_python() {
  const char* chosen = std::getenv("TIDALCRUST_PYTHON");
  return chosen != nullptr && *chosen != '\0' ? fs::path(chosen) : fs::path("/usr/bin/python3");
}

fs::path figure_package_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / TIDALCRUST_PYTHON_SITE;
    if (fs::is_regular_file(installed / "tidalcrust" / "figures" / "__main__.py", ec)) return installed;
  }
  return TIDALCRUST_PYTHON_SOURCE;
}

namespace {
std::string last_line(const std::string& text) {
  std::size_t end = text.find_last_not_of(" \n\r\t");
  if (end == std::string::npos) return "";
  const std::size_t begin = text.rfind('\n', end);
  return text.substr(begin == std::string::npos ? 0 : begin + 1, end + 1 - (begin == std::string::npos ? 0 : begin + 1));
}
}  // namespace

void draw_figures(const std::string& kind, const std::vector<std::string>& args) {
  const fs::path python = figure_python();
  const std::string what = fmt::format("figures ({} -m tidalcrust.figures {})", python.string(), kind);
  // A bare name ("python3") is looked up on PATH, as a shell would; a path must be executable.
  const bool on_path = python.string().find('/') == std::string::npos;
  if (!on_path && ::access(python.c_str(), X_OK) != 0)
    throw InputError(fmt::format("{}: no such interpreter ({}; set TIDALCRUST_PYTHON to a python3 with matplotlib "
                                 "and cartopy)", python.string(), std::strerror(errno)));
  std::vector<std::string> argv_text{python.string(), "-m", "tidalcrust.figures", kind};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);

  // The environment, with the package first on PYTHONPATH and the non-interactive backend.
  std::vector<std::string> env_text;
  std::string pythonpath = figure_package_dir().string();
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    if (entry.rfind("PYTHONPATH=", 0) == 0) {
      if (entry.size() > 11) pythonpath += ":" + entry.substr(11);
    } else if (entry.rfind("MPLBACKEND=", 0) != 0) {
      env_text.push_back(entry);
    }
  }
  env_text.push_back("PYTHONPATH=" + pythonpath);
  env_text.push_back("MPLBACKEND=Agg");
  std::vector<char*> envp;
  for (auto& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  int err_pipe[2];
  if (::pipe(err_pipe) != 0) throw InputError(fmt::format("{}: cannot make a pipe: {}", what, std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, err_pipe[0]);
  posix_spawn_file_actions_addclose(&actions, err_pipe[1]);
  pid_t pid = 0;
  const int spawned = on_path ? ::posix_spawnp(&pid, python.c_str(), &actions, nullptr, argv.data(), envp.data())
                              : ::posix_spawn(&pid, python.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  ::close(err_pipe[1]);
  if (spawned != 0) {
    ::close(err_pipe[0]);
    throw InputError(fmt::format("{}: cannot start: {} (set TIDALCRUST_PYTHON to a python3 with matplotlib and "
                                 "cartopy)", what, std::strerror(spawned)));
  }
  std::string err_text;
  char buffer[4096];
  for (;;) {
    const ssize_t got = ::read(err_pipe[0], buffer, sizeof buffer);
    if (got > 0) err_text.append(buffer, static_cast<std::size_t>(got));
    else if (got == 0 || errno != EINTR) break;
  }
  ::close(err_pipe[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  const std::string how = WIFEXITED(status) ? fmt::format("exit {}", WEXITSTATUS(status))
                                            : fmt::format("signal {}", WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  const std::string line = last_line(err_text);
  throw InputError(fmt::format("{} failed ({}): {}", what, how, line.empty() ? "no message" : line));
}

}  // namespace tidalcrust
