#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "io/atomic_file.hpp"
#include "support/files.hpp"
#include "support/processes.hpp"

using namespace tidalcrust;
namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// The names in `folder`, to see that no temporary is left behind.
std::vector<std::string> names_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.push_back(entry.path().filename().string());
  return names;
}

}  // namespace

TEST(AtomicFile, WritesAndReplacesAFile) {
  const test_support::ScratchFolder scratch("atomic_replace");
  const fs::path file = scratch.path / "status.json";
  write_file_atomically(file, "first");
  EXPECT_EQ(read_text(file), "first");
  write_file_atomically(file, "second, longer");
  EXPECT_EQ(read_text(file), "second, longer");
  EXPECT_EQ(names_in(scratch.path), std::vector<std::string>{"status.json"});
}

TEST(AtomicFile, FailingWriterLeavesTheFileAndNoTemporary) {
  const test_support::ScratchFolder scratch("atomic_throw");
  const fs::path file = scratch.path / "summary.json";
  write_file_atomically(file, "old");
  EXPECT_THROW(replace_file_atomically(file,
                                       [](int fd, const fs::path&) {
                                         EXPECT_EQ(::write(fd, "half", 4), 4);
                                         throw std::runtime_error("disk full");
                                       }),
               std::runtime_error);
  EXPECT_EQ(read_text(file), "old");
  EXPECT_EQ(names_in(scratch.path), std::vector<std::string>{"summary.json"});
}

TEST(AtomicFile, MissingFolderNamesTheFileAndTheReason) {
  const test_support::ScratchFolder scratch("atomic_missing");
  const fs::path file = scratch.path / "no_such_folder" / "a.txt";
  try {
    write_file_atomically(file, "text");
    FAIL() << "expected an InputError";
  } catch (const InputError& err) {
    const std::string message = err.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("No such file or directory"), std::string::npos) << message;
  }
  EXPECT_EQ(names_in(scratch.path), std::vector<std::string>{});
}

TEST(AtomicFile, ALinkPlantedAsTheTemporaryIsRefusedAndItsTargetKept) {
  // Issue 28: the temporaries FILE.tmp-PID were opened O_CREAT|O_TRUNC and followed a link.
  const test_support::ScratchFolder scratch("atomic_link");
  const fs::path file = scratch.path / "relax.h5";
  const fs::path target = scratch.path / "precious.txt";
  test_support::write_file(target, "the user's data");
  for (const bool dangling : {false, true}) {
    fs::remove(temporary_path(file));
    fs::create_symlink(dangling ? scratch.path / "nothing-here" : target, temporary_path(file));
    try {
      write_file_atomically(file, "new content");
      ADD_FAILURE() << "wrote through a symbolic link";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(temporary_path(file).string()), std::string::npos) << message;
      EXPECT_NE(message.find("symbolic link; refusing"), std::string::npos) << message;
    }
    EXPECT_EQ(read_text(target), "the user's data");
    EXPECT_FALSE(fs::exists(scratch.path / "nothing-here"));
    EXPECT_FALSE(fs::exists(file));
  }
  // A link at the file itself is replaced by the new file (rename), its target kept.
  fs::remove(temporary_path(file));
  fs::create_symlink(target, file);
  write_file_atomically(file, "new content");
  EXPECT_FALSE(fs::is_symlink(file));
  EXPECT_EQ(read_text(file), "new content");
  EXPECT_EQ(read_text(target), "the user's data");
}

TEST(AtomicFile, ALeftoverTemporaryOfThisPidIsReplaced) {
  const test_support::ScratchFolder scratch("atomic_own");
  const fs::path file = scratch.path / "a.json";
  test_support::write_file(temporary_path(file), "half of an earlier process's write");
  write_file_atomically(file, "whole");
  EXPECT_EQ(read_text(file), "whole");
  EXPECT_EQ(names_in(scratch.path), std::vector<std::string>{"a.json"});
}

TEST(AtomicFile, StaleTemporariesOfDeadProcessesAreRemoved) {
  // Issue 28: kills at the checkpoint write left *.tmp-PID files that no later run removed.
  const test_support::ScratchFolder scratch("atomic_stale");
  const fs::path file = scratch.path / "encounter.h5";
  const long dead = test_support::dead_pid();
  const std::string host = test_support::this_host();
  const std::string stale[] = {fmt::format("encounter.h5.tmp-{}.{}", dead, host),
                               fmt::format("encounter.h5.tmp-{}", dead)};  // as written before hosts were named
  const std::string kept[] = {
      fmt::format("encounter.h5.tmp-{}.{}", static_cast<long>(::getppid()), host),  // a live process
      fmt::format("encounter.h5.tmp-{}.another-host", dead),                         // cannot be checked
      fmt::format("encounter.mid.h5.tmp-{}.{}", dead, host),                         // another file's
      "encounter.h5.tmp-notapid", "encounter.h5"};
  for (const auto& name : stale) test_support::write_file(scratch.path / name, "half");
  for (const auto& name : kept) test_support::write_file(scratch.path / name, "kept");
  EXPECT_EQ(remove_stale_temporaries(scratch.path, "encounter.h5.tmp-"), 2);
  for (const auto& name : stale) EXPECT_FALSE(fs::exists(scratch.path / name)) << name;
  for (const auto& name : kept) EXPECT_TRUE(fs::exists(scratch.path / name)) << name;
  // The first write of a file in a process removes its stale temporaries too.
  const fs::path other = scratch.path / "status.json";
  const std::string left = fmt::format("status.json.tmp-{}.{}", dead, host);
  test_support::write_file(scratch.path / left, "half");
  write_file_atomically(other, "{}");
  EXPECT_FALSE(fs::exists(scratch.path / left));
  // A prefix covers a stage's family of files (run_stage: "encounter." when it takes the lock).
  EXPECT_EQ(remove_stale_temporaries(scratch.path, "encounter."), 1);  // encounter.mid.h5's
  EXPECT_TRUE(fs::exists(scratch.path / kept[0]));
  EXPECT_TRUE(fs::exists(scratch.path / kept[1]));
}
