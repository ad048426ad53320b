// The single-stage commands chained by hand: wrong stage order is refused with exit 2, an
// interrupted relax (exit 130) resumes from its mid-stage checkpoint to the same bits.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/state_hash.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// A scratch folder for one chain of stage commands; at(name) is a file in it, quoted.
struct Chain {
  const ScratchFolder scratch{"stages"};
  const fs::path& dir = scratch.path;
  std::string at(const char* name) const { return quoted(dir / name); }
};

std::string quick() { return quoted(workflow_file("quick.toml")); }

}  // namespace

TEST(StageCli, WrongStageOrderExitsTwoAndInterruptedRelaxResumesBitIdentical) {
  Chain c;
  // Shorter relaxation keeps the test fast; the physics of relax is tested in test_relax_stage.
  ASSERT_EQ(run_cli("build --config " + quick() + " --set relax.duration=0.6 --set relax.settle_duration=0.2"
                    " --set relax.probe_duration=0.2 --out " + c.at("body.h5")).exit_code, 0);

  auto relax_of_build = run_cli("relax --from " + c.at("body.h5") + " --out " + c.at("r.h5"));
  EXPECT_EQ(relax_of_build.exit_code, 2);
  EXPECT_NE(relax_of_build.err.find("is a 'build' checkpoint; relax needs a stretch or relax checkpoint"),
            std::string::npos) << relax_of_build.err;
  EXPECT_EQ(count_lines(relax_of_build.err), 1);

  ASSERT_EQ(run_cli("stretch --from " + c.at("body.h5") + " --out " + c.at("stretched.h5")).exit_code, 0);
  auto stretch_again = run_cli("stretch --from " + c.at("stretched.h5") + " --out " + c.at("s2.h5"));
  EXPECT_EQ(stretch_again.exit_code, 2);
  EXPECT_NE(stretch_again.err.find("stretch needs a build checkpoint"), std::string::npos) << stretch_again.err;
  auto encounter_of_stretch =
      run_cli("encounter --from " + c.at("stretched.h5") + " --out " + c.at("e.h5") + " --m2 1 --q 1.6 --vq 1.6");
  EXPECT_EQ(encounter_of_stretch.exit_code, 2) << encounter_of_stretch.err;

  // Straight through.
  ASSERT_EQ(run_cli("relax --quiet --from " + c.at("stretched.h5") + " --out " + c.at("straight.h5")).exit_code, 0);
  // Stopped after step 37 (exit 130, mid-stage checkpoint), then resumed from it.
  auto stopped = run_cli("relax --quiet --stop-after-step 37 --from " + c.at("stretched.h5") + " --out " +
                         c.at("resumed.h5"));
  EXPECT_EQ(stopped.exit_code, 130) << stopped.err;
  ASSERT_TRUE(fs::exists(c.dir / "resumed.mid.h5"));
  EXPECT_FALSE(fs::exists(c.dir / "resumed.h5"));
  EXPECT_EQ(read_checkpoint(c.dir / "resumed.mid.h5").state.step, 37);
  // The same command again continues from the mid-stage checkpoint (here to step 60), never from
  // the beginning: a killed run's progress survives repeating the command that started it.
  auto repeated = run_cli("relax --quiet --stop-after-step 60 --from " + c.at("stretched.h5") + " --out " +
                          c.at("resumed.h5"));
  EXPECT_EQ(repeated.exit_code, 130) << repeated.err;
  EXPECT_NE(repeated.err.find("resuming from " + (c.dir / "resumed.mid.h5").string() + " (step 37)"), std::string::npos)
      << repeated.err;
  EXPECT_EQ(read_checkpoint(c.dir / "resumed.mid.h5").state.step, 60);
  auto changed = run_cli("relax --quiet --from " + c.at("resumed.mid.h5") + " --set relax.damping=10 --out " +
                         c.at("resumed.h5"));
  EXPECT_EQ(changed.exit_code, 2) << changed.err;  // a resume keeps its own configuration
  ASSERT_EQ(run_cli("relax --quiet --from " + c.at("resumed.mid.h5") + " --out " + c.at("resumed.h5")).exit_code, 0);
  EXPECT_EQ(state_hash(read_checkpoint(c.dir / "resumed.h5").state),
            state_hash(read_checkpoint(c.dir / "straight.h5").state));
  EXPECT_FALSE(fs::exists(c.dir / "resumed.mid.h5"));  // the finished stage cleans its mid file up
  auto already = run_cli("relax --from " + c.at("straight.h5") + " --out " + c.at("again.h5"));
  EXPECT_EQ(already.exit_code, 2);
}

TEST(StageCli, BlowUpExitsOneNamingStepAndCauseAndWritesDiagnosticCheckpoint) {
  Chain c;
  ASSERT_EQ(run_cli("build --config " + quick() + " --set relax.duration=0.4 --set relax.settle_duration=0.1"
                    " --set relax.stability_probe=false --out " + c.at("body.h5")).exit_code, 0);
  ASSERT_EQ(run_cli("stretch --from " + c.at("body.h5") + " --out " + c.at("stretched.h5")).exit_code, 0);
  ASSERT_EQ(run_cli("relax --quiet --from " + c.at("stretched.h5") + " --out " + c.at("relaxed.h5")).exit_code, 0);
  // dt far beyond the stability bound of the stiffest spring (eq. 13).
  auto r = run_cli("encounter --quiet --from " + c.at("relaxed.h5") + " --out " + c.at("enc.h5") +
                   " --m2 1 --q 1.6 --vq 1.6 --set integrator.dt=0.05");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("blow-up at step"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("stability bound"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("enc.diagnostic.h5"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(c.dir / "enc.h5"));
  const Checkpoint diagnostic = read_checkpoint(c.dir / "enc.diagnostic.h5");  // valid, inspectable
  EXPECT_FALSE(diagnostic.stage.complete);
  EXPECT_NE(diagnostic.stage.diagnostic.find("stability bound"), std::string::npos) << diagnostic.stage.diagnostic;

  // Encounters the time step cannot resolve (issue 10, item 6): exit 2, one line naming dt and
  // the encounter, nothing written. Quick's dt = 0.004; the pericenter passage q/V_q spans 0.01,
  // 0.4 and ~1e-150 steps.
  for (const char* orbit : {"--m2 1e9 --q 1.84 --vq 33100", "--m2 1e6 --q 1.84 --vq 1042.6",
                            "--m2 1e300 --q 1.84 --vq 1.0425e150"}) {
    r = run_cli("encounter --quiet --from " + c.at("relaxed.h5") + " --out " + c.at("unresolved.h5") + " " + orbit);
    EXPECT_EQ(r.exit_code, 2) << orbit << "\n" << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("dt = 0.004"), std::string::npos) << r.err;
    // Named by the checkpoint whose time step it is.
    EXPECT_NE(r.err.find((c.dir / "relaxed.h5").string() + ": encounter '"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(c.dir / "unresolved.h5"));
  }
}
