#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "stages/build_stage.hpp"
#include "physics/crust_relaxation.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "forces/hinge_geometry.hpp"
#include "integrate/leapfrog.hpp"
#include "stages/relax_stage.hpp"
#include "physics/shell_failure.hpp"
#include "stages/stability_probe.hpp"
#include "io/state_hash.hpp"
#include "io/stop_signal.hpp"
#include "stages/stretch_stage.hpp"
#include "io/checkpoint_file.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"
#include "support/shared_checkpoint.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

/// quick.toml with a short relaxation: 60 steps (creep phase 40, settle 20), rest lengths
/// every 10 steps, hinges every 25, probe 20 steps.
Config short_config() {
  Config c = quick_config();
  c.relax.duration = 60 * c.integrator.dt;
  c.relax.settle_duration = 20 * c.integrator.dt;
  c.relax.hinge_reset_interval = 25;
  c.relax.probe_duration = 20 * c.integrator.dt;
  return c;
}

Checkpoint run_straight(const Config& config) {
  Checkpoint c = begin_relax(quick_stretched(), config);
  EXPECT_EQ(run_relax(c, config, quiet_loop()), LoopOutcome::finished);
  return c;
}

std::string relax_error(const Checkpoint& c, const Config& config) {
  try {
    Checkpoint copy = c;
    if (std::holds_alternative<RelaxRecord>(c.stage.record))
      run_relax(copy, config, quiet_loop());
    else
      begin_relax(c, config);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(RelaxStage, BeginSetsDampingStepsAndBookkeeping) {
  const Config config = quick_config();
  const Checkpoint& s = quick_stretched();
  const Checkpoint c = begin_relax(s, config);
  EXPECT_STREQ(c.stage.name(), "relax");
  EXPECT_FALSE(c.stage.complete);
  EXPECT_EQ(c.stage.clock.start_step, s.state.step);
  EXPECT_EQ(c.stage.end_step, s.state.step + 750);  // T = 3 at dt = 0.004
  EXPECT_EQ(c.stage.parent_hash, state_hash(s.state));
  EXPECT_EQ(c.config_toml, to_toml(config));
  EXPECT_EQ(c.state.time, s.state.time);
  EXPECT_EQ(c.stage.clock.dt, config.integrator.dt);
  EXPECT_EQ(c.stage.clock.start_time, s.state.time);
  EXPECT_EQ(c.stage.as<RelaxRecord>().damping, config.relax.damping);
  EXPECT_EQ(c.state.springs.rest_length, s.state.springs.rest_length);
  ASSERT_EQ(c.observables.timeseries.size(), 1u);
}

TEST(RelaxStage, RelaxedQuickBodyIsAtRestWithAnUnstressedCrust) {
  const Config config = quick_config();
  const Checkpoint& r = quick_relaxed();
  const RelaxRecord& sc = r.stage.as<RelaxRecord>();
  EXPECT_TRUE(r.stage.complete);
  EXPECT_EQ(r.state.step, r.stage.end_step);
  EXPECT_LT(sc.internal_kinetic_energy, 1e-6);
  EXPECT_LT(std::abs(sc.mean_shell_radius - 1.0), 0.01);
  EXPECT_DOUBLE_EQ(sc.max_shell_strain, max_abs_shell_strain(r.body, r.state));
  // What is left in the crust is the load it must carry at rest (the oblique cross springs'
  // pull): below the weakest crust of the workflows (T1: eps_S = 0.002).
  EXPECT_LT(sc.max_shell_tension, 0.002);
  EXPECT_LT(sc.max_shell_strain, config.shell.failure_strain);
  // Interior and cross springs keep their stretched rest lengths; nothing failed.
  const Checkpoint& s = quick_stretched();
  for (std::size_t n = 0; n < r.body.spring_count(); ++n) {
    if (r.body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::shell)) {
      ASSERT_EQ(r.state.springs.rest_length[n], s.state.springs.rest_length[n]) << n;
    }
    ASSERT_EQ(r.state.springs.stiffness[n], s.state.springs.stiffness[n]) << n;
    ASSERT_EQ(r.state.springs.failed[n], 0) << n;
  }
}

TEST(RelaxStage, StabilityProbeFindsNoFailuresAtEitherCrustStrength) {
  const Config config = quick_config();
  const RelaxRecord& sc = quick_relaxed().stage.as<RelaxRecord>();
  EXPECT_EQ(sc.probe_failure_strain, config.shell.failure_strain);
  EXPECT_EQ(sc.probe_failures, 0);
  ASSERT_EQ(sc.probe_other_strains, std::vector<double>{0.002});
  EXPECT_EQ(sc.probe_other_failures, std::vector<std::int64_t>{0});
  EXPECT_LT(sc.probe_max_shell_strain, 0.002);
  EXPECT_GE(sc.probe_max_shell_strain, sc.max_shell_tension);
}

TEST(RelaxStage, ConservesMomentumAndAngularMomentum) {
  const Config config = quick_config();
  const Checkpoint& r = quick_relaxed();
  const auto& ts = r.observables.timeseries;
  // One sample at the start, then every sample_interval steps.
  ASSERT_EQ(ts.size(), static_cast<std::size_t>(750 / config.encounter.sample_interval + 1));
  EXPECT_EQ(ts.back().time, r.state.time);
  for (const auto& sample : ts)
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(sample.momentum[k], ts.front().momentum[k], 1e-12);
      EXPECT_NEAR(sample.angular_momentum[k], ts.front().angular_momentum[k], 1e-12);
    }
  double peak = 0;
  for (const auto& sample : ts) peak = std::max(peak, sample.kinetic_energy);
  EXPECT_GT(peak, 1e-7);  // the body did move, and settled
  EXPECT_LT(ts.back().kinetic_energy, 1e-6);
}

TEST(RelaxStage, CrustIsExactlyStressFreeWhenTheCreepPhaseEnds) {
  const Config config = short_config();
  Checkpoint c = begin_relax(quick_stretched(), config);
  const std::int64_t creep_end = c.stage.as<RelaxRecord>().creep_end_step;
  EXPECT_EQ(creep_end, c.stage.clock.start_step + 40);
  StepLoopOptions o = quiet_loop();
  o.stop_after_step = creep_end;
  ASSERT_EQ(run_relax(c, config, o), LoopOutcome::interrupted);
  EXPECT_EQ(max_abs_shell_strain(c.body, c.state), 0.0);
  // Every hinge at its rest angle, bit for bit, measured with the atan2 the stage uses (SLEEF's in
  // portable mode, which a build without AVX-512 always runs; docs/determinism.md).
  for (std::size_t h = 0; h < c.body.hinge_count(); ++h) {
    const auto& v = c.body.hinges[h];
    auto at = [&](int k) { return vec3_at(c.state.position, static_cast<std::size_t>(v[k])); };
    ASSERT_EQ(c.state.hinges.rest_angle[h], hinge_angle(at(0), at(1), at(2), at(3), portable_mode(config)));
  }
}

TEST(RelaxStage, ShellRestLengthsCreepOnTheirStepSchedule) {
  const Config config = short_config();
  Checkpoint c = begin_relax(quick_stretched(), config);
  StepLoopOptions o = quiet_loop();
  o.stop_after_step = c.stage.clock.start_step + 19;  // just before the second update
  run_relax(c, config, o);
  const std::vector<double> before = c.state.springs.rest_length;
  Checkpoint next = c;
  o.stop_after_step = c.stage.clock.start_step + 20;
  run_relax(next, config, o);
  // Step 20: shell rest lengths moved by rest_length_rate of the difference, others kept.
  State expected = next.state;
  expected.springs.rest_length = before;
  creep_shell_rest_lengths(next.body, expected, config.relax.rest_length_rate);
  EXPECT_EQ(next.state.springs.rest_length, expected.springs.rest_length);
  std::size_t moved = 0;
  for (std::size_t n = 0; n < c.body.spring_count(); ++n) moved += before[n] != next.state.springs.rest_length[n];
  EXPECT_EQ(moved, c.body.count_springs(SpringKind::shell));
}

TEST(RelaxStage, SameBitsWithOneAndTwoThreads) {
  const Config config = short_config();
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Checkpoint one = run_straight(config);
  omp_set_num_threads(2);
  const Checkpoint two = run_straight(config);
  omp_set_num_threads(threads);
  EXPECT_EQ(state_hash(one.state), state_hash(two.state));
  EXPECT_EQ(one.stage.record, two.stage.record);
}

TEST(RelaxStage, ResumedRunEqualsStraightRunBitForBit) {
  const Config config = short_config();
  const Checkpoint straight = run_straight(config);
  const ScratchFolder scratch("relax_resume");
  const auto& dir = scratch.path;
  // k = 25: inside a rest-length interval (updates at 20 and 30) and a hinge interval.
  for (std::int64_t k : {25, 45, 65}) {  // creep phase, settle phase, stability probe
    Checkpoint c = begin_relax(quick_stretched(), config);
    StepLoopOptions o = quiet_loop();
    o.mid_checkpoint = dir / "mid.h5";
    o.stop_after_step = c.stage.clock.start_step + k;
    ASSERT_EQ(run_relax(c, config, o), LoopOutcome::interrupted) << k;
    Checkpoint resumed = read_checkpoint(o.mid_checkpoint);
    EXPECT_FALSE(resumed.stage.complete);
    o.stop_after_step = -1;
    ASSERT_EQ(run_relax(resumed, config, o), LoopOutcome::finished) << k;
    EXPECT_EQ(state_hash(resumed.state), state_hash(straight.state)) << k;
    EXPECT_EQ(resumed.stage.record, straight.stage.record) << k;
    EXPECT_EQ(resumed.observables.timeseries.size(), straight.observables.timeseries.size()) << k;
    EXPECT_TRUE(resumed.stage.complete);
  }
}

TEST(RelaxStage, ProbeCountsFailuresOfAPrestressedCrustWithoutChangingTheBody) {
  const Config config = short_config();
  Checkpoint c = quick_relaxed();
  // Shorten every fourth shell spring's rest length by 1 %: a crust in tension.
  for (std::size_t n = 0; n < c.body.spring_count(); n += 4)
    if (c.body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell)) c.state.springs.rest_length[n] *= 0.99;
  const std::string hash = state_hash(c.state);
  const ProbeResult p = run_stability_probe(c, config, 0.003, quiet_loop());
  EXPECT_FALSE(p.interrupted);
  EXPECT_EQ(p.failures, 20 / config.encounter.fail_interval);  // one per check: every check fails one
  EXPECT_GT(p.max_shell_tension, 0.009);
  EXPECT_EQ(state_hash(c.state), hash);
}

TEST(RelaxStage, RefusesWrongStagesAndChangedConfiguration) {
  const Config config = quick_config();
  std::string msg = relax_error(quick_built(), config);
  EXPECT_NE(msg.find("'stretch'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'build'"), std::string::npos) << msg;
  Checkpoint incomplete = quick_stretched();
  incomplete.stage.complete = false;
  msg = relax_error(incomplete, config);
  EXPECT_NE(msg.find("incomplete"), std::string::npos) << msg;
  // run_relax on anything but a relax checkpoint.
  Checkpoint stretched = quick_stretched();
  msg = "";
  try {
    run_relax(stretched, config, quiet_loop());
  } catch (const InputError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("'relax'"), std::string::npos) << msg;
  // Resuming with another configuration.
  Checkpoint c = begin_relax(quick_stretched(), config);
  Config other = config;
  other.relax.damping = 10;
  msg = relax_error(c, other);
  EXPECT_NE(msg.find("configuration differs"), std::string::npos) << msg;
  // The stretch stage refuses a relaxed body.
  msg = "";
  try {
    stretch_stage(quick_relaxed(), config);
  } catch (const InputError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("'build'"), std::string::npos) << msg;
}

// Issue "a crust you can trust": with the balanced support the relaxed crust carries no load.
// Measured on the quick body: largest |shell strain| 4.3e-6 (paper support: 1.7e-3), internal
// kinetic energy 3e-14, mean shell radius 0.9995, probe strain 2.7e-6.
TEST(RelaxStage, BalancedSupportLeavesTheCrustWithoutPreStress) {
  Config config = quick_config();
  config.cross.min_per_shell_node = 3;
  config.relax.crust_support = CrustSupport::balanced;
  config.shell.failure_strain = 5e-4;  // the probe fails nothing even at a realistic eps_S
  config.encounter.failure_rule = FailureRuleKind::local;
  const Checkpoint built = build_stage(config);
  Checkpoint c = begin_relax(stretch_stage(built, config), config);
  ASSERT_EQ(run_relax(c, config, quiet_loop()), LoopOutcome::finished);
  const auto& r = c.stage.as<RelaxRecord>();
  EXPECT_LE(r.max_shell_strain, 1e-4);
  EXPECT_LT(r.internal_kinetic_energy, 1e-6);
  EXPECT_NEAR(r.mean_shell_radius, 1.0, 0.01);
  EXPECT_EQ(r.probe_failure_strain, 5e-4);
  EXPECT_EQ(r.probe_failures, 0);
  EXPECT_LE(r.probe_max_shell_strain, 1e-4);
  // The paper's support on the same body keeps a pre-stress of order eps_S.
  EXPECT_GT(quick_relaxed(false).stage.as<RelaxRecord>().max_shell_strain, 1e-3);
}

TEST(RelaxStage, UnknownCrustSupportOrFailureRuleIsAClearError) {
  for (const char* line : {"relax.crust_support=\"glued\"", "encounter.failure_rule=\"fast\""}) {
    Config config = quick_config();
    try {
      apply_override(config, line);
      validate(config, "--set");
      ADD_FAILURE() << line << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("is not one of"), std::string::npos) << e.what();
    }
  }
}

namespace {

/// workflows/quick-welded.toml (level 3, the crust welded to its interior) relaxed with `support`;
/// eps_S = 5e-4 so that the stability probe checks a realistic ice failure strain.
Checkpoint relaxed_welded(CrustSupport support) {
  Config config = load_config(workflow_file("quick-welded.toml"));
  config.relax.crust_support = support;
  config.shell.failure_strain = 5e-4;
  Checkpoint c = begin_relax(stretch_stage(build_stage(config), config), config);
  EXPECT_EQ(run_relax(c, config, quiet_loop()), LoopOutcome::finished);
  return c;
}

const Checkpoint& relaxed_welded_once(CrustSupport support) {
  static const Checkpoint balanced =
      shared_checkpoint("quick-welded-balanced", [] { return relaxed_welded(CrustSupport::balanced); });
  static const Checkpoint lithostatic =
      shared_checkpoint("quick-welded-lithostatic", [] { return relaxed_welded(CrustSupport::lithostatic); });
  return support == CrustSupport::balanced ? balanced : lithostatic;
}

std::vector<double> self_gravity(const Checkpoint& c) {
  const Config config = load_config(workflow_file("quick-welded.toml"));
  ForceField forces(c.body, force_options(config, 0.0));
  std::vector<double> g(c.state.position.size());
  forces.compute_gravity(c.state.position.data(), g.data());
  return g;
}

double mean_shell_strain(const Checkpoint& c) {
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t n = 0; n < c.body.spring_count(); ++n)
    if (c.body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell)) {
      sum += spring_strain(c.body, c.state, n);
      ++count;
    }
  return sum / static_cast<double>(count);
}

}  // namespace

// Issue 23 item 4: the lithostatic crust keeps the compression its own weight gives on the welded
// interior, eps_L = -w / (1/c + 2C/R_S) (docs/crust-support.md, "The lithostatic crust"). Measured on
// quick-welded: eps_L = -6.68e-4, shell strains -7.00e-4 .. -6.60e-4, their mean 1.2% beyond eps_L.
TEST(RelaxStage, LithostaticSupportKeepsTheCompressionOfTheCrustsWeight) {
  const Checkpoint& c = relaxed_welded_once(CrustSupport::lithostatic);
  const Config config = load_config(workflow_file("quick-welded.toml"));
  const double eps_l = lithostatic_crust_strain(c.body, c.state, self_gravity(c), config.interior.radius,
                                                config.interior.spring_distance);
  EXPECT_LT(eps_l, -3e-4);
  EXPECT_GT(eps_l, -1.5e-3);
  for (std::size_t n = 0; n < c.body.spring_count(); ++n)
    if (c.body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell)) {
      const double strain = spring_strain(c.body, c.state, n);
      ASSERT_LT(strain, 0.9 * eps_l) << "shell spring " << n;
      ASSERT_GT(strain, 1.1 * eps_l) << "shell spring " << n;
    }
  EXPECT_NEAR(mean_shell_strain(c), eps_l, 0.03 * std::abs(eps_l));
  const auto& r = c.stage.as<RelaxRecord>();
  EXPECT_EQ(r.max_shell_tension, 0.0);  // every crust spring compressed
  EXPECT_LT(r.internal_kinetic_energy, 1e-6);
  EXPECT_EQ(r.probe_failure_strain, 5e-4);
  EXPECT_EQ(r.probe_failures, 0);
  EXPECT_EQ(r.probe_max_shell_strain, 0.0);  // the tension a failure needs never appears when left alone
}

// The derivation of eps_L checked in the model: a degree-0 surface load w' (every shell node's own
// weight once more, as an extra acceleration) on the relaxed balanced welded body compresses the
// crust by about eps_L w'/w. The formula leaves out the network's non-affine softness (its measured
// modulus is 0.84x eq. 15 on this body) and the interior's gravity growing as it compresses, both
// of which make the model's compression larger. Measured: -7.64e-4 against -6.68e-4, ratio 1.14
// (settled: the same 4 digits after 4500 steps).
TEST(RelaxStage, ASurfaceLoadCompressesTheWeldedCrustAsTheLithostaticFormulaSays) {
  Checkpoint c = relaxed_welded_once(CrustSupport::balanced);
  const Config config = load_config(workflow_file("quick-welded.toml"));
  const std::vector<double> g0 = self_gravity(c);
  const double eps_l = lithostatic_crust_strain(c.body, c.state, g0, config.interior.radius,
                                                config.interior.spring_distance);
  const double before = mean_shell_strain(c);
  ForceField forces(c.body, force_options(config, config.relax.damping));
  Leapfrog leapfrog(forces, StepClock{0, 0, config.integrator.dt});
  leapfrog.set_extra_acceleration([&](const double*, const double*, std::vector<double>& a) {
    for (std::size_t i = 0; i < c.body.particle_count(); ++i)
      if (c.body.species[i] == static_cast<std::uint8_t>(Species::shell))
        for (std::size_t k = 0; k < 3; ++k) a[3 * i + k] += g0[3 * i + k];
  });
  for (int step = 0; step < 1500; ++step) leapfrog.step(c.state);
  const double ratio = (mean_shell_strain(c) - before) / eps_l;
  EXPECT_GT(ratio, 1.0);
  EXPECT_LT(ratio, 1.3);
}

// A crust that varies (docs/crust.md) on the welded quick body: a thickness dichotomy toward +y
// (t from 0.5 to 1.5: node masses, spring and hinge stiffnesses), a strength dichotomy (f from 0.6
// to 1.4) and a weak great circle (f = 0.5) relax as the uniform crust does: the balanced support
// carries each node's own weight, and the probe, at eps_S = 5e-4 (1.5e-4 where the great circle
// crosses the weak side), fails nothing.
TEST(RelaxStage, AVaryingWeldedCrustRelaxesAndItsProbeFailsNothing) {
  Config config = load_config(workflow_file("quick-welded.toml"));
  config.shell.failure_strain = 5e-4;
  config.crust.thickness_harmonics = "s11 = 0.5";
  config.crust.strength_harmonics = "s11 = -0.4";
  config.crust.weak_lines = "pole_lon = 0, pole_lat = 0, half_width = 5, factor = 0.5";
  validate(config, "varying");
  Checkpoint c = begin_relax(stretch_stage(build_stage(config), config), config);
  ASSERT_EQ(run_relax(c, config, quiet_loop()), LoopOutcome::finished);
  const auto& r = c.stage.as<RelaxRecord>();
  EXPECT_EQ(r.probe_failure_strain, 5e-4);
  EXPECT_EQ(r.probe_failures, 0);
  EXPECT_LT(r.probe_max_shell_strain, 1e-4) << "the largest crust strain the probe saw";
  EXPECT_LT(r.internal_kinetic_energy, 1e-6);
  EXPECT_LT(*std::min_element(c.body.strength_factor.begin(), c.body.strength_factor.end()), 0.31);
}

TEST(RelaxStage, ALithostaticCrustOnThePapersCouplingIsAClearError) {
  Config config = quick_config();  // cross.coupling = "paper"
  apply_override(config, "relax.crust_support=lithostatic");
  try {
    validate(config, "quick.toml");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "quick.toml: relax.crust_support = \"lithostatic\" needs a crust welded to the interior "
              "(cross.coupling = \"welded\"): its compression is derived for a welded crust");
  }
}
