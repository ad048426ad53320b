#pragma once
// Runs the tidalcrust binary as a user would (run_cli: exit code, stdout, stderr; quoted paths).
#include <fmt/format.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
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
/// with stdin from /dev/null.
inline CliResult run_cli(const std::string& args) {
  const ScratchFolder capture("cli");
  const auto out = capture.path / "out.txt", err = capture.path / "err.txt";
  const std::string command =
      fmt::format("'{}' {} >{} 2>{} </dev/null", TIDALCRUST_EXE, args, quoted(out), quoted(err));
  const int status = std::system(command.c_str());
  CliResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = read_file(out);
  result.err = read_file(err);
  return result;
}

inline int count_lines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace tidalcrust::test_support
