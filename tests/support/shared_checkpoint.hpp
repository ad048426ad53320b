#pragma once
// Checkpoints and run folders that tests of several processes need, made once per build of the
// test binary.
// ctest runs every test in a process of its own, so a function-local static alone recomputes a
// relaxed body for each test that reads it.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "io/checkpoint_file.hpp"
#include "model/checkpoint.hpp"
#include "support/files.hpp"

namespace tidalcrust::test_support {

namespace detail {

/// Holds an exclusive flock on `file` (created if missing) while alive; `held` is false if the
/// file cannot be opened or locked.
class FileLock {
 public:
  explicit FileLock(const std::filesystem::path& file) : fd_(::open(file.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
    held = fd_ >= 0 && ::flock(fd_, LOCK_EX) == 0;
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the lock
  }
  bool held = false;

 private:
  int fd_;
};

/// build/test-cache/<identity of this binary>, or "" without TIDALCRUST_TEST_CACHE. The identity is
/// the device, inode, size and modification time of /proc/self/exe: a rebuilt binary gets a new
/// folder, and the folders of earlier builds are removed when it is made.
inline std::filesystem::path cache_folder() {
  const char* root = std::getenv("TIDALCRUST_TEST_CACHE");
  struct stat exe {};
  if (!root || !*root || ::stat("/proc/self/exe", &exe) != 0) return {};
  const std::string identity = std::to_string(exe.st_dev) + "-" + std::to_string(exe.st_ino) + "-" +
                               std::to_string(exe.st_size) + "-" + std::to_string(exe.st_mtim.tv_sec) + "." +
                               std::to_string(exe.st_mtim.tv_nsec);
  const std::filesystem::path folder = std::filesystem::path(root) / identity;
  std::error_code error;
  if (std::filesystem::is_directory(folder, error)) return folder;
  std::filesystem::create_directories(root, error);
  const FileLock lock(std::filesystem::path(root) / ".lock");
  if (!lock.held) return {};
  for (const auto& entry : std::filesystem::directory_iterator(root, error))
    if (entry.is_directory() && entry.path().filename() != identity) std::filesystem::remove_all(entry.path(), error);
  std::filesystem::create_directories(folder, error);
  return error ? std::filesystem::path() : folder;
}

}  // namespace detail

/// The folder `name` after fill(folder) has filled it, once per build of the test binary: with
/// TIDALCRUST_TEST_CACHE set (ctest sets build/test-cache) the first process fills
/// <cache>/<binary identity>/NAME and marks it complete, the others wait on a lock while it does and
/// then use it; an incomplete folder (a process killed while filling) is emptied and filled again.
/// Without the variable (the binary run by hand), or where the cache cannot be used, a scratch
/// folder of this process, removed at its exit.
inline std::filesystem::path shared_folder(const std::string& name,
                                           const std::function<void(const std::filesystem::path&)>& fill) {
  const std::filesystem::path root = detail::cache_folder();
  std::optional<detail::FileLock> lock;
  if (!root.empty()) lock.emplace(root / (name + ".lock"));
  if (!lock || !lock->held) {
    static std::vector<std::unique_ptr<ScratchFolder>> kept;  // alive until the process ends
    kept.push_back(std::make_unique<ScratchFolder>(name));
    fill(kept.back()->path);
    return kept.back()->path;
  }
  const std::filesystem::path folder = root / name, complete = root / (name + ".complete");
  if (std::filesystem::exists(complete)) return folder;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  fill(folder);
  std::ofstream(complete) << "complete\n";
  return folder;
}

/// compute(), once per build of the test binary (shared_folder: NAME/checkpoint.h5): every test
/// process, the first included, reads the stored file, so every test sees the same bits (the round
/// trip keeps every bit: tests Checkpoint.RoundTrip*).
inline Checkpoint shared_checkpoint(const std::string& name, const std::function<Checkpoint()>& compute) {
  const std::filesystem::path folder =
      shared_folder(name, [&](const std::filesystem::path& f) { write_checkpoint(f / "checkpoint.h5", compute()); });
  return read_checkpoint(folder / "checkpoint.h5");
}

}  // namespace tidalcrust::test_support
