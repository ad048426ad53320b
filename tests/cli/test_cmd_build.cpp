// `tidalcrust build` as a user runs it: same config and seed give the same state_hash, another
// seed another; bad input exits 2 with one line naming the file or key and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/state_hash.hpp"
#include "model/config.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

std::string quick() { return workflow_file("quick.toml").string(); }

}  // namespace

TEST(BuildCli, SameSeedSameHashOtherSeedOtherHash) {
  const ScratchFolder scratch("build_seed");
  const fs::path& dir = scratch.path;
  ASSERT_EQ(run_cli("build --config '" + quick() + "' --out '" + (dir / "a.h5").string() + "'").exit_code, 0);
  ASSERT_EQ(run_cli("build --config '" + quick() + "' --out '" + (dir / "b.h5").string() + "'").exit_code, 0);
  ASSERT_EQ(run_cli("build --config '" + quick() + "' --set workflow.seed=8 --out '" + (dir / "c.h5").string() + "'")
                .exit_code,
            0);
  const auto a = read_checkpoint(dir / "a.h5"), b = read_checkpoint(dir / "b.h5"), c = read_checkpoint(dir / "c.h5");
  EXPECT_EQ(state_hash(a.state), state_hash(b.state));
  EXPECT_EQ(read_file(dir / "a.h5"), read_file(dir / "b.h5"));  // byte-identical files
  EXPECT_NE(state_hash(a.state), state_hash(c.state));
  EXPECT_EQ(a.body.count_species(Species::shell), 642u);
  EXPECT_TRUE(fs::exists(dir / "a.xdmf"));
}

TEST(BuildCli, BadInputExitsTwoNamingTheProblemAndKeepsExistingFiles) {
  const ScratchFolder scratch("build_bad");
  const fs::path& dir = scratch.path;
  const auto out = dir / "body.h5";
  ASSERT_EQ(run_cli("build --config '" + quick() + "' --out '" + out.string() + "'").exit_code, 0);
  const std::string before = read_file(out);

  const auto unknown_key = dir / "unknown.toml";
  std::ofstream(unknown_key) << "[interior]\ncount = 100\nradious = 0.8\n";
  const auto malformed = dir / "malformed.toml";
  std::ofstream(malformed) << "[interior\ncount = 100\n";
  const auto out_of_range = dir / "range.toml";
  std::ofstream(out_of_range) << "[shell]\nfailure_strain = -0.1\n";

  struct Case {
    std::string args, expected;
  } cases[] = {
      {"build --config '" + unknown_key.string() + "' --out '" + out.string() + "'", "interior.radious"},
      {"build --config '" + malformed.string() + "' --out '" + out.string() + "'", "malformed.toml:1"},
      {"build --config '" + out_of_range.string() + "' --out '" + out.string() + "'", "shell.failure_strain"},
      {"build --config '" + (dir / "missing.toml").string() + "' --out '" + out.string() + "'", "missing.toml"},
      {"build --config '" + quick() + "' --set shell.level=9 --out '" + out.string() + "'", "shell.level"},
      {"build --config '" + quick() + "' --out '" + (dir / "no/such/folder/b.h5").string() + "'", "does not exist"},
      {"build --out '" + out.string() + "'", "--config"},
      {"build --config '" + quick() + "' '" + out.string() + "'", "unexpected argument"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
  }
  EXPECT_EQ(read_file(out), before);  // nothing already written was damaged
}

// An option a command accepts is applied: --dt-factor scales the time step the build checkpoint
// records (clock and stored configuration), which stretch, relax and encounters continue with.
TEST(BuildCli, DtFactorScalesTheRecordedTimeStep) {
  const ScratchFolder scratch("build_dt_factor");
  const fs::path& dir = scratch.path;
  ASSERT_EQ(run_cli("build --config '" + quick() + "' --out '" + (dir / "a.h5").string() + "'").exit_code, 0);
  const CliResult half =
      run_cli("build --config '" + quick() + "' --dt-factor 0.5 --out '" + (dir / "b.h5").string() + "'");
  ASSERT_EQ(half.exit_code, 0) << half.err;
  const auto a = read_checkpoint(dir / "a.h5"), b = read_checkpoint(dir / "b.h5");
  EXPECT_DOUBLE_EQ(b.stage.clock.dt, 0.5 * a.stage.clock.dt);
  EXPECT_DOUBLE_EQ(parse_config(b.config_toml, "b.h5").integrator.dt, 0.5 * a.stage.clock.dt);
  EXPECT_EQ(state_hash(a.state), state_hash(b.state));  // the built body itself does not depend on dt
}
