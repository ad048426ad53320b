// I/O failures seen from the command line: a full disk ends every writing command with exit 2,
// one line naming the file and the errno text, no crash, no temporaries, and the checkpoint
// already in the folder untouched.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/cli_runner.hpp"
#include "support/files.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;
using test_support::quoted;
using test_support::run_cli;

/// A small tmpfs mounted on a folder, unmounted (and the folder removed) on destruction.
struct SmallTmpfs {
  explicit SmallTmpfs(const fs::path& where, const std::string& size) : path(where) {
    fs::create_directories(path);
    const std::string command = "mount -t tmpfs -o size=" + size + " tmpfs " + quoted(path) + " 2>/dev/null";
    mounted = std::system(command.c_str()) == 0;
  }
  ~SmallTmpfs() {
    if (mounted) std::system(("umount " + quoted(path)).c_str());
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
  SmallTmpfs(const SmallTmpfs&) = delete;
  SmallTmpfs& operator=(const SmallTmpfs&) = delete;
  fs::path path;
  bool mounted = false;
};

/// Names of files in `folder` (recursively) whose name holds ".tmp".
std::string temporaries_in(const fs::path& folder) {
  std::string found;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.path().filename().string().find(".tmp") != std::string::npos) found += entry.path().string() + " ";
  return found;
}

void expect_disk_full_failure(const test_support::CliResult& r, const std::string& file_part) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  // Progress lines may precede it when a stage runs long; the error is one line, the last.
  std::size_t errors = 0, pos = 0;
  while ((pos = r.err.find("error:", pos)) != std::string::npos) ++errors, ++pos;
  EXPECT_EQ(errors, 1u) << r.err;
  const auto last_line_start = r.err.rfind('\n', r.err.size() >= 2 ? r.err.size() - 2 : 0);
  const std::string last = r.err.substr(last_line_start == std::string::npos ? 0 : last_line_start + 1);
  EXPECT_NE(last.find("error:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(file_part), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
}

TEST(IoFailures, DiskFullEndsEveryWritingCommandWithExit2AndKeepsTheExistingCheckpoint) {
  const test_support::ScratchFolder scratch("diskfull");
  const fs::path body = scratch.path / "b.h5";
  const auto built = run_cli("build --config " + quoted(test_support::workflow_file("quick.toml")) + " --out " +
                             quoted(body));
  ASSERT_EQ(built.exit_code, 0) << built.err;
  const std::string body_bytes = test_support::read_file(body);
  ASSERT_GT(body_bytes.size(), 100000u);

  // Room for the existing checkpoint and its sidecar, not for a second one.
  const SmallTmpfs tiny(scratch.path / "tiny", std::to_string(body_bytes.size() * 3 / 2 / 1024) + "k");
  if (!tiny.mounted) GTEST_SKIP() << "mounting a tmpfs is not permitted here (needs root or CAP_SYS_ADMIN)";
  const fs::path existing = tiny.path / "b.h5";
  fs::copy_file(body, existing);
  fs::copy_file(scratch.path / "b.xdmf", tiny.path / "b.xdmf");
  const std::string sidecar_bytes = test_support::read_file(tiny.path / "b.xdmf");

  // build over the existing checkpoint: the failure must not touch it.
  expect_disk_full_failure(run_cli("build --config " + quoted(test_support::workflow_file("quick.toml")) + " --out " +
                                   quoted(existing)),
                           existing.string());
  // build and stretch into a new file, run into a workflow folder on the full disk.
  expect_disk_full_failure(run_cli("build --config " + quoted(test_support::workflow_file("quick.toml")) + " --out " +
                                   quoted(tiny.path / "other.h5")),
                           (tiny.path / "other.h5").string());
  expect_disk_full_failure(run_cli("stretch --from " + quoted(existing) + " --out " + quoted(tiny.path / "s.h5")),
                           (tiny.path / "s.h5").string());
  expect_disk_full_failure(run_cli("run " + quoted(test_support::workflow_file("quick.toml")) + " --out " +
                                   quoted(tiny.path / "wf")),
                           (tiny.path / "wf").string());

  // relax, encounter (which write mid-stage checkpoints) and analyze, from a finished workflow.
  const fs::path wf = scratch.path / "wf";
  const auto ran = run_cli("run " + quoted(test_support::workflow_file("quick.toml")) + " --out " + quoted(wf));
  ASSERT_EQ(ran.exit_code, 0) << ran.err;
  expect_disk_full_failure(run_cli("relax --from " + quoted(wf / "body/stretch.h5") + " --out " +
                                   quoted(tiny.path / "r.h5")),
                           (tiny.path / "r.").string());  // r.mid.h5 or r.h5
  expect_disk_full_failure(run_cli("encounter --from " + quoted(wf / "body/relax.h5") + " --out " +
                                   quoted(tiny.path / "e.h5") + " --encounter strong"),
                           (tiny.path / "e.").string());  // a snapshot, e.mid.h5 or e.h5
  expect_disk_full_failure(run_cli("analyze --from " + quoted(wf / "strong/encounter.h5") + " --out " +
                                   quoted(tiny.path / "analysis")),
                           (tiny.path / "analysis").string());

  EXPECT_EQ(temporaries_in(tiny.path), "");
  EXPECT_TRUE(test_support::read_file(existing) == body_bytes) << "existing checkpoint changed";
  EXPECT_TRUE(test_support::read_file(tiny.path / "b.xdmf") == sidecar_bytes) << "existing sidecar changed";
  const auto inspected = run_cli("inspect " + quoted(existing));
  EXPECT_EQ(inspected.exit_code, 0) << inspected.err;
}

}  // namespace
}  // namespace tidalcrust
