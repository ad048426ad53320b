// cli/child_jobs.hpp: a child whose program cannot be executed says so on its stderr, which the
// parent passes on with the job's name, and ends with exit code 127 (issue 28: it was silent).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/child_jobs.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

TEST(ChildJobs, AChildThatCannotStartIsNamedAndExits127) {
  const ScratchFolder scratch("child_jobs_missing");
  const std::string missing = (scratch.path / "no-such-program").string();
  const std::string log = (scratch.path / "stderr.txt").string();
  // The parent writes the children's lines to its stderr: catch them in a file.
  std::fflush(stderr);
  const int saved = dup(2);
  ASSERT_NE(std::freopen(log.c_str(), "w", stderr), nullptr);
  const auto outcomes =
      run_child_jobs(Executable{missing, -1}, {"first"}, 1, [](std::size_t, std::size_t) {
        return std::vector<std::string>{"--help"};
      }, nullptr);
  std::fflush(stderr);
  dup2(saved, 2);
  close(saved);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_EQ(outcomes[0].exit_code, 127);
  const std::string err = read_file(log);
  EXPECT_NE(err.find("[first] cannot start " + missing + ": errno 2"), std::string::npos) << err;
}

TEST(ChildJobs, OwnExecutableIsOpenedAndNamed) {
  const Executable self = own_executable();
  EXPECT_GE(self.fd, 0);
  EXPECT_TRUE(std::filesystem::exists(self.path)) << self.path;
}
