// A changed value reruns exactly the stages it affects: each stage's fingerprint holds what it
// reads and nothing else.
#include <gtest/gtest.h>

#include "model/config.hpp"
#include "model/stage_fingerprint.hpp"
#include "support/files.hpp"

using namespace tidalcrust;

namespace {

struct Fingerprints {
  std::string build, stretch, relax, encounter;
};

Fingerprints of(const Config& c) {
  return {build_fingerprint(c), stretch_fingerprint(c), relax_fingerprint(c),
          encounter_fingerprint(c, c.find_encounter("T5"))};
}

/// Which fingerprints change when `assignment` is applied to paper-T: "b s r e" letters.
std::string changed_by(const std::string& assignment) {
  Config base = load_config(test_support::workflow_file("paper-T.toml"));
  Config changed = base;
  apply_override(changed, assignment);
  const Fingerprints a = of(base), b = of(changed);
  std::string out;
  out += a.build != b.build ? "b" : "";
  out += a.stretch != b.stretch ? "s" : "";
  out += a.relax != b.relax ? "r" : "";
  out += a.encounter != b.encounter ? "e" : "";
  return out;
}

}  // namespace

TEST(StageFingerprint, EachValueReachesExactlyTheStagesThatReadIt) {
  EXPECT_EQ(changed_by("interior.count=1500"), "b");
  EXPECT_EQ(changed_by("workflow.seed=2"), "b");
  EXPECT_EQ(changed_by("shell.spring_constant=0.05"), "b");
  EXPECT_EQ(changed_by("stretch.cross_compression=0.001"), "s");
  EXPECT_EQ(changed_by("cross.nonlinear=true"), "sre");
  EXPECT_EQ(changed_by("relax.damping=40.0"), "r");
  EXPECT_EQ(changed_by("shell.failure_strain=0.0025"), "re");  // the probe and the encounters
  EXPECT_EQ(changed_by("encounter.damping=0.02"), "e");
  EXPECT_EQ(changed_by("encounter.fail_interval=2"), "re");
  EXPECT_EQ(changed_by("encounters.T5.pericenter=1.9"), "e");
  EXPECT_EQ(changed_by("integrator.dt=0.001"), "re");
  EXPECT_EQ(changed_by("core.radius=0.4"), "bs");  // masses and stiffnesses; the layered pressure
  // Checkpoint intervals and the workflow name change no result.
  EXPECT_EQ(changed_by("relax.checkpoint_interval=100"), "");
  EXPECT_EQ(changed_by("encounter.checkpoint_interval=100"), "");
  EXPECT_EQ(changed_by("workflow.name=\"other\""), "");
}

TEST(StageFingerprint, FirstDifferenceNamesTheKey) {
  Config a = load_config(test_support::workflow_file("paper-T.toml"));
  Config b = a;
  apply_override(b, "interior.count=1500");
  EXPECT_EQ(first_difference(build_fingerprint(a), build_fingerprint(b)),
            "'interior.count = 1869' -> 'interior.count = 1500'");
}

TEST(StageFingerprint, TheTreeGravityMethodAndItsErrorAreOtherStages) {
  // Every stage that computes forces (stretch, relax, encounter) reads the gravity method.
  EXPECT_EQ(changed_by("gravity.method=\"tree\""), "sre");
  // The direct sum does not read force_error: a direct run's fingerprints stay as they were.
  EXPECT_EQ(changed_by("gravity.force_error=0.001"), "");
  Config tree = load_config(test_support::workflow_file("paper-T.toml"));
  apply_override(tree, "gravity.method=\"tree\"");
  Config looser = tree;
  apply_override(looser, "gravity.force_error=0.001");
  EXPECT_NE(encounter_fingerprint(tree, tree.find_encounter("T5")),
            encounter_fingerprint(looser, looser.find_encounter("T5")));
  EXPECT_NE(relax_fingerprint(tree).find("gravity.method = 'tree'"), std::string::npos) << relax_fingerprint(tree);
  EXPECT_NE(stretch_fingerprint(looser).find("gravity.force_error = 0.001"), std::string::npos);
}
