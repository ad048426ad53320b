#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/json.hpp"
#include "io/progress.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
namespace fs = std::filesystem;

// A resumed stage's line gives the share of the whole stage done (not of this process's part),
// and the status file says where the stage began and where this process took it up.
TEST(Progress, AResumedStageReportsItsShareOfTheWholeStage) {
  const test_support::ScratchFolder scratch("progress_resumed");
  const fs::path status = scratch.path / "status.json";
  ProgressReporter line("encounter T5", 100, 900, 1100, status);
  testing::internal::CaptureStderr();
  line.update(1000, true);
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_NE(printed.find("encounter T5: step 1000 of 1100 (90%)"), std::string::npos) << printed;

  std::ifstream in(status);
  const Json written = Json::parse(in);
  EXPECT_EQ(written.at("first_step"), 100);
  EXPECT_EQ(written.at("start_step"), 900);
  EXPECT_EQ(written.at("step"), 1000);
  EXPECT_EQ(written.at("last_step"), 1100);
  EXPECT_EQ(written.at("state"), "running");
}
