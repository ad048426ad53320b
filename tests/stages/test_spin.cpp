// A spinning body (issue 26, docs/spin.md): the [spin] key and moon.spin_period, the co-rotating
// frame's accelerations, the relaxed body's flattening against h2 q / 2, its equilibrium when
// left alone, resume and thread independence with spin, angular momentum with spin, and the
// failures mapped in the body frame.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <numbers>
#include <regex>
#include <string>

#include "analysis/conservation_drift.hpp"
#include "analysis/elastic_validation.hpp"
#include "analysis/fracture_analysis.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "io/checkpoint_file.hpp"
#include "io/state_hash.hpp"
#include "model/stage_fingerprint.hpp"
#include "physics/continuum_elasticity.hpp"
#include "physics/orbital_frame.hpp"
#include "physics/shell_failure.hpp"
#include "physics/spin_frame.hpp"
#include "stages/build_stage.hpp"
#include "stages/encounter_stage.hpp"
#include "stages/relax_stage.hpp"
#include "stages/stretch_stage.hpp"
#include "stages/time_step.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"
#include "support/shared_checkpoint.hpp"
#include "support/synthetic_encounter.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;
using namespace test_support;

constexpr double deg = 180 / std::numbers::pi;

std::string with_spin(const std::string& toml, const std::string& spin) {
  return toml + "\n[spin]\nangular_velocity = " + spin + "\n";
}

// ---- the key ---------------------------------------------------------------------------------

TEST(SpinConfig, ZeroIsNoSpinAndKeepsTextAndFingerprints) {
  const std::string base = read_file(workflow_file("welded-L3.toml"));
  const Config plain = parse_config(base, "welded-L3.toml");
  const Config zero = parse_config(with_spin(base, "0"), "zero.toml");
  EXPECT_FALSE(zero.spin.angular_velocity.has_value());
  EXPECT_EQ(to_toml(zero), to_toml(plain));
  for (StageId stage : {StageId::build, StageId::stretch, StageId::relax, StageId::encounter})
    EXPECT_EQ(stage_fingerprint(zero, stage, &zero.encounters[0]), stage_fingerprint(plain, stage, &plain.encounters[0]));
  Config set = plain;
  apply_override(set, "spin.angular_velocity=0");
  EXPECT_EQ(to_toml(set), to_toml(plain));
}

TEST(SpinConfig, ASpinRerunsRelaxAndTheEncounterOnly) {
  const std::string base = read_file(workflow_file("welded-L3.toml"));
  const Config plain = parse_config(base, "welded-L3.toml");
  const Config spinning = parse_config(with_spin(base, "0.3"), "spin.toml");
  EXPECT_EQ(spinning.spin.rate(), 0.3);
  EXPECT_EQ(parse_config(to_toml(spinning), "resolved").spin.rate(), 0.3);
  for (StageId stage : {StageId::build, StageId::stretch})
    EXPECT_EQ(stage_fingerprint(spinning, stage), stage_fingerprint(plain, stage));
  for (StageId stage : {StageId::relax, StageId::encounter})
    EXPECT_NE(stage_fingerprint(spinning, stage, &spinning.encounters[0]),
              stage_fingerprint(plain, stage, &plain.encounters[0]));
}

TEST(SpinConfig, MoonSpinPeriodGivesTheAngularVelocity) {
  const std::string moon = read_file(source_file("tests/support/tiny-moon.toml"));
  const std::string text = std::regex_replace(moon, std::regex("\\[moon\\]\n"), "[moon]\nspin_period = \"40 h\"\n");
  const Config c = parse_config(text, "tiny-moon.toml");
  const double t_grav = moon_scale(c.moon, "tiny-moon.toml").units.time_s;
  EXPECT_NEAR(c.spin.rate(), 2 * std::numbers::pi * t_grav / (40 * 3600.0), 1e-12);
  // Given twice with one value: accepted (the resolved text carries both).
  EXPECT_EQ(parse_config(to_toml(c), "resolved").spin.rate(), c.spin.rate());
}

std::string config_error(const std::string& text) {
  try {
    parse_config(text, "bad.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SpinConfig, OutOfRangeSpinsAndBadPeriodsAreOneLineErrorsNamingFileAndKey) {
  const std::string base = read_file(workflow_file("welded-L3.toml"));
  for (const char* bad : {"0.9", "1.5", "-0.1", "nan"}) {
    const std::string message = config_error(with_spin(base, bad));
    EXPECT_NE(message.find("bad.toml"), std::string::npos) << bad << ": " << message;
    EXPECT_NE(message.find("spin.angular_velocity"), std::string::npos) << message;
    EXPECT_NE(message.find("[0, 0.9)"), std::string::npos) << message;
  }
  EXPECT_EQ(config_error(with_spin(base, "0.899")), "");
  const std::string moon = read_file(source_file("tests/support/tiny-moon.toml"));
  auto period = [&](const std::string& p) {
    return config_error(std::regex_replace(moon, std::regex("\\[moon\\]\n"), "[moon]\nspin_period = " + p + "\n"));
  };
  EXPECT_NE(period("\"45 km\"").find("moon.spin_period"), std::string::npos) << period("\"45 km\"");
  EXPECT_NE(period("\"45 parsecs per\"").find("moon.spin_period"), std::string::npos);
  EXPECT_NE(period("\"-3 h\"").find("moon.spin_period"), std::string::npos);
  EXPECT_NE(period("\"1 h\"").find("beyond 0.9 of breakup"), std::string::npos) << period("\"1 h\"");

  // On the command line: exit 2, one line naming the file and the key.
  const ScratchFolder scratch("spin_cli");
  const fs::path file = scratch.path / "fast.toml";
  write_file(file, with_spin(base, "0.95"));
  const CliResult r = run_cli("estimate --config " + quoted(file));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("fast.toml"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("spin.angular_velocity = 0.95"), std::string::npos) << r.err;
  const fs::path unit = scratch.path / "unit.toml";
  write_file(unit, std::regex_replace(read_file(source_file("tests/support/tiny-moon.toml")), std::regex("\\[moon\\]\n"),
                                      "[moon]\nspin_period = \"45 furlongs\"\n"));
  const CliResult u = run_cli("estimate --config " + quoted(unit));
  EXPECT_EQ(u.exit_code, 2);
  EXPECT_EQ(count_lines(u.err), 1) << u.err;
  EXPECT_NE(u.err.find("unit.toml"), std::string::npos) << u.err;
  EXPECT_NE(u.err.find("moon.spin_period"), std::string::npos) << u.err;
}

// ---- the frame -------------------------------------------------------------------------------

TEST(SpinFrame, AFluidBodyFlattensAsMaclaurinsSpheroid) {
  // f = h2 q / 2; a fluid's h2 = 5/2 gives 5 q / 4 (Maclaurin, small q).
  EXPECT_DOUBLE_EQ(centrifugal_flattening(2.5, 0.3), 1.25 * 0.09);
  EXPECT_EQ(centrifugal_flattening(0.06, 0), 0);
}

TEST(SpinFrame, ShellFlatteningFitsASpheroidExactly) {
  Checkpoint c = synthetic_encounter(3);
  const double a0 = 1.0, a2 = -2e-3;
  for (std::size_t i = 1; i < c.body.particle_count(); ++i) {
    const Vec3 u = vec3_at(c.state.position, i).normalized();
    set_vec3(c.state.position, i, Vec3(u * (a0 + a2 * (1.5 * u.z() * u.z() - 0.5))));
  }
  set_vec3(c.state.position, 0, Vec3::Zero());
  // The centre of mass moves a little off 0 with the shell: the fit about it is still close.
  const ShellFlattening f = shell_flattening(c.body, c.state);
  EXPECT_NEAR(f.p2_amplitude, a2, 1e-9);
  EXPECT_NEAR(f.flattening, (-1.5 * a2) / (a0 - 0.5 * a2), 1e-9);
  EXPECT_LT(f.rms_residual, 1e-9);
  // Seen tipped over (the body frame's z along x), the same body is prolate about z.
  Matrix3 tip;
  tip << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  EXPECT_LT(shell_flattening(c.body, c.state, tip).flattening, 0);
}

TEST(SpinFrame, RotatingToInertialTurnsTheBodyAndAddsTheRigidRotation) {
  Checkpoint c = synthetic_encounter(2);
  const State before = c.state;  // at rest, t = 2
  const double spin = 0.4;
  rotating_to_inertial(c.body, c.state, spin);
  const Matrix3 turn = spin_rotation(spin, before.time);
  const Vec3 center = body_center_of_mass(c.body, before);
  for (std::size_t i = 0; i < c.body.particle_count(); ++i) {
    const Vec3 r = turn * (vec3_at(before.position, i) - center);
    EXPECT_LT((vec3_at(c.state.position, i) - center - r).norm(), 1e-14);
    EXPECT_LT((vec3_at(c.state.velocity, i) - Vec3(0, 0, spin).cross(r)).norm(), 1e-14);
  }
  const Vec3 w = body_angular_velocity(c.body, c.state);
  EXPECT_NEAR(w.z(), spin, 1e-12);
  EXPECT_NEAR(w.head<2>().norm(), 0, 1e-12);
  State again = before;
  rotating_to_inertial(c.body, again, 0);
  EXPECT_EQ(state_hash(again), state_hash(before));  // no spin: not a bit changes
}

TEST(SpinFrame, AFailureAtAKnownBodyPointIsMappedThereAfterTheBodyTurned) {
  Checkpoint c = synthetic_encounter(2);
  const std::int32_t spring = spring_between(c.body, c.body.faces[7][0], c.body.faces[7][1]);
  ASSERT_GE(spring, 0);
  c.state.springs.failed[static_cast<std::size_t>(spring)] = 1;
  const FractureSummary unturned = analyze_fractures(c);  // no stored configuration: no spin
  ASSERT_EQ(unturned.count(), 1u);
  const FailedShellSpring at_rest = unturned.failed[0];

  // The same body spinning at 0.35 and seen at t = 2: turned by Rz(0.7) in the inertial frame.
  const double spin = 0.35;
  Config config = quick_config();
  config.spin.angular_velocity = spin;
  c.config_toml = to_toml(config);
  const Matrix3 turn = spin_rotation(spin, c.state.time);
  for (std::size_t i = 0; i < c.body.particle_count(); ++i)
    set_vec3(c.state.position, i, Vec3(turn * vec3_at(c.state.position, i)));
  const FractureSummary turned = analyze_fractures(c);
  ASSERT_EQ(turned.count(), 1u);
  EXPECT_NEAR(turned.failed[0].longitude_deg, at_rest.longitude_deg, 1e-9);
  EXPECT_NEAR(turned.failed[0].latitude_deg, at_rest.latitude_deg, 1e-9);
  // The subsatellite point: the pericenter direction (+y) turned back by the angle at t_q = 1.2.
  const double t_q = c.stage.as<EncounterRecord>().pericenter_time;
  EXPECT_NEAR(longitude_deg(turned.subsatellite), 90 - spin * t_q * deg, 1e-9);
  EXPECT_NEAR(latitude_deg(turned.subsatellite), 0, 1e-9);
  EXPECT_NEAR(turned.failed[0].angle_from_subsatellite_deg,
              angle_from_subsatellite_deg(at_rest.midpoint, turned.subsatellite), 1e-9);
  // In the inertial frame (the hemisphere views): where the spring is now.
  const FractureSummary inertial = analyze_fractures(c.body, c.state, fracture_scope(c, /*in_body_frame=*/false));
  EXPECT_NEAR(inertial.failed[0].longitude_deg, std::remainder(at_rest.longitude_deg + spin * c.state.time * deg, 360.0),
              1e-9);
}

// ---- the spinning body -----------------------------------------------------------------------

/// welded-L3 spinning at `spin`, built, stretched and relaxed with its probe (also at eps_S = 5e-4).
struct SpinningBody {
  Config config;
  Checkpoint relaxed;
};

SpinningBody relax_spinning_welded_l3(double spin) {
  SpinningBody b;
  b.config = parse_config(with_spin(read_file(workflow_file("welded-L3.toml")), std::to_string(spin)), "spin.toml");
  b.config.encounters[0].failure_strain = 5e-4;  // probed too
  b.relaxed = shared_checkpoint("spinning-welded-L3-" + std::to_string(spin), [&] {
    Config config = b.config;
    const Checkpoint stretched = stretch_stage(build_stage(config), config);
    settle_time_step(config, stretched, "stretch.h5");
    Checkpoint c = begin_relax(stretched, config);
    EXPECT_EQ(run_relax(c, config, quiet_loop()), LoopOutcome::finished);
    return c;
  });
  b.config.integrator.dt = b.relaxed.stage.clock.dt;  // what settle_time_step chose
  b.config.choose_dt = false;
  return b;
}

const SpinningBody& spinning_welded_l3() {
  static const SpinningBody body = relax_spinning_welded_l3(0.3);
  return body;
}

TEST(SpinningBody, RelaxesToTheFlatteningOfItsLoveNumberWithin10Percent) {
  const SpinningBody& b = spinning_welded_l3();
  const Checkpoint& c = b.relaxed;
  const double spin = b.config.spin.rate();
  const ShellFlattening shape =
      shell_flattening(c.body, c.state, spin_rotation(spin, c.state.time).transpose());
  // h2 of the homogeneous sphere of the network's measured moduli (TS72, as validate --measure tide).
  const BodyMaterial sphere = measure_interior_moduli(c, body_material(c, b.config)).material;
  const double h2 =
      homogeneous_sphere_love_numbers(2, sphere.youngs_modulus, sphere.poisson_ratio, sphere.density, sphere.radius).h;
  const double theory = centrifugal_flattening(h2, spin);
  std::printf("[ info ] welded-L3 at Omega = %.2f: flattening %.5g, h2 q / 2 = %.5g (h2 = %.5g), ratio %.4f\n", spin,
              shape.flattening, theory, h2, shape.flattening / theory);
  EXPECT_NEAR(shape.flattening / theory, 1.0, 0.10);
  // The body spins at Omega about z, in the inertial frame.
  const Vec3 w = body_angular_velocity(c.body, c.state);
  EXPECT_NEAR(w.z(), spin, 1e-9);
  EXPECT_LT(w.head<2>().norm(), 1e-9);
}

TEST(SpinningBody, StaysInEquilibriumWhenLeftAlone) {
  const SpinningBody& b = spinning_welded_l3();
  const RelaxRecord& r = b.relaxed.stage.as<RelaxRecord>();
  // The probe: the relaxed, spinning body alone at low damping with failures on.
  EXPECT_EQ(r.probe_failures, 0);
  ASSERT_EQ(r.probe_other_strains, (std::vector<double>{5e-4, 2e-3}));  // the override, T1's weaker crust
  EXPECT_EQ(r.probe_other_failures, (std::vector<std::int64_t>{0, 0}));
  EXPECT_LT(r.probe_max_shell_strain, 1e-4) << "largest crust tension while spinning alone";
  EXPECT_LT(r.internal_kinetic_energy, 1e-8) << "kinetic energy in the co-rotating frame when relaxed";
  // One t_grav spinning freely (probe damping): the shape in the body frame keeps its flattening,
  // and no shell spring's strain changes by more than a small fraction of eps_S.
  Checkpoint c = b.relaxed;
  const double spin = b.config.spin.rate();
  const double before = shell_flattening(c.body, c.state, spin_rotation(spin, c.state.time).transpose()).flattening;
  std::vector<double> strain0;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s)
    if (c.body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell)) strain0.push_back(spring_strain(c.body, c.state, s));
  ForceField forces(c.body, force_options(b.config, b.config.relax.probe_damping));
  Leapfrog leapfrog(forces, StepClock{c.state.time, c.state.step, c.stage.clock.dt});
  leapfrog.advance(c.state, steps_for_duration(1.0, c.stage.clock.dt));
  const double after = shell_flattening(c.body, c.state, spin_rotation(spin, c.state.time).transpose()).flattening;
  double change = 0;
  std::size_t k = 0;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s)
    if (c.body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell))
      change = std::max(change, std::abs(spring_strain(c.body, c.state, s) - strain0[k++]));
  std::printf("[ info ] free spin for 1 t_grav: flattening %.5g -> %.5g, largest shell strain change %.2e\n", before,
              after, change);
  EXPECT_NEAR(after / before, 1.0, 0.02);
  EXPECT_LT(change, 1e-4);
}

/// quick.toml spinning at 0.6 with a short relaxation (60 steps) and T5 ("strong") from 2 R.
Config quick_spinning() {
  Config c = quick_config();
  c.spin.angular_velocity = 0.6;
  c.relax.duration = 60 * c.integrator.dt;
  c.relax.settle_duration = 20 * c.integrator.dt;
  c.relax.probe_duration = 20 * c.integrator.dt;
  c.encounter.start_distance = 2.2;
  c.encounter.end_distance = 2.2;
  validate(c, "quick-spinning");
  return c;
}

TEST(SpinningBody, RelaxAndEncounterResumeBitForBitOnAnyThreadCount) {
  const Config config = quick_spinning();
  const Checkpoint& stretched = quick_stretched();
  const int threads = omp_get_max_threads();
  const Checkpoint straight = relaxed_alike_on_one_and_two_threads(stretched, config);
  omp_set_num_threads(2);
  // It spins (in the inertial frame) and differs from the body without spin.
  EXPECT_NEAR(body_angular_velocity(straight.body, straight.state).z(), 0.6, 1e-9);

  // creep phase, settle phase, stability probe
  expect_relax_resumes_bit_for_bit(stretched, config, straight, {25, 45, 65}, "spin_resume");
  const ScratchFolder scratch("spin_resume_encounter");

  const Encounter spec = config.find_encounter("strong");
  Checkpoint done = begin_encounter(straight, config, spec);
  Checkpoint resumed = done;
  ASSERT_EQ(run_encounter(done, config, quiet_loop()), LoopOutcome::finished);
  const auto& failures = done.observables.failures;
  ASSERT_GT(failures.size(), 3u);
  StepLoopOptions o = quiet_loop();
  o.mid_checkpoint = scratch.path / "encounter.mid.h5";
  o.stop_after_step = failures[failures.size() / 2].step;
  ASSERT_EQ(run_encounter(resumed, config, o), LoopOutcome::interrupted);
  resumed = read_checkpoint(o.mid_checkpoint);
  omp_set_num_threads(1);
  ASSERT_EQ(run_encounter(resumed, config, quiet_loop()), LoopOutcome::finished);
  omp_set_num_threads(threads);
  EXPECT_EQ(state_hash(resumed.state), state_hash(done.state));
  EXPECT_EQ(resumed.observables.failures.size(), failures.size());

  // Angular momentum with spin: conserved relative to the total (spin + orbit).
  const ConservationDrift drift = conservation_drift(done.observables.timeseries);
  const auto& l0 = done.observables.timeseries.front().angular_momentum;
  std::printf("[ info ] spin 0.6: max |L - L0| / |L0| = %.2e (L0 = %.4f, %.4f, %.4f)\n",
              drift.max_relative_angular_momentum_change, l0[0], l0[1], l0[2]);
  EXPECT_LT(drift.max_relative_angular_momentum_change, 1e-12);
  EXPECT_LT(drift.max_momentum_change, 1e-12);
}

}  // namespace
}  // namespace tidalcrust
