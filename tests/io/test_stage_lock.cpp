// Stage locks (io/stage_lock.hpp): a held lock names its holder to the next process, a released
// one leaves no file, the lock file of a process that died is taken over; the same with the
// O_CREAT|O_EXCL fallback for file systems without locks (ENOLCK), which can tell a dead holder
// only on its own host.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "base/errors.hpp"
#include "io/stage_lock.hpp"
#include "support/files.hpp"
#include "support/processes.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

std::string lock_text(long pid, const std::string& host, const std::string& identity) {
  return "pid=" + std::to_string(pid) + "\nhost=" + host + "\nsince=2026-01-01T00:00:00Z\nidentity=" + identity + "\n";
}

class StageLockTest : public ::testing::TestWithParam<LockMethod> {};

}  // namespace

TEST_P(StageLockTest, HeldLockNamesItsHolderAndReleaseRemovesTheFile) {
  const ScratchFolder scratch("lock_held");
  const fs::path stage = scratch.path / "relax.h5";
  LockAttempt first = try_lock_stage(stage, "abc", GetParam());
  ASSERT_TRUE(first.lock);
  EXPECT_FALSE(first.holder);
  EXPECT_EQ(first.lock->path(), scratch.path / "relax.h5.lock");
  EXPECT_FALSE(first.lock->taken_over_from());
  EXPECT_TRUE(fs::exists(lock_path(stage)));

  // flock conflicts between two open file descriptions even within one process.
  const LockAttempt second = try_lock_stage(stage, "other", GetParam());
  ASSERT_FALSE(second.lock);
  ASSERT_TRUE(second.holder);
  EXPECT_EQ(second.holder->pid, static_cast<long>(getpid()));
  EXPECT_EQ(second.holder->host, this_host());
  EXPECT_EQ(second.holder->identity, "abc");
  EXPECT_NE(second.holder->describe().find("pid " + std::to_string(getpid()) + " on host " + this_host() + " (since "),
            std::string::npos)
      << second.holder->describe();

  first.lock->release();
  EXPECT_FALSE(fs::exists(lock_path(stage)));
  const LockAttempt third = try_lock_stage(stage, "other", GetParam());
  ASSERT_TRUE(third.lock);
  EXPECT_FALSE(third.lock->taken_over_from());
}

TEST_P(StageLockTest, LockFileOfADeadProcessIsTakenOver) {
  const ScratchFolder scratch("lock_dead");
  const fs::path stage = scratch.path / "build.h5";
  const long dead = dead_pid();
  write_file(lock_path(stage), lock_text(dead, this_host(), "abc"));
  const LockAttempt attempt = try_lock_stage(stage, "new", GetParam());
  ASSERT_TRUE(attempt.lock);
  ASSERT_TRUE(attempt.lock->taken_over_from());
  EXPECT_EQ(attempt.lock->taken_over_from()->pid, dead);
  EXPECT_NE(attempt.lock->takeover_note().find("took over the stale lock of pid " + std::to_string(dead)),
            std::string::npos)
      << attempt.lock->takeover_note();
  // The file now names the new holder.
  EXPECT_NE(read_file(lock_path(stage)).find("identity=new\n"), std::string::npos);
}

TEST_P(StageLockTest, ALinkPlantedAsTheLockFileIsRefusedAndItsTargetKept) {
  // Issue 28: a symbolic link at OUT/body/build.h5.lock had its target truncated and overwritten
  // with the lock's text. Neither a symbolic link (dangling or not) nor a hard link is written to.
  const ScratchFolder scratch("lock_link");
  const fs::path stage = scratch.path / "build.h5";
  const fs::path target = scratch.path / "precious.txt";
  write_file(target, "the user's data\n");
  for (const bool hard : {false, true}) {
    for (const bool dangling : {false, true}) {
      if (hard && dangling) continue;
      fs::remove(lock_path(stage));
      if (hard) fs::create_hard_link(target, lock_path(stage));
      else fs::create_symlink(dangling ? scratch.path / "nothing-here" : target, lock_path(stage));
      // The exclusive-create method never writes to a file it did not create: a hard link
      // there is only a lock file naming nobody (its target stays as it is).
      const bool must_refuse = !hard || GetParam() == LockMethod::flock;
      try {
        const LockAttempt attempt = try_lock_stage(stage, "abc", GetParam());
        if (must_refuse) ADD_FAILURE() << "locked through a " << (hard ? "hard" : "symbolic") << " link";
      } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(lock_path(stage).string()), std::string::npos) << message;
        EXPECT_NE(message.find("refusing"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      }
      EXPECT_EQ(read_file(target), "the user's data\n");
      EXPECT_FALSE(fs::exists(scratch.path / "nothing-here"));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BothMethods, StageLockTest,
                         ::testing::Values(LockMethod::flock, LockMethod::exclusive_create));

TEST(StageLock, FlockTakesOverAnUnlockedFileThatNamesNobody) {
  const ScratchFolder scratch("lock_empty");
  const fs::path stage = scratch.path / "relax.h5";
  write_file(lock_path(stage), "");
  const LockAttempt attempt = try_lock_stage(stage, "x");
  ASSERT_TRUE(attempt.lock);
  ASSERT_TRUE(attempt.lock->taken_over_from());
  EXPECT_EQ(attempt.lock->taken_over_from()->pid, 0);
}

// Without locks the file's existence is the lock: a living holder on this host, or any holder on
// another host (whose liveness cannot be checked), keeps it.
TEST(StageLock, ExclusiveCreateRespectsLivingAndRemoteHolders) {
  const ScratchFolder scratch("lock_excl");
  const fs::path stage = scratch.path / "encounter.h5";
  write_file(lock_path(stage), lock_text(getppid(), this_host(), "abc"));
  LockAttempt attempt = try_lock_stage(stage, "abc", LockMethod::exclusive_create);
  ASSERT_TRUE(attempt.holder);
  EXPECT_EQ(attempt.holder->pid, static_cast<long>(getppid()));

  write_file(lock_path(stage), lock_text(dead_pid(), "another-host.example", "abc"));
  attempt = try_lock_stage(stage, "abc", LockMethod::exclusive_create);
  ASSERT_TRUE(attempt.holder);
  EXPECT_EQ(attempt.holder->host, "another-host.example");
}

namespace {

/// Sets the environment variable `name` for one scope (the testing aids of io/test_points.hpp).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) { ::setenv(name, value.c_str(), 1); }
  ~ScopedEnv() { ::unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};

/// Sets the mtime of `file` to `seconds` before now.
void age_file(const fs::path& file, long seconds) {
  struct timespec times[2] = {{0, UTIME_OMIT}, {0, 0}};
  times[1].tv_sec = ::time(nullptr) - seconds;
  ASSERT_EQ(::utimensat(AT_FDCWD, file.c_str(), times, 0), 0);
}

}  // namespace

// Issue 28, item 7: where flock is not supported (ENOLCK, EOPNOTSUPP: NFS mounted with
// `nolock`) the lock file that try_lock_stage has just created is its own lock, held at once: it
// is not taken for one "of a process that has not named itself" and waited for (10 s per stage).
TEST(StageLock, WithoutFlockTheLockFileJustCreatedIsItsOwn) {
  for (const char* error : {"ENOLCK", "EOPNOTSUPP"}) {
    const ScopedEnv no_flock("TIDALCRUST_TEST_FLOCK_ERROR", error);
    const ScratchFolder scratch("lock_noflock");
    const fs::path stage = scratch.path / "relax.h5";
    LockAttempt first = try_lock_stage(stage, "abc");
    ASSERT_TRUE(first.lock) << error;
    EXPECT_EQ(first.lock->method(), LockMethod::exclusive_create) << error;
    EXPECT_FALSE(first.lock->taken_over_from()) << error;
    EXPECT_EQ(first.lock->takeover_note(), "") << error;
    const LockAttempt second = try_lock_stage(stage, "abc");
    ASSERT_TRUE(second.holder) << error;
    EXPECT_EQ(second.holder->pid, static_cast<long>(getpid())) << error;
    EXPECT_EQ(second.holder->identity, "abc") << error;
    first.lock->release();
    EXPECT_FALSE(fs::exists(lock_path(stage))) << error;
    // A file that was there before (of another process) is not taken for our own.
    write_file(lock_path(stage), lock_text(getppid(), this_host(), "abc"));
    const LockAttempt third = try_lock_stage(stage, "abc");
    ASSERT_TRUE(third.holder) << error;
    EXPECT_EQ(third.holder->pid, static_cast<long>(getppid())) << error;
  }
}

// Issue 28, item 7: a lock file that names nobody (its creator died before writing it) is
// abandoned after 10 s by the file system's clock, whatever this process's clock says (a client's
// clock may be off its NFS server's by hours): judged against a file created there now.
TEST(StageLock, TheAgeOfAnUnnamedLockIsMeasuredByTheFileSystemsClock) {
  const ScratchFolder scratch("lock_skew");
  const fs::path stage = scratch.path / "encounter.h5";
  for (const long skew : {3600L, -3600L, 0L}) {
    const ScopedEnv skewed("TIDALCRUST_TEST_CLOCK_SKEW", std::to_string(skew));
    write_file(lock_path(stage), "");  // just created: young, whatever our clock says
    const LockAttempt young = try_lock_stage(stage, "abc", LockMethod::exclusive_create);
    ASSERT_TRUE(young.holder) << "skew " << skew << ": a lock file created just now was taken over";
    EXPECT_EQ(young.holder->pid, 0);
    age_file(lock_path(stage), 30);  // 30 s old on the file system: abandoned
    const LockAttempt old = try_lock_stage(stage, "abc", LockMethod::exclusive_create);
    ASSERT_TRUE(old.lock) << "skew " << skew << ": a lock file 30 s old was not taken over";
    ASSERT_TRUE(old.lock->taken_over_from());
    EXPECT_EQ(old.lock->taken_over_from()->pid, 0);
  }
  for (const auto& entry : fs::directory_iterator(scratch.path))
    EXPECT_EQ(entry.path().filename().string().find(".clock-"), std::string::npos) << entry.path();
}

TEST(StageLock, IdentityDependsOnFingerprintAndParent) {
  EXPECT_EQ(stage_lock_identity("a = 1", "p"), stage_lock_identity("a = 1", "p"));
  EXPECT_NE(stage_lock_identity("a = 1", "p"), stage_lock_identity("a = 2", "p"));
  EXPECT_NE(stage_lock_identity("a = 1", "p"), stage_lock_identity("a = 1", "q"));
  EXPECT_EQ(stage_lock_identity("", "").size(), 16u);
}

TEST(StageLock, UncreatableLockFileIsAnInputErrorNamingIt) {
  const ScratchFolder scratch("lock_nofolder");
  const fs::path stage = scratch.path / "missing" / "relax.h5";
  try {
    try_lock_stage(stage, "x");
    FAIL() << "no error";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("relax.h5.lock: cannot create the lock file: No such file or directory"),
              std::string::npos)
        << err.what();
  }
}
