#pragma once
// The lock of a stage being computed: a file `<stage>.h5.lock` beside the stage's checkpoint,
// held with flock(2) (the kernel releases it when the holder dies, also over NFSv4) and holding
// the holder's pid, host, start time and the identity of what it computes (a digest of the
// stage's fingerprint and parent), so that another process can name the holder and tell whether
// it computes the same version of the stage (wait for it) or another one (refuse). Where the file
// system has no locks (flock fails with ENOLCK or EOPNOTSUPP) the lock is the file's existence
// instead (O_CREAT|O_EXCL; the file just created for the flock is already it); a holder that died
// is then recognised only on the same host (by its pid), and a file that names nobody is
// abandoned after 10 s by the file system's clock (not this process's).
// Limits: docs/architecture.md, "Locks".
#include <filesystem>
#include <optional>
#include <string>

namespace tidalcrust {

/// Who holds (or held) a stage lock, as written inside the lock file.
struct LockHolder {
  long pid = 0;
  std::string host;
  std::string since;     ///< UTC start of the holding, ISO 8601
  std::string identity;  ///< what it computes (stage_lock_identity); empty for a single-stage command
  /// "pid 1234 on host h (since 2026-01-01T12:00:00Z)".
  std::string describe() const;
};

/// This machine's host name (gethostname), as lock files and temporaries record it.
std::string host_name();

/// False only when the process `pid` of `host` is known to be gone: a process of this host that
/// no longer exists (pid <= 0 counts as gone). A process of another host cannot be checked and
/// counts as alive. Stale locks and stale temporaries (io/atomic_file.hpp) are judged by it.
bool process_may_be_alive(long pid, const std::string& host);

/// How the lock is held: flock(2), or (no locks on the file system) the lock file's existence.
enum class LockMethod { flock, exclusive_create };

/// `<stage_file>.lock`, e.g. body/relax.h5.lock.
std::filesystem::path lock_path(const std::filesystem::path& stage_file);

/// 16 hex digits naming one version of a stage: a digest of its fingerprint and parent hash.
std::string stage_lock_identity(const std::string& fingerprint, const std::string& parent_hash);

struct LockAttempt;

/// A held stage lock; released (lock file removed) when destroyed or by release().
class StageLock {
 public:
  StageLock() = default;
  StageLock(StageLock&& other) noexcept;
  StageLock& operator=(StageLock&& other) noexcept;
  StageLock(const StageLock&) = delete;
  StageLock& operator=(const StageLock&) = delete;
  ~StageLock();

  /// Removes the lock file and drops the lock (idempotent).
  void release();
  bool held() const { return !path_.empty(); }
  const std::filesystem::path& path() const { return path_; }
  LockMethod method() const { return method_; }
  /// The holder recorded in a lock file left behind by a process that no longer runs, which
  /// this lock took over (pid 0 and no host when the file named nobody).
  const std::optional<LockHolder>& taken_over_from() const { return taken_over_from_; }
  /// One line for stderr when the lock was taken over ("<lock>: took over the stale lock of
  /// <holder>, which no longer runs"), else empty.
  std::string takeover_note() const;

 private:
  friend struct StageLockAccess;  // try_lock_stage makes the held locks
  std::filesystem::path path_;
  int fd_ = -1;
  LockMethod method_ = LockMethod::flock;
  std::optional<LockHolder> taken_over_from_;
};

/// One attempt, without waiting: exactly one of `lock` (taken) and `holder` (held by another
/// process; its pid is 0 when it has not yet written its name) is set.
struct LockAttempt {
  std::optional<StageLock> lock;
  std::optional<LockHolder> holder;
};

/// Tries to lock the stage whose checkpoint is `stage_file`, for computing the version
/// `identity`. With LockMethod::flock it falls back to exclusive_create when the file system
/// has no locks (ENOLCK, EOPNOTSUPP). InputError (naming the lock file and the errno text) when
/// the lock file cannot be created.
LockAttempt try_lock_stage(const std::filesystem::path& stage_file, const std::string& identity,
                           LockMethod method = LockMethod::flock);

}  // namespace tidalcrust
