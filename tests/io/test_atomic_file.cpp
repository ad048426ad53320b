#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "io/atomic_file.hpp"
#include "support/files.hpp"

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
                                       [](const fs::path& tmp) {
                                         std::ofstream(tmp) << "half";
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
