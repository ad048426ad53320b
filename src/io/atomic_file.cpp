#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <set>

#include "base/errors.hpp"
#include "io/stage_lock.hpp"
#include "io/test_points.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

/// InputError "<file>: <what>: <strerror(err)>".
InputError os_error(const fs::path& file, const std::string& what, int err) {
  return InputError(fmt::format("{}: {}: {}", file.string(), what, std::strerror(err)));
}

/// fsync on a folder, so that its directory entries reach the disk. `file` is the file being
/// replaced, for the message.
void sync_folder(const fs::path& file, const fs::path& folder) {
  const int fd = ::open(folder.c_str(), O_RDONLY | O_CLOEXEC | O_DIRECTORY);
  if (fd < 0) throw os_error(file, fmt::format("cannot open {} for fsync", folder.string()), errno);
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0) throw os_error(file, fmt::format("fsync of {} failed", folder.string()), err);
}

/// Writes all of `text` to the open file `fd` (the temporary `tmp`).
void write_bytes(const fs::path& file, const fs::path& tmp, int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw os_error(file, fmt::format("cannot write {}", tmp.string()), errno);
    text.remove_prefix(static_cast<std::size_t>(n));
  }
}

/// Creates the temporary `tmp` of `file` new, never through a link: O_EXCL does not follow a
/// symbolic link at the name (EEXIST), O_NOFOLLOW makes sure of it. A regular file already there
/// carries this process's pid and host, so an earlier process of that pid left it: replaced.
int create_temporary(const fs::path& file, const fs::path& tmp) {
  for (int attempt = 0;; ++attempt) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0) return fd;
    const int err = errno;
    struct stat info {};
    if (err == EEXIST && attempt == 0 && ::lstat(tmp.c_str(), &info) == 0) {
      if (!S_ISREG(info.st_mode))
        throw InputError(fmt::format("{}: the temporary {} exists and is {}; refusing to write through it", file.string(),
                                     tmp.string(), S_ISLNK(info.st_mode) ? "a symbolic link" : "not a regular file"));
      if (::unlink(tmp.c_str()) == 0 || errno == ENOENT) continue;
    }
    throw os_error(file, fmt::format("cannot create {}", tmp.string()), err);
  }
}

/// The pid and host of a temporary's suffix ("1234" or "1234.host"); false when it is not one.
bool parse_temporary_suffix(const std::string& suffix, long& pid, std::string& host) {
  std::size_t digits = 0;
  while (digits < suffix.size() && suffix[digits] >= '0' && suffix[digits] <= '9') ++digits;
  if (digits == 0 || digits > 18 || (digits < suffix.size() && suffix[digits] != '.')) return false;
  pid = std::strtol(suffix.substr(0, digits).c_str(), nullptr, 10);
  host = digits < suffix.size() ? suffix.substr(digits + 1) : "";
  return pid > 0;
}

/// remove_stale_temporaries once per file and process (the first write of each file).
void remove_stale_temporaries_once(const fs::path& file) {
  static std::mutex mutex;
  static std::set<std::string> done;
  {
    const std::lock_guard<std::mutex> guard(mutex);
    if (!done.insert(file.string()).second) return;
  }
  remove_stale_temporaries(file.parent_path(), file.filename().string() + ".tmp-");
}

}  // namespace

fs::path temporary_path(const fs::path& file) {
  fs::path tmp = file;
  tmp += fmt::format(".tmp-{}.{}", static_cast<long>(::getpid()), host_name());
  return tmp;
}

int remove_stale_temporaries(const fs::path& folder, std::string_view prefix) {
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::size_t at = name.rfind(".tmp-");
    if (!name.starts_with(prefix) || at == std::string::npos || at + 5 < prefix.size()) continue;
    long pid = 0;
    std::string host;
    if (!parse_temporary_suffix(name.substr(at + 5), pid, host)) continue;
    if (host.empty()) host = host_name();  // written before temporaries named their host
    if (pid == static_cast<long>(::getpid()) && host == host_name()) continue;  // this process's own
    if (process_may_be_alive(pid, host)) continue;
    if (::unlink(it->path().c_str()) == 0) ++removed;  // unlink removes a link itself, never its target
  }
  return removed;
}

void replace_file_atomically(const fs::path& file, const std::function<void(int, const fs::path&)>& write_to) {
  remove_stale_temporaries_once(file);
  const fs::path tmp = temporary_path(file);
  const fs::path folder = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  const int fd = create_temporary(file, tmp);
  bool open = true;
  try {
    write_to(fd, tmp);
    if (::fsync(fd) != 0) throw os_error(file, fmt::format("fsync of {} failed", tmp.string()), errno);
    open = false;
    if (::close(fd) != 0) throw os_error(file, fmt::format("cannot write {}", tmp.string()), errno);
    if (std::rename(tmp.c_str(), file.c_str()) != 0)
      throw os_error(file, fmt::format("cannot rename {} into place", tmp.string()), errno);
    sync_folder(file, folder);
  } catch (...) {
    if (open) ::close(fd);
    ::unlink(tmp.c_str());
    throw;
  }
}

void write_file_atomically(const fs::path& file, std::string_view text) {
  // In two halves with the testing aid's mid-write point between them (io/test_points.hpp).
  replace_file_atomically(file, [&](int fd, const fs::path& tmp) {
    write_bytes(file, tmp, fd, text.substr(0, text.size() / 2));
    test_point_mid_write();
    write_bytes(file, tmp, fd, text.substr(text.size() / 2));
  });
}

}  // namespace tidalcrust
