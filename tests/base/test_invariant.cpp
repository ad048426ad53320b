#include "base/invariant.hpp"

#include <gtest/gtest.h>

#include <string>

#include "base/errors.hpp"

namespace tidalcrust {
namespace {

int calls = 0;
std::string counted(const char* text) {
  ++calls;
  return text;
}

}  // namespace

TEST(Invariant, HoldingCheckThrowsNothingAndBuildsNoMessage) {
  calls = 0;
  EXPECT_NO_THROW(TIDALCRUST_ASSERT(1 + 1 == 2, counted("never")));
  EXPECT_EQ(calls, 0);  // the message is built only on failure
}

TEST(Invariant, BrokenCheckIsAnInternalErrorWithFileAndLine) {
  const int line = __LINE__ + 2;
  try {
    TIDALCRUST_ASSERT(2 < 1, std::string("two is not below one"));
    FAIL() << "no throw";
  } catch (const InternalError& e) {
    EXPECT_EQ(std::string(e.what()), "two is not below one (tests/base/test_invariant.cpp:" + std::to_string(line) + ")");
  }
}

TEST(Invariant, InternalErrorIsNeitherBadInputNorASimulationFailure) {
  // src/cli/main.cpp sorts by type: InputError exits 2, SimulationError 1 ("simulation failed"),
  // any other std::exception 1 with "internal error: <what>".
  bool input = false, simulation = false, other = false;
  try {
    TIDALCRUST_ASSERT(false, "x");
  } catch (const InputError&) {
    input = true;
  } catch (const SimulationError&) {
    simulation = true;
  } catch (const std::exception&) {
    other = true;
  }
  EXPECT_FALSE(input);
  EXPECT_FALSE(simulation);
  EXPECT_TRUE(other);
  EXPECT_EQ(exit_simulation_failure, 1);
}

}  // namespace tidalcrust
