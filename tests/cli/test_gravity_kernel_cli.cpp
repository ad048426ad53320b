// Stepping on from a checkpoint computed by another gravity kernel: refused with exit 2 naming
// both kernels (a mid-stage resume, and a new stage from a finished parent), for the stage
// commands and for `run`; allowed with --allow-kernel-change, which the checkpoint records.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "forces/gravity.hpp"
#include "io/checkpoint_file.hpp"
#include "support/quick_workflow.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// This build's fast kernel ("fast/avx512" with AVX-512).
const std::string fast = gravity_kernel_label(GravityKernel::fast);
/// Whether this build's fast kernel gives other bits than the portable one (only with AVX-512;
/// without it the two are one code and a change between them is never refused).
const bool kernels_differ = !same_gravity_bits(fast, "portable");

bool names_both_kernels(const std::string& err) {
  return err.find("computed by the " + fast + " gravity kernel, but this run uses portable") != std::string::npos;
}

/// A small body with short stages and frequent mid-stage checkpoints.
fs::path small_workflow(const fs::path& dir) {
  const auto file = dir / "small.toml";
  std::ofstream(file) << small_body_toml("small") << R"(checkpoint_interval = 15
[encounter]
failure_rule = "paper"
start_distance = 2.2
end_distance = 2.2
checkpoint_interval = 15
[[encounters]]
name = "A"
perturber_mass = 1.0
pericenter = 1.5
pericenter_speed = 1.6
)";
  return file;
}

}  // namespace

TEST(KernelCli, StageCommandsRefuseAnotherKernelUnlessAllowed) {
  const ScratchFolder scratch("kernel_stages");
  const fs::path& dir = scratch.path;
  const std::string workflow = quoted(small_workflow(dir));
  auto at = [&](const char* name) { return quoted(dir / name); };
  ASSERT_EQ(run_cli("build --config " + workflow + " --out " + at("body.h5")).exit_code, 0);
  ASSERT_EQ(run_cli("stretch --from " + at("body.h5") + " --out " + at("s.h5")).exit_code, 0);
  EXPECT_EQ(read_checkpoint(dir / "s.h5").stage.gravity_kernel, fast);
  EXPECT_EQ(read_checkpoint(dir / "body.h5").stage.gravity_kernel, "");  // build computes no forces
  ASSERT_EQ(run_cli("relax --quiet --stop-after-step 20 --from " + at("s.h5") + " --out " + at("r.h5")).exit_code,
            130);
  const std::string mid_bytes = read_file(dir / "r.mid.h5");

  // Resuming the mid-stage checkpoint under the portable kernel.
  const CliResult refused =
      run_cli("relax --quiet --gravity-kernel portable --from " + at("r.mid.h5") + " --out " + at("r.h5"));
  if (kernels_differ) {
    EXPECT_EQ(refused.exit_code, 2) << refused.err;
    EXPECT_EQ(count_lines(refused.err), 1) << refused.err;
    EXPECT_NE(refused.err.find((dir / "r.mid.h5").string()), std::string::npos) << refused.err;
    EXPECT_TRUE(names_both_kernels(refused.err)) << refused.err;
    EXPECT_FALSE(fs::exists(dir / "r.h5"));
    EXPECT_EQ(read_file(dir / "r.mid.h5"), mid_bytes);  // nothing written is touched
  } else {
    EXPECT_EQ(refused.exit_code, 0) << refused.err;
  }
  if (kernels_differ) {
    const CliResult allowed = run_cli("relax --quiet --gravity-kernel portable --allow-kernel-change --from " +
                                      at("r.mid.h5") + " --out " + at("r.h5"));
    ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
  }
  const Checkpoint relaxed = read_checkpoint(dir / "r.h5");
  EXPECT_EQ(relaxed.stage.gravity_kernel, "portable");
  if (kernels_differ) {
    EXPECT_EQ(relaxed.stage.gravity_kernel_changes, "step 20: " + fast + " -> portable (--allow-kernel-change)");
    const CliResult shown = run_cli("inspect " + at("r.h5"));
    EXPECT_NE(shown.out.find("gravity_kernel_changes"), std::string::npos) << shown.out;
  }
  // The stored configuration follows the kernel, so the next stage continues with it; a new
  // stage from the finished one under the other kernel is refused too.
  EXPECT_NE(relaxed.config_toml.find("kernel = 'portable'"), std::string::npos);
  const CliResult other = run_cli("encounter --quiet --gravity-kernel fast --from " + at("r.h5") +
                                  " --m2 1 --q 1.5 --vq 1.6 --out " + at("e2.h5"));
  if (kernels_differ) {
    EXPECT_EQ(other.exit_code, 2) << other.err;
    EXPECT_NE(other.err.find("computed by the portable gravity kernel, but this run uses " + fast),
              std::string::npos) << other.err;
    EXPECT_FALSE(fs::exists(dir / "e2.h5"));
    EXPECT_FALSE(fs::exists(dir / "e2.mid.h5"));
  }
  EXPECT_EQ(run_cli("relax --gravity-kernel exact --from " + at("s.h5") + " --out " + at("x.h5")).exit_code, 2);
}

TEST(KernelCli, RunRefusesToResumeUnderAnotherKernelUnlessAllowed) {
  const ScratchFolder scratch("kernel_run");
  const fs::path& dir = scratch.path;
  const auto workflow = small_workflow(dir);
  const auto out = dir / "out";
  const std::string common = "run " + quoted(workflow) + " --quiet --out " + quoted(out) + " --set relax.duration=1.0";
  // Stopped (SIGINT) inside the relaxation, as a preempted cluster job is: held after its 20th
  // step (io/test_points.hpp) so that the signal lands there on any machine.
  const fs::path hold = dir / "held";
  BackgroundCli first(common, hold_at_step(20, hold));
  ASSERT_TRUE(wait_while_running(first.pid(), [&] { return fs::exists(hold); }));
  const auto mid = out / "body" / "relax.mid.h5";
  kill(first.pid(), SIGINT);
  ASSERT_EQ(first.finish().exit_code, 130);
  const std::string mid_bytes = read_file(mid);
  EXPECT_EQ(read_checkpoint(mid).stage.gravity_kernel, fast);

  const CliResult refused = run_cli(common + " --gravity-kernel portable");
  if (!kernels_differ) {
    EXPECT_EQ(refused.exit_code, 0) << refused.err;
    return;
  }
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_EQ(count_lines(refused.err), 1) << refused.err;
  EXPECT_NE(refused.err.find(mid.string()), std::string::npos) << refused.err;
  EXPECT_TRUE(names_both_kernels(refused.err)) << refused.err;
  EXPECT_EQ(read_file(mid), mid_bytes);
  EXPECT_FALSE(fs::exists(out / "body" / "relax.h5"));

  const CliResult allowed = run_cli(common + " --set gravity.kernel=portable --allow-kernel-change");
  ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
  const Checkpoint relaxed = read_checkpoint(out / "body" / "relax.h5");
  EXPECT_EQ(relaxed.stage.gravity_kernel, "portable");
  EXPECT_NE(relaxed.stage.gravity_kernel_changes.find(" -> portable (--allow-kernel-change)"), std::string::npos);
  EXPECT_EQ(read_checkpoint(out / "A" / "encounter.h5").stage.gravity_kernel, "portable");
  // The finished chain is portable now: the fast kernel may not continue from it.
  const CliResult back = run_cli(common + " --set encounter.damping=0.02");
  EXPECT_EQ(back.exit_code, 2) << back.err;
  EXPECT_NE(back.err.find("computed by the portable gravity kernel, but this run uses " + fast), std::string::npos)
      << back.err;
}
