#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "base/errors.hpp"
#include "io/test_points.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

/// InputError "<file>: <what>: <strerror(err)>".
InputError os_error(const fs::path& file, const std::string& what, int err) {
  return InputError(fmt::format("{}: {}: {}", file.string(), what, std::strerror(err)));
}

/// fsync on a file or folder, so that its content (or its directory entries) reach the disk.
/// `file` is the file being replaced, for the message.
void sync_path(const fs::path& file, const fs::path& p, bool directory) {
  const int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC | (directory ? O_DIRECTORY : 0));
  if (fd < 0) throw os_error(file, fmt::format("cannot open {} for fsync", p.string()), errno);
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw os_error(file, fmt::format("fsync of {} failed", p.string()), err);
}

/// Writes all of `text` to the open file `fd` (the temporary `tmp`); closes it on failure.
void write_bytes(const fs::path& file, const fs::path& tmp, int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw os_error(file, fmt::format("cannot write {}", tmp.string()), err);
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

/// Writes all of `text` to a new file `tmp`, in two halves with the testing aid's mid-write
/// point between them (io/test_points.hpp).
void write_all(const fs::path& file, const fs::path& tmp, std::string_view text) {
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw os_error(file, fmt::format("cannot create {}", tmp.string()), errno);
  write_bytes(file, tmp, fd, text.substr(0, text.size() / 2));
  test_point_mid_write();
  write_bytes(file, tmp, fd, text.substr(text.size() / 2));
  if (::close(fd) != 0) throw os_error(file, fmt::format("cannot write {}", tmp.string()), errno);
}

}  // namespace

void replace_file_atomically(const fs::path& file, const std::function<void(const fs::path&)>& write_to) {
  fs::path tmp = file;
  tmp += fmt::format(".tmp-{}", ::getpid());
  const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  try {
    write_to(tmp);
    sync_path(file, tmp, false);
    if (std::rename(tmp.c_str(), file.c_str()) != 0)
      throw os_error(file, fmt::format("cannot rename {} into place", tmp.string()), errno);
    sync_path(file, folder, true);
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

void write_file_atomically(const fs::path& file, std::string_view text) {
  replace_file_atomically(file, [&](const fs::path& tmp) { write_all(file, tmp, text); });
}

}  // namespace tidalcrust
