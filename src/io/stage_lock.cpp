#include "io/stage_lock.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <xxhash.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>

#include "base/errors.hpp"
#include "io/test_points.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

/// Makes a held StageLock (the only way one is made).
struct StageLockAccess {
  static LockAttempt held(const fs::path& path, int fd, LockMethod method, std::optional<LockHolder> taken_over) {
    LockAttempt taken;
    taken.lock.emplace();
    taken.lock->path_ = path;
    taken.lock->fd_ = fd;
    taken.lock->method_ = method;
    taken.lock->taken_over_from_ = std::move(taken_over);
    return taken;
  }
};

namespace {

/// A lock file of the exclusive_create method that names no holder and is older than this was
/// abandoned by a process that died between creating and writing it (seconds, measured by the
/// file system's clock: unnamed_lock_age).
constexpr long abandoned_unnamed_lock_age = 10;

InputError os_error(const fs::path& file, const std::string& what, int err) {
  return InputError(fmt::format("{}: {}: {}", file.string(), what, std::strerror(err)));
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr) + test_point_clock_skew();
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

std::string holder_text(const std::string& identity) {
  return fmt::format("pid={}\nhost={}\nsince={}\nidentity={}\n", static_cast<long>(::getpid()), host_name(), utc_now(),
                     identity);
}

/// The holder written in a lock file; nothing unless all four lines are there (a file being
/// written, empty or foreign).
std::optional<LockHolder> parse_holder(const std::string& text) {
  LockHolder holder;
  int seen = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // an unfinished last line
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    if (key == "pid") {
      char* stop = nullptr;
      holder.pid = std::strtol(value.c_str(), &stop, 10);
      if (stop == value.c_str() || *stop != '\0') return std::nullopt;
      seen |= 1;
    } else if (key == "host") {
      holder.host = value, seen |= 2;
    } else if (key == "since") {
      holder.since = value, seen |= 4;
    } else if (key == "identity") {
      holder.identity = value, seen |= 8;
    }
  }
  if (seen != 15) return std::nullopt;
  return holder;
}

std::string read_fd(int fd) {
  std::string text;
  char buffer[1024];
  for (off_t offset = 0; text.size() < 8192;) {
    const ssize_t n = ::pread(fd, buffer, sizeof buffer, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buffer, static_cast<std::size_t>(n));
    offset += n;
  }
  return text;
}

void write_holder(const fs::path& path, int fd, const std::string& identity) {
  const std::string text = holder_text(identity);
  if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) != static_cast<ssize_t>(text.size()))
    throw os_error(path, "cannot write the lock file", errno);
}

bool may_be_alive(const LockHolder& holder) { return process_may_be_alive(holder.pid, holder.host); }

/// InputError unless the open lock file `fd` is a regular file with no other name: a hard link
/// to another file would have that file truncated and overwritten with the holder's lines.
void check_plain_lock_file(const fs::path& path, int fd) {
  struct stat info {};
  if (::fstat(fd, &info) != 0) throw os_error(path, "cannot examine the lock file", errno);
  if (!S_ISREG(info.st_mode) || info.st_nlink != 1)
    throw InputError(fmt::format("{}: the lock file is {}; refusing to write to it (remove it if it is not yours)",
                                 path.string(), S_ISREG(info.st_mode) ? "a hard link to another file" : "not a regular file"));
}

/// The errno of a failed open of the lock file as an InputError; a symbolic link at its name
/// (O_NOFOLLOW: ELOOP) is refused, never followed.
InputError lock_open_error(const fs::path& path, const char* what, int err) {
  if (err == ELOOP)
    return InputError(fmt::format("{}: the lock file is a symbolic link; refusing to follow it (remove it if it is "
                                  "not yours)",
                                  path.string()));
  return os_error(path, what, err);
}

/// How old (seconds) the lock file `existing` (its fstat) is by the clock of the file system
/// that holds it: its mtime against that of a file created there now (`<lock>.clock-<pid>.<host>`), not
/// against this process's clock, which may be off the file server's by any amount. Nothing when
/// no file can be created there (then the lock is not judged abandoned).
std::optional<long> unnamed_lock_age(const fs::path& path, const struct stat& existing) {
  fs::path probe = path;
  probe += fmt::format(".clock-{}.{}", static_cast<long>(::getpid()), host_name());
  const int fd = ::open(probe.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) return std::nullopt;
  struct stat now {};
  const bool measured = ::fstat(fd, &now) == 0;
  ::close(fd);
  ::unlink(probe.c_str());
  if (!measured) return std::nullopt;
  return static_cast<long>(now.st_mtime - existing.st_mtime);
}

/// Writes this process's holder lines into the lock file `fd` it has just created (O_EXCL) and
/// returns the lock held by its existence; on failure removes the file.
LockAttempt hold_created(const fs::path& path, int fd, const std::string& identity,
                         std::optional<LockHolder> taken_over) {
  try {
    write_holder(path, fd, identity);
  } catch (...) {
    ::close(fd);
    ::unlink(path.c_str());
    throw;
  }
  ::close(fd);
  return StageLockAccess::held(path, -1, LockMethod::exclusive_create, std::move(taken_over));
}

LockAttempt try_exclusive_create(const fs::path& path, const std::string& identity) {
  std::optional<LockHolder> taken_over;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0) return hold_created(path, fd, identity, taken_over);
    if (errno != EEXIST) throw lock_open_error(path, "cannot create the lock file", errno);
    const int existing = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (existing < 0 && errno == ELOOP) throw lock_open_error(path, "", ELOOP);
    if (existing < 0) continue;  // released meanwhile
    struct stat info {};
    const bool examined = ::fstat(existing, &info) == 0;
    const std::optional<LockHolder> holder = parse_holder(read_fd(existing));
    ::close(existing);
    std::optional<long> age;
    if (!holder && examined) age = unnamed_lock_age(path, info);
    const bool gone = holder ? !may_be_alive(*holder) : age && *age > abandoned_unnamed_lock_age;
    if (!gone) return {std::nullopt, holder.value_or(LockHolder{})};
    // Move the dead holder's file aside: rename is atomic, so of several processes that found
    // it dead only one moves it, and the others then see the new holder's file or none.
    fs::path aside = path;
    aside += fmt::format(".stale-{}", static_cast<long>(::getpid()));
    if (std::rename(path.c_str(), aside.c_str()) == 0) {
      ::unlink(aside.c_str());
      taken_over = holder.value_or(LockHolder{});
    }
  }
  throw InputError(fmt::format("{}: cannot take the lock: the lock file keeps changing", path.string()));
}

}  // namespace

std::string host_name() {
  char buffer[256] = {};
  if (::gethostname(buffer, sizeof buffer - 1) != 0) return "unknown";
  return buffer;
}

bool process_may_be_alive(long pid, const std::string& host) {
  if (host != host_name()) return true;
  if (pid <= 0) return false;
  return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

std::string LockHolder::describe() const {
  if (pid <= 0) return "a process that has not named itself";
  return fmt::format("pid {} on host {} (since {})", pid, host, since);
}

fs::path lock_path(const fs::path& stage_file) {
  fs::path p = stage_file;
  p += ".lock";
  return p;
}

std::string stage_lock_identity(const std::string& fingerprint, const std::string& parent_hash) {
  const std::string text = fingerprint + '\n' + parent_hash;
  return fmt::format("{:016x}", static_cast<unsigned long long>(XXH3_64bits(text.data(), text.size())));
}

StageLock::StageLock(StageLock&& other) noexcept
    : path_(std::move(other.path_)), fd_(other.fd_), method_(other.method_),
      taken_over_from_(std::move(other.taken_over_from_)) {
  other.path_.clear();
  other.fd_ = -1;
}

StageLock& StageLock::operator=(StageLock&& other) noexcept {
  if (this != &other) {
    release();
    path_ = std::move(other.path_);
    fd_ = other.fd_;
    method_ = other.method_;
    taken_over_from_ = std::move(other.taken_over_from_);
    other.path_.clear();
    other.fd_ = -1;
  }
  return *this;
}

StageLock::~StageLock() { release(); }

std::string StageLock::takeover_note() const {
  if (!taken_over_from_) return "";
  return fmt::format("{}: took over the stale lock of {}, which no longer runs", path_.string(),
                     taken_over_from_->describe());
}

void StageLock::release() {
  if (path_.empty()) return;
  // Remove the file while still holding it: a process waiting on this inode then finds the path
  // gone or replaced and tries again on the new file.
  ::unlink(path_.c_str());
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  path_.clear();
}

LockAttempt try_lock_stage(const fs::path& stage_file, const std::string& identity, LockMethod method) {
  const fs::path path = lock_path(stage_file);
  if (method == LockMethod::exclusive_create) return try_exclusive_create(path, identity);
  for (int attempt = 0; attempt < 100; ++attempt) {
    // Never through a link: O_NOFOLLOW refuses a symbolic link at the name (ELOOP), and an
    // existing file must be a plain one (check_plain_lock_file) before it is truncated.
    int fd = ::open(path.c_str(), O_RDWR | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0 && errno == ELOOP) throw lock_open_error(path, "", ELOOP);
    const bool existed = fd >= 0;
    if (!existed) fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0 && errno == EEXIST) continue;  // made by another process meanwhile
    if (fd < 0) throw lock_open_error(path, "cannot create the lock file", errno);
    try {
      check_plain_lock_file(path, fd);
    } catch (...) {
      ::close(fd);
      throw;
    }
    const int injected = test_point_flock_error();
    if (injected != 0 || ::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = injected != 0 ? injected : errno;
      if (err == EWOULDBLOCK) {
        const std::optional<LockHolder> holder = parse_holder(read_fd(fd));
        ::close(fd);
        return {std::nullopt, holder.value_or(LockHolder{})};
      }
      if (err == ENOLCK || err == EOPNOTSUPP || err == ENOSYS) {
        // No locks here: the lock is the file's existence. A file this call has just created
        // (O_EXCL) is already that lock: it is ours, not one "that names nobody" to wait for.
        if (!existed) return hold_created(path, fd, identity, std::nullopt);
        ::close(fd);
        return try_exclusive_create(path, identity);
      }
      ::close(fd);
      throw os_error(path, "cannot lock the lock file", err);
    }
    // The holder we waited for may have removed the file between our open and our flock: then
    // we hold a lock on a file nobody else will see; start again on the current one.
    struct stat held {}, current {};
    if (::fstat(fd, &held) != 0 || ::stat(path.c_str(), &current) != 0 || held.st_ino != current.st_ino ||
        held.st_dev != current.st_dev) {
      ::close(fd);
      continue;
    }
    // A lock file that exists and is not locked was left by a holder that died (a finished
    // holder removes it).
    std::optional<LockHolder> taken_over;
    if (existed) taken_over = parse_holder(read_fd(fd)).value_or(LockHolder{});
    LockAttempt taken = StageLockAccess::held(path, fd, LockMethod::flock, std::move(taken_over));
    write_holder(path, fd, identity);  // on failure the lock is released (file removed)
    return taken;
  }
  throw InputError(fmt::format("{}: cannot take the lock: the lock file keeps changing", path.string()));
}

}  // namespace tidalcrust
