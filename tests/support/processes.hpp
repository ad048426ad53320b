#pragma once
// Processes for lock tests: the pid of a process that no longer runs (dead_pid), this host's name.
#include <sys/wait.h>
#include <unistd.h>

#include <string>

namespace tidalcrust::test_support {

/// The pid of a child process that has already exited and been reaped: no process has it (until
/// the system reuses it, which takes a full turn of the pid space).
inline long dead_pid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  int status = 0;
  waitpid(pid, &status, 0);
  return pid;
}

/// gethostname(2), as the lock files record it.
inline std::string this_host() {
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  return name;
}

}  // namespace tidalcrust::test_support
