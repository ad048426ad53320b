#pragma once
// Files for tests: scratch folders (ScratchFolder), whole-file reads and writes, source-tree paths.
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

namespace tidalcrust::test_support {

/// A fresh empty folder below the system temporary folder, removed with its contents when the
/// object goes out of scope. The name holds `name`, the process id and a per-process count, so
/// test binaries of several worktrees running at once, and several folders of one test, never
/// share one.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("tidalcrust_test_" + name + "_" + std::to_string(::getpid()) + "_" + std::to_string(next_number()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }

  const std::filesystem::path path;

 private:
  static int next_number() {
    static std::atomic<int> count{0};
    return count++;
  }
};

/// The bytes of `file` ("" if it cannot be read).
inline std::string read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Replaces the contents of `file` by `bytes`.
inline void write_file(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// `relative` inside the source tree (e.g. "tests/reference/golden.toml").
inline std::filesystem::path source_file(const std::string& relative) {
  return std::filesystem::path(TIDALCRUST_SOURCE_DIR) / relative;
}

/// A workflow file of the repository, e.g. workflow_file("quick.toml").
inline std::filesystem::path workflow_file(const std::string& name) { return source_file("workflows/" + name); }

}  // namespace tidalcrust::test_support
