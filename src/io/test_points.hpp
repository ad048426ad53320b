#pragma once
// Testing aids: kill or hold the process at a point counted in steps or file writes, so that
// tests of interruption (kill -9 mid-write, Ctrl-C inside a stage, SIGTERM to `run --jobs`) hit
// the same moment on any machine at any load. Switched on only by the environment; without it
// every call below is a test of one flag.
//
//   TIDALCRUST_TEST_KILL_AT=step:N   SIGKILL right after the N-th step this process takes
//                                     (every time-stepping loop counts: relax, the stability
//                                     probe, encounters; N >= 1)
//   TIDALCRUST_TEST_KILL_AT=write:N  SIGKILL in the middle of the N-th file this process writes
//                                     atomically (io/atomic_file.hpp): half of its bytes are in
//                                     the temporary, which is never renamed into place
//   TIDALCRUST_TEST_HOLD_AT=step:N   after the N-th step, append the pid as a line to the file
//                                     named by TIDALCRUST_TEST_HOLD_FILE and wait until that file
//                                     is removed or SIGINT/SIGTERM arrives (then the loop stops
//                                     as on any stop)
//   TIDALCRUST_TEST_HOLD_AT=body-check:N  the same hold after the N-th time this process
//                                     checked an output folder's body before locking its first
//                                     stage (stages/workflow.cpp): a file-system stall between
//                                     that check and the lock
//   TIDALCRUST_TEST_READ_EIO=N:K      the N-th to (N+K-1)-th attempt of this process to read a
//                                     checkpoint file's bytes (io/checkpoint_file.cpp, retries
//                                     counted) fails with EIO, as a flaky disk or an NFS hiccup
//                                     makes it (N, K >= 1)
//   TIDALCRUST_TEST_FLOCK_ERROR=NAME flock(2) of a stage lock fails with ENOLCK or EOPNOTSUPP
//                                     (NAME), as on NFS mounted with `nolock` (io/stage_lock.cpp)
//   TIDALCRUST_TEST_CLOCK_SKEW=S      this process's clock, as the stage locks read it, is S
//                                     seconds (an integer, may be negative) off the file
//                                     system's, as a client's clock may be off its NFS server's
//
// These two are read at every call (the unit tests set them within one process). A malformed
// value is an InputError naming the variable.
#include <string_view>

namespace tidalcrust {

/// Counts one step of this process; kills or holds it there when the environment asks.
void test_point_after_step();

/// Counts one check of an output folder's body before its first stage is locked; holds the
/// process there when the environment asks.
void test_point_after_body_check();

/// Counts one attempt to read a checkpoint file's bytes; EIO when the environment asks this
/// attempt to fail, else 0.
int test_point_read_attempt();

/// The errno that flock(2) of a stage lock is to fail with (TIDALCRUST_TEST_FLOCK_ERROR), else 0.
int test_point_flock_error();

/// Seconds to add to this process's clock (TIDALCRUST_TEST_CLOCK_SKEW), else 0.
long test_point_clock_skew();

/// Counts one atomic file write of this process; called when half of its bytes are written.
/// Kills the process there when the environment asks.
void test_point_mid_write();

}  // namespace tidalcrust
