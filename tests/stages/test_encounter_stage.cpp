// The encounter stage on the quick body (workflows/quick.toml): set-up on the two-body orbit,
// closest approach, crust failures, resume and thread independence (bitwise), conservation,
// snapshots, second passes and bad input.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "stages/build_stage.hpp"
#include "io/checkpoint_file.hpp"
#include "model/config.hpp"
#include "physics/conservation.hpp"
#include "io/checkpoint_names.hpp"
#include "stages/analysis_stage.hpp"
#include "stages/encounter_stage.hpp"
#include "base/errors.hpp"
#include "analysis/crust_statistics.hpp"
#include "analysis/fracture_analysis.hpp"
#include "model/crust_field.hpp"
#include "physics/orbital_frame.hpp"
#include "stages/relax_stage.hpp"
#include "io/state_hash.hpp"
#include "stages/stretch_stage.hpp"
#include "physics/two_body_orbit.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"
#include "support/shared_checkpoint.hpp"

namespace tidalcrust {
namespace {

namespace fs = std::filesystem;
using namespace test_support;

/// The parent of the encounters: the relaxed quick body (its stability probe is not needed here).
const Checkpoint& quick_parent() { return quick_relaxed(false); }

/// The quick "strong" encounter (the T5 orbit: M2 = 0.5, q = 1.84, V_q = 1.6) run straight through on 2 threads,
/// with its snapshot files, once per test binary.
struct StrongRun {
  Config config;
  Encounter spec;
  Checkpoint begun;
  Checkpoint done;
  fs::path output;
};

const StrongRun& strong_run() {
  static const StrongRun run = [] {
    StrongRun r;
    r.config = quick_config();
    r.spec = r.config.find_encounter("strong");
    r.begun = begin_encounter(quick_parent(), r.config, r.spec);
    // The run and its snapshot files, made by the first test process that needs them
    // (tests/support/shared_checkpoint.hpp).
    const fs::path folder = shared_folder("quick-strong-encounter", [&](const fs::path& f) {
      Checkpoint done = r.begun;
      omp_set_num_threads(2);
      EXPECT_EQ(run_encounter(done, r.config, quiet_loop(), f / "strong.h5"), LoopOutcome::finished);
      write_checkpoint(f / "strong.h5", done);
    });
    r.output = folder / "strong.h5";
    r.done = read_checkpoint(r.output);
    return r;
  }();
  return run;
}

std::size_t count_failed(const State& state) {
  return static_cast<std::size_t>(std::count(state.springs.failed.begin(), state.springs.failed.end(), 1));
}

void expect_same_failures(const std::vector<FailureEvent>& a, const std::vector<FailureEvent>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].step, b[i].step) << "event " << i;
    EXPECT_EQ(a[i].spring, b[i].spring) << "event " << i;
    EXPECT_EQ(a[i].time, b[i].time) << "event " << i;
    EXPECT_EQ(a[i].strain, b[i].strain) << "event " << i;
    EXPECT_EQ(a[i].position, b[i].position) << "event " << i;
    EXPECT_EQ(a[i].released_energy, b[i].released_energy) << "event " << i;
  }
}

void expect_same_timeseries(const std::vector<TimeseriesSample>& a, const std::vector<TimeseriesSample>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].time, b[i].time) << "sample " << i;
    EXPECT_EQ(a[i].failed, b[i].failed) << "sample " << i;
    EXPECT_EQ(a[i].kinetic_energy, b[i].kinetic_energy) << "sample " << i;
    EXPECT_EQ(a[i].momentum, b[i].momentum) << "sample " << i;
    EXPECT_EQ(a[i].angular_momentum, b[i].angular_momentum) << "sample " << i;
    EXPECT_EQ(a[i].perturber_offset, b[i].perturber_offset) << "sample " << i;
    // The energy budget, its accumulators included (they continue across a resume).
    for (double TimeseriesSample::*term :
         {&TimeseriesSample::internal_kinetic_energy, &TimeseriesSample::spring_energy, &TimeseriesSample::hinge_energy,
          &TimeseriesSample::self_gravity_energy, &TimeseriesSample::perturber_energy,
          &TimeseriesSample::damping_dissipated, &TimeseriesSample::failure_released,
          &TimeseriesSample::hinge_residual_work})
      EXPECT_EQ(a[i].*term, b[i].*term) << "sample " << i;
  }
}

Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

TEST(EncounterStage, BeginPlacesPerturberOnTheOrbitAndLeavesTheBodyAlone) {
  const StrongRun& r = strong_run();
  const Checkpoint& parent = quick_parent();
  const Checkpoint& c = r.begun;

  EXPECT_STREQ(c.stage.name(), "encounter");
  EXPECT_FALSE(c.stage.complete);
  EXPECT_EQ(c.stage.parent_hash, state_hash(parent.state));
  EXPECT_EQ(c.stage.as<EncounterRecord>().encounter.name, "strong");
  EXPECT_EQ(c.config_toml, to_toml(r.config));
  EXPECT_EQ(c.state.position, parent.state.position);
  EXPECT_EQ(c.state.velocity, parent.state.velocity);
  EXPECT_EQ(c.state.springs.rest_length, parent.state.springs.rest_length);
  EXPECT_EQ(c.state.springs.stiffness, parent.state.springs.stiffness);
  EXPECT_EQ(c.state.step, parent.state.step);
  EXPECT_EQ(c.state.time, parent.state.time);
  const EncounterRecord& record = c.stage.as<EncounterRecord>();
  EXPECT_EQ(c.stage.clock.dt, r.config.integrator.dt);
  EXPECT_EQ(record.damping, r.config.encounter.damping);

  // Perturber on the incoming branch at start_distance from the body's centre of mass, with
  // the two-body relative velocity; the orbit's pericenter lies along +y.
  const TwoBodyOrbit orbit = perturber_orbit(r.spec.perturber_mass, r.spec.pericenter, r.spec.pericenter_speed);
  const EncounterStart start = encounter_start(orbit, r.config.encounter.start_distance);
  const Vec3 rel = vec(c.state.perturber.position) - body_center_of_mass(c.body, c.state);
  const Vec3 vrel = vec(c.state.perturber.velocity) - body_center_of_mass_velocity(c.body, c.state);
  ASSERT_TRUE(c.state.perturber.present);
  EXPECT_EQ(c.state.perturber.mass, r.spec.perturber_mass);
  EXPECT_NEAR(rel.norm(), r.config.encounter.start_distance, 1e-12);
  EXPECT_LT((rel - start.relative.position).norm(), 1e-12);
  EXPECT_LT((vrel - start.relative.velocity).norm(), 1e-12);
  EXPECT_GT(rel.x(), 0);  // comes in from +x
  EXPECT_NEAR(rel.z(), 0, 1e-12);

  // Schedule in steps.
  const double t_peri = start.time_to_pericenter;
  const double t_after = orbit.time_to_pericenter(r.config.encounter.end_distance);
  EXPECT_EQ(c.stage.clock.start_step, parent.state.step);
  EXPECT_EQ(c.stage.end_step, c.stage.clock.start_step + steps_for_duration(t_peri + t_after, c.stage.clock.dt));
  EXPECT_EQ(record.pericenter_step, c.stage.clock.start_step + steps_for_duration(t_peri, c.stage.clock.dt));
  EXPECT_EQ(record.encounter, r.spec);
  EXPECT_EQ(record.pericenter_time, parent.state.time + t_peri);
  EXPECT_NEAR(record.min_distance, r.config.encounter.start_distance, 1e-12);
  EXPECT_EQ(record.failure_strain, r.config.shell.failure_strain);
  EXPECT_EQ(record.failed_stiffness_factor, r.config.shell.failed_stiffness_factor);
  EXPECT_EQ(record.failure_rule, FailureRule(PaperFailureRule{r.config.encounter.fail_interval}));
  EXPECT_EQ(record.sample_interval, r.config.encounter.sample_interval);

  // Snapshots: ascending, inside (start, end], at pericenter and at the end.
  const auto& snaps = record.snapshot_steps;
  ASSERT_GE(snaps.size(), 2u);
  EXPECT_TRUE(std::is_sorted(snaps.begin(), snaps.end()));
  EXPECT_GT(snaps.front(), c.stage.clock.start_step);
  EXPECT_EQ(snaps.back(), c.stage.end_step);
  EXPECT_TRUE(std::binary_search(snaps.begin(), snaps.end(), record.pericenter_step));

  // Fresh observables: no failures yet, one sample of the starting state.
  EXPECT_TRUE(c.observables.failures.empty());
  ASSERT_EQ(c.observables.timeseries.size(), 1u);
  const Conservation totals = measure_conservation(c.body, c.state);
  EXPECT_EQ(c.observables.timeseries[0].time, c.state.time);
  EXPECT_EQ(c.observables.timeseries[0].momentum, totals.momentum);
  EXPECT_EQ(c.observables.timeseries[0].angular_momentum, totals.angular_momentum);
  const Vec3 offset = vec(c.state.perturber.position) - body_center_of_mass(c.body, c.state);
  EXPECT_EQ(c.observables.timeseries[0].perturber_offset, (std::array<double, 3>{offset.x(), offset.y(), offset.z()}));
}

TEST(EncounterStage, PerturberReachesPericenterAtQWithSpeedVq) {
  const StrongRun& r = strong_run();
  const EncounterRecord& s = r.done.stage.as<EncounterRecord>();
  const double q = r.spec.pericenter, vq = r.spec.pericenter_speed;
  EXPECT_NEAR(s.min_distance, q, 0.01 * q);
  EXPECT_NEAR(s.speed_at_min, vq, 0.01 * vq);
  // ... at the time of the analytic pericenter (within 0.02 t_grav: 5 steps at dt = 0.004).
  EXPECT_NEAR(s.time_of_min, s.pericenter_time, 0.02);
  EXPECT_TRUE(r.done.stage.complete);
  EXPECT_EQ(r.done.state.step, r.done.stage.end_step);
  // It ends back at end_distance (same orbit, within the same 1%).
  const double end = (vec(r.done.state.perturber.position) - body_center_of_mass(r.done.body, r.done.state)).norm();
  EXPECT_NEAR(end, r.config.encounter.end_distance, 0.01 * r.config.encounter.end_distance);
}

TEST(EncounterStage, SampledPerturberOffsetsTraceTheOrbitAroundTheCentreOfMass) {
  const StrongRun& r = strong_run();
  const Checkpoint& c = r.done;
  const auto& series = c.observables.timeseries;
  ASSERT_GT(series.size(), 10u);
  const Vec3 last = vec(c.state.perturber.position) - body_center_of_mass(c.body, c.state);
  EXPECT_EQ(series.back().perturber_offset, (std::array<double, 3>{last.x(), last.y(), last.z()}));
  // The closest sampled offset is no closer than the closest approach measured every step, and
  // misses it by at most the chord sag over half a sample interval, (V_q h / 2)^2 / (2 q).
  std::size_t nearest = 0;
  for (std::size_t i = 0; i < series.size(); ++i)
    if (vec(series[i].perturber_offset).norm() < vec(series[nearest].perturber_offset).norm()) nearest = i;
  const double q = r.spec.pericenter, vq = r.spec.pericenter_speed;
  const double h = static_cast<double>(r.config.encounter.sample_interval) * c.stage.clock.dt;
  const double closest_sampled = vec(series[nearest].perturber_offset).norm();
  const double min_distance = c.stage.as<EncounterRecord>().min_distance;
  EXPECT_GE(closest_sampled, min_distance);
  EXPECT_LE(closest_sampled - min_distance, 1.01 * (vq * h / 2) * (vq * h / 2) / (2 * q) + 1e-12);
  // Pericenter on +y, moving along -x, in the xy plane.
  ASSERT_GT(nearest, 0u);
  ASSERT_LT(nearest + 1, series.size());
  const Vec3 at = vec(series[nearest].perturber_offset);
  EXPECT_NEAR(at.x(), 0, vq * h);
  EXPECT_NEAR(at.y(), q, 0.01 * q);
  const Vec3 along = vec(series[nearest + 1].perturber_offset) - vec(series[nearest - 1].perturber_offset);
  EXPECT_LT(along.x(), 0);
  EXPECT_LT(std::abs(along.y()), 0.1 * std::abs(along.x()));
  // Out of the plane only by what the lumpy body's pull adds (about 0.002 R here).
  for (const auto& sample : series) EXPECT_LT(std::abs(sample.perturber_offset[2]), 0.01 * q);
}

TEST(EncounterStage, StrongEncounterCracksTheCrustFacingThePerturber) {
  const StrongRun& r = strong_run();
  const Checkpoint& c = r.done;
  const auto& failures = c.observables.failures;
  const std::size_t shell_springs = c.body.count_springs(SpringKind::shell);
  std::printf("[ info ] quick strong: %zu failures (%.1f%% of %zu shell springs)\n", failures.size(),
              100.0 * static_cast<double>(failures.size()) / static_cast<double>(shell_springs), shell_springs);
  EXPECT_GE(failures.size(), 30u);
  EXPECT_LT(failures.size(), shell_springs / 2);
  // Mostly on the hemisphere facing pericenter (+y from the centre of mass; about 0.9 here).
  const FractureSummary fractures = analyze_fractures(c.body, c.state);
  EXPECT_EQ(fractures.count(), failures.size());
  EXPECT_GT(fractures.hemisphere_fraction, 0.75);
  EXPECT_EQ(count_failed(c.state), failures.size() + count_failed(quick_parent().state));

  const double eps = c.stage.as<EncounterRecord>().failure_strain;
  const double factor = c.stage.as<EncounterRecord>().failed_stiffness_factor;
  const std::int64_t interval = r.config.encounter.fail_interval;
  std::set<std::int32_t> springs;
  for (std::size_t i = 0; i < failures.size(); ++i) {
    const FailureEvent& e = failures[i];
    const auto n = static_cast<std::size_t>(e.spring);
    EXPECT_EQ(c.body.spring_kind[n], static_cast<std::uint8_t>(SpringKind::shell));
    EXPECT_EQ((e.step - c.stage.clock.start_step) % interval, 0) << "failure " << i << " off the t_fail schedule";
    if (i > 0) {
      EXPECT_GT(e.step, failures[i - 1].step) << "at most one failure per check";
    }
    EXPECT_GT(e.strain, eps);
    EXPECT_TRUE(springs.insert(e.spring).second) << "spring " << e.spring << " failed twice";
    EXPECT_EQ(c.state.springs.failed[n], 1);
    EXPECT_EQ(c.state.springs.stiffness[n], quick_parent().state.springs.stiffness[n] * factor);
  }
}

TEST(EncounterStage, MomentumAndAngularMomentumAreConserved) {
  const StrongRun& r = strong_run();
  const auto& series = r.done.observables.timeseries;
  const double m2 = r.spec.perturber_mass;
  const double momentum_scale = m2 * r.spec.pericenter_speed;
  const double angular_scale = m2 * r.spec.pericenter * r.spec.pericenter_speed;
  ASSERT_GT(series.size(), 10u);
  double dp = 0, dl = 0;
  for (const auto& sample : series) {
    dp = std::max(dp, (vec(sample.momentum) - vec(series.front().momentum)).norm());
    dl = std::max(dl, (vec(sample.angular_momentum) - vec(series.front().angular_momentum)).norm());
  }
  std::printf("[ info ] max |dP|/(M2 V_q) = %.2e, max |dL|/(M2 q V_q) = %.2e\n", dp / momentum_scale,
              dl / angular_scale);
  EXPECT_LT(dp / momentum_scale, 1e-12);
  EXPECT_LT(dl / angular_scale, 1e-12);

  // Sampled every sample_interval steps from the start, and at the end.
  const double dt = r.done.stage.clock.dt;
  const std::int64_t interval = r.config.encounter.sample_interval;
  for (std::size_t i = 0; i + 1 < series.size(); ++i)
    EXPECT_EQ(series[i].time, r.begun.state.time + static_cast<double>(i * interval) * dt);
  EXPECT_EQ(series.back().time, r.done.state.time);
  EXPECT_EQ(static_cast<std::size_t>(series.back().failed), count_failed(r.done.state));
}

TEST(EncounterStage, SnapshotFilesAtTheirSteps) {
  const StrongRun& r = strong_run();
  // analyze finds exactly the planned snapshots beside the output.
  std::vector<std::int64_t> found;
  for (const SnapshotFile& f : find_snapshots(r.output)) found.push_back(f.step);
  EXPECT_EQ(found, r.done.stage.as<EncounterRecord>().snapshot_steps);
  for (std::int64_t step : r.done.stage.as<EncounterRecord>().snapshot_steps) {
    const fs::path file = snapshot_path(r.output, step);
    EXPECT_EQ(file.filename().string(), "strong.snap-" + std::to_string(step) + ".h5");
    ASSERT_TRUE(fs::exists(file)) << file;
    const Checkpoint snap = read_checkpoint(file);
    EXPECT_STREQ(snap.stage.name(), "encounter");
    EXPECT_EQ(snap.state.step, step);
    EXPECT_EQ(snap.stage.as<EncounterRecord>().encounter.name, "strong");
    if (step == r.done.stage.end_step) {
      EXPECT_EQ(state_hash(snap.state), state_hash(r.done.state));
    }
  }
}

TEST(EncounterStage, ResumedRunIsBitIdentical) {
  const StrongRun& r = strong_run();
  const std::int64_t start = r.begun.stage.clock.start_step;
  const std::int64_t interval = r.config.encounter.fail_interval;
  // Stops: inside a t_fail interval, right at a failure step, and past pericenter.
  const auto& failures = r.done.observables.failures;
  ASSERT_GT(failures.size(), 5u);
  const std::int64_t inside = start + 10 * interval + 1;
  const std::int64_t at_failure = failures[failures.size() / 2].step;
  const std::int64_t late = (at_failure + r.done.stage.end_step) / 2 + 1;
  ASSERT_NE((inside - start) % interval, 0);
  ASSERT_LT(inside, at_failure);
  ASSERT_LT(at_failure, late);

  const ScratchFolder scratch("encounter_resume");
  const fs::path& dir = scratch.path;
  const fs::path output = dir / "strong.h5";
  Checkpoint c = begin_encounter(quick_parent(), r.config, r.spec);
  for (std::int64_t stop : {inside, at_failure, late}) {
    StepLoopOptions options = quiet_loop();
    options.stop_after_step = stop;
    options.mid_checkpoint = dir / "strong.mid.h5";
    ASSERT_EQ(run_encounter(c, r.config, options, output), LoopOutcome::interrupted);
    ASSERT_EQ(c.state.step, stop);
    c = read_checkpoint(options.mid_checkpoint);  // continue only from what the file holds
    EXPECT_EQ(c.state.step, stop);
    EXPECT_FALSE(c.stage.complete);
  }
  ASSERT_EQ(run_encounter(c, r.config, quiet_loop(), output), LoopOutcome::finished);

  EXPECT_EQ(state_hash(c.state), state_hash(r.done.state));
  expect_same_failures(c.observables.failures, r.done.observables.failures);
  expect_same_timeseries(c.observables.timeseries, r.done.observables.timeseries);
  EXPECT_EQ(c.stage.record, r.done.stage.record);
  for (std::int64_t step : c.stage.as<EncounterRecord>().snapshot_steps)
    EXPECT_EQ(state_hash(read_checkpoint(snapshot_path(output, step)).state),
              state_hash(read_checkpoint(snapshot_path(r.output, step)).state))
        << "snapshot at step " << step;
}

TEST(EncounterStage, SameBitsOnOneAndTwoThreads) {
  const StrongRun& r = strong_run();  // 2 threads
  Checkpoint c = begin_encounter(quick_parent(), r.config, r.spec);
  omp_set_num_threads(1);
  const LoopOutcome outcome = run_encounter(c, r.config, quiet_loop());
  omp_set_num_threads(2);
  ASSERT_EQ(outcome, LoopOutcome::finished);
  EXPECT_EQ(state_hash(c.state), state_hash(r.done.state));
  expect_same_failures(c.observables.failures, r.done.observables.failures);
}

TEST(EncounterStage, SecondPassReplacesThePerturberAndKeepsTheCracks) {
  const StrongRun& r = strong_run();
  Encounter again = r.spec;
  again.name = "again";
  again.perturber_mass = 0.25;
  again.failure_strain = 0.002;
  const Checkpoint c = begin_encounter(r.done, r.config, again);
  EXPECT_EQ(c.stage.parent_hash, state_hash(r.done.state));
  EXPECT_EQ(c.stage.clock.start_step, r.done.stage.end_step);
  EXPECT_EQ(c.state.springs.failed, r.done.state.springs.failed);
  EXPECT_EQ(c.state.springs.stiffness, r.done.state.springs.stiffness);
  EXPECT_EQ(c.state.position, r.done.state.position);
  EXPECT_EQ(c.state.perturber.mass, 0.25);
  EXPECT_EQ(c.stage.as<EncounterRecord>().failure_strain, 0.002);
  EXPECT_EQ(c.stage.as<EncounterRecord>().encounter.name, "again");
  const Vec3 rel = vec(c.state.perturber.position) - body_center_of_mass(c.body, c.state);
  EXPECT_NEAR(rel.norm(), r.config.encounter.start_distance, 1e-12);
  EXPECT_TRUE(c.observables.failures.empty());
  ASSERT_EQ(c.observables.timeseries.size(), 1u);
  EXPECT_EQ(static_cast<std::size_t>(c.observables.timeseries[0].failed), count_failed(r.done.state));
}

/// The InputError message of begin_encounter, or "" if it did not throw.
std::string rejection(const Checkpoint& parent, const Config& config, const Encounter& spec) {
  try {
    begin_encounter(parent, config, spec);
  } catch (const InputError& err) {
    return err.what();
  }
  return "";
}

TEST(EncounterStage, BadParametersAreRejected) {
  const Config config = quick_config();
  const Encounter good = config.find_encounter("strong");
  const Checkpoint& parent = quick_parent();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto with = [&](auto change) {
    Encounter spec = good;
    change(spec);
    return rejection(parent, config, spec);
  };
  EXPECT_NE(with([](Encounter& s) { s.perturber_mass = -1; }).find("perturber_mass"), std::string::npos);
  EXPECT_NE(with([&](Encounter& s) { s.perturber_mass = nan; }).find("perturber_mass"), std::string::npos);
  EXPECT_NE(with([](Encounter& s) { s.pericenter = 0.8; }).find("pericenter"), std::string::npos);
  EXPECT_NE(with([&](Encounter& s) { s.pericenter = nan; }).find("pericenter"), std::string::npos);
  EXPECT_NE(with([&](Encounter& s) { s.pericenter_speed = nan; }).find("pericenter_speed"), std::string::npos);
  EXPECT_NE(with([](Encounter& s) { s.pericenter_speed = 0; }).find("pericenter_speed"), std::string::npos);
  EXPECT_NE(with([](Encounter& s) { s.failure_strain = -0.001; }).find("failure_strain"), std::string::npos);
  // Pericenter beyond the start distance: the orbit cannot start there.
  EXPECT_NE(with([](Encounter& s) { s.pericenter = 3.5; }), "");
  EXPECT_EQ(with([](Encounter&) {}), "");

  // Wrong parent: not relax/encounter, or unfinished.
  Checkpoint stretched = parent;
  stretched.stage.record = StretchRecord{};
  EXPECT_NE(rejection(stretched, config, good).find("'stretch'"), std::string::npos);
  Checkpoint unfinished = parent;
  unfinished.stage.complete = false;
  EXPECT_NE(rejection(unfinished, config, good).find("unfinished"), std::string::npos);

  // run_encounter refuses anything but an encounter checkpoint.
  Checkpoint relaxed = parent;
  EXPECT_THROW(run_encounter(relaxed, config, quiet_loop()), InputError);
}

// Encounters the time step cannot resolve (issue 10, item 6) are refused by begin_encounter,
// which `run`, `encounter` and the workflow all go through, naming the encounter and dt: at
// dt = 0.004, M2 = 1e9 at V_q = 33100 passes pericenter in 0.01 steps, M2 = 1e6 at the parabolic
// speed in 0.4 steps, and M2 = 1e300 at its parabolic speed in far less.
TEST(EncounterStage, UnresolvableEncountersAreRefusedNamingDtAndTheEncounter) {
  const Config config = quick_config();
  ASSERT_EQ(config.integrator.dt, 0.004);
  const Checkpoint& parent = quick_parent();
  const auto parabolic = [](double m2, double q) { return std::sqrt(2.0 * (1.0 + m2) / q); };
  const Encounter cases[] = {encounter_of("fast", 1e9, 1.84, 33100),
                             encounter_of("heavy", 1e6, 1.84, parabolic(1e6, 1.84)),
                             encounter_of("extreme", 1e300, 1.84, parabolic(1e300, 1.84))};
  for (const Encounter& spec : cases) {
    const std::string message = rejection(parent, config, spec);
    EXPECT_NE(message.find("encounter '" + spec.name + "'"), std::string::npos) << message;
    EXPECT_NE(message.find("dt = 0.004"), std::string::npos) << message;
    EXPECT_NE(message.find("not resolved"), std::string::npos) << message;
  }
}

// The paper's encounters (paper-T.toml at its dt) and quick's "strong" span hundreds of steps
// per pericenter passage q/V_q and about a thousand or more in all: all accepted.
TEST(EncounterStage, PaperAndQuickEncountersAreResolved) {
  const Checkpoint& parent = quick_parent();
  const Config paper = load_config(workflow_file("paper-T.toml"));
  Config config = quick_config();
  config.integrator.dt = paper.integrator.dt;
  config.encounter.start_distance = paper.encounter.start_distance;
  config.encounter.end_distance = paper.encounter.end_distance;
  ASSERT_EQ(paper.encounters.size(), 4u);
  for (const Encounter& spec : paper.encounters) {
    EXPECT_EQ(rejection(parent, config, spec), "") << spec.name;
    EXPECT_GT(spec.pericenter / spec.pericenter_speed / config.integrator.dt, 100) << spec.name;
  }
  const Config quick = quick_config();
  const Encounter strong = quick.find_encounter("strong");
  EXPECT_EQ(rejection(parent, quick, strong), "");
  const Checkpoint begun = begin_encounter(parent, quick, strong);
  EXPECT_GT(begun.stage.end_step - begun.stage.clock.start_step, 500);  // 918
}

// The one-line summary `run` prints per encounter (stages/analysis_stage.hpp).
TEST(FractureSummaryLine, NoFailureSaysSoWithoutNotANumber) {
  FractureSummary none;
  none.shell_springs = 7680;
  none.hemisphere_fraction = NAN;
  none.median_angle_from_subsatellite_deg = NAN;
  const std::string line = fracture_summary_line("M0.1_q2_V1.4", none);
  EXPECT_EQ(line, "M0.1_q2_V1.4: no failed shell springs (0 of 7680)");
  EXPECT_EQ(line.find("nan"), std::string::npos);
}

TEST(FractureSummaryLine, FailuresGiveTheirStatistics) {
  FractureSummary some;
  some.shell_springs = 100;
  some.failed.resize(5);
  some.fraction_shell = 0.05;
  some.hemisphere_fraction = 0.8;
  some.median_angle_from_subsatellite_deg = 42.4;
  some.longest_crack_length = 0.25;
  const std::string line = fracture_summary_line("T5", some);
  EXPECT_NE(line.find("T5: 5 failed shell springs"), std::string::npos) << line;
  EXPECT_NE(line.find("median angle from it 42 deg"), std::string::npos) << line;
  EXPECT_NE(line.find("largest network 0.25 R"), std::string::npos) << line;
}

/// How many springs failed at each step of `failures` (step order).
std::map<std::int64_t, int> failures_per_step(const std::vector<FailureEvent>& failures) {
  std::map<std::int64_t, int> per_step;
  for (const auto& e : failures) ++per_step[e.step];
  return per_step;
}

/// Runs the quick body's "strong" encounter under `config` straight through, and again interrupted
/// at its middle failure's step (a mid-stage file written right at a failure) and resumed from
/// that file: the two must end in the same state and failure log. Returns the straight run.
Checkpoint run_and_check_resume(const Config& config, const std::string& scratch_name,
                                const Checkpoint& parent = quick_parent()) {
  const Encounter spec = config.find_encounter("strong");
  const ScratchFolder scratch(scratch_name);
  Checkpoint straight = begin_encounter(parent, config, spec);
  Checkpoint resumed = straight;
  EXPECT_EQ(run_encounter(straight, config, quiet_loop()), LoopOutcome::finished);
  const auto& failures = straight.observables.failures;
  EXPECT_GT(failures.size(), 5u);
  if (failures.empty()) return straight;
  StepLoopOptions options = quiet_loop();
  options.stop_after_step = failures[failures.size() / 2].step;
  options.mid_checkpoint = scratch.path / "strong.mid.h5";
  EXPECT_EQ(run_encounter(resumed, config, options), LoopOutcome::interrupted);
  resumed = read_checkpoint(options.mid_checkpoint);
  EXPECT_EQ(resumed.stage.as<EncounterRecord>().failure_rule, straight.stage.as<EncounterRecord>().failure_rule);
  EXPECT_EQ(run_encounter(resumed, config, quiet_loop()), LoopOutcome::finished);
  EXPECT_EQ(state_hash(resumed.state), state_hash(straight.state));
  expect_same_failures(resumed.observables.failures, failures);
  return straight;
}

// The shadow failure rule in a whole encounter: its record holds it, the run resumes bit for bit
// from a mid-stage file written right at a failure, and new cracks are held apart (fewer failures
// than the local rule of the same neighbourhood on the same body and orbit).
TEST(EncounterStage, ShadowRuleResumesBitIdenticallyAndFailsFewerThanLocal) {
  Config config = quick_config();
  config.encounter.failure_rule = FailureRuleKind::shadow;
  config.encounter.shadow_distance = 0.8;  // > r_ex = 2 L_S on the quick body (level 3)
  const Checkpoint shadow = run_and_check_resume(config, "encounter_shadow");
  const auto* rule = std::get_if<ShadowFailureRule>(&shadow.stage.as<EncounterRecord>().failure_rule);
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->shadow_distance, 0.8);
  EXPECT_LT(rule->local.exclusion_distance, 0.8);

  config.encounter.failure_rule = FailureRuleKind::local;
  Checkpoint local = begin_encounter(quick_parent(), config, config.find_encounter("strong"));
  ASSERT_EQ(run_encounter(local, config, quiet_loop()), LoopOutcome::finished);
  // 290 against 339 when written; one run's spread is about 3% (docs/results/ensembles.md).
  const std::size_t failures = shadow.observables.failures.size();
  EXPECT_LT(static_cast<double>(failures), 0.95 * static_cast<double>(local.observables.failures.size()))
      << "shadow " << failures << ", local " << local.observables.failures.size();
}

// The griffith rule in a whole encounter: its record holds the flaw and the tip strain factor,
// the first failure opens a whole flaw at one step, and the run resumes bit for bit.
TEST(EncounterStage, GriffithRuleOpensFlawsAndResumesBitIdentically) {
  Config config = quick_config();
  config.encounter.failure_rule = FailureRuleKind::griffith;
  config.encounter.shadow_distance = 0.8;
  config.encounter.flaw_length = 0.8;  // ~ 3 L_S on the quick body (level 3)
  const Checkpoint straight = run_and_check_resume(config, "encounter_griffith");
  const auto& record = straight.stage.as<EncounterRecord>();
  const auto* rule = std::get_if<GriffithFailureRule>(&record.failure_rule);
  ASSERT_NE(rule, nullptr);
  EXPECT_EQ(rule->flaw_length, 0.8);
  EXPECT_GT(rule->growth_strain_factor, 1.0);
  const auto& failures = straight.observables.failures;
  ASSERT_FALSE(failures.empty());
  EXPECT_GE(failures_per_step(failures).begin()->second, 3);  // the first flaw opens at one step
  EXPECT_GT(failures.front().strain, record.failure_strain);  // the candidate that opened it
}

// The critical_distance and nonlocal rules in a whole encounter: the record holds the rule and its
// segment, cracks open and grow by whole segments at one step (on the quick body a segment of 0.8 R
// crosses about 5 springs), and the run resumes bit for bit. The quick crust's failures at
// eps_S = 3e-3 come from its pre-stress, which a segment's mean averages away (no failure), so
// eps_S is 1.5e-3 here (23 failures under critical_distance when written).
// Under the nonlocal rule a crack's tip advances by the half segment ahead of it, which may hold
// no other intact spring: a step may then fail one spring, but only at a crack's tip, within the
// neighbourhood of an earlier failure.
// Returns the encounter run straight through; `exclusion_distance`, when given, sets r_ex as a
// length (with exclusion_radius at its default).
template <typename Rule>
Checkpoint expect_whole_segments_and_a_bitwise_resume(FailureRuleKind kind, double exclusion_radius, const std::string& name,
                                                      std::optional<double> exclusion_distance = std::nullopt) {
  Config config = quick_config();
  config.encounter.failure_rule = kind;
  config.encounter.exclusion_radius = exclusion_radius;
  config.encounter.exclusion_distance = exclusion_distance;
  config.encounter.shadow_distance = 0.8;
  config.encounter.flaw_length = 0.8;  // ~ 3 L_S on the quick body (level 3)
  for (auto& e : config.encounters)
    if (e.name == "strong") e.failure_strain = 1.5e-3;
  Checkpoint straight = run_and_check_resume(config, name);
  const auto& record = straight.stage.as<EncounterRecord>();
  const auto* stored = std::get_if<Rule>(&record.failure_rule);
  EXPECT_NE(stored, nullptr);
  if (!stored) return straight;
  // nonlocal_principal: its nonlocal rule's segment and neighbourhood.
  const auto* rule = [&] {
    if constexpr (std::is_same_v<Rule, PrincipalNonlocalFailureRule>) return &stored->nonlocal;
    else return stored;
  }();
  EXPECT_EQ(rule->segment_length, 0.8);
  EXPECT_FALSE(straight.observables.failures.empty());
  if (straight.observables.failures.empty()) return straight;
  const std::map<std::int64_t, int> per_step = failures_per_step(straight.observables.failures);
  EXPECT_GE(per_step.begin()->second, 3);  // the first segment fails at one step
  // Every failure belongs to a segment: no step fails a single spring, except at a tip (nonlocal).
  const double neighbourhood = rule->shadow.local.exclusion_distance;
  const auto& failures = straight.observables.failures;
  for (const auto& [step, count] : per_step) {
    if (count >= 2) continue;
    EXPECT_TRUE(kind == FailureRuleKind::nonlocal || kind == FailureRuleKind::nonlocal_principal) << "step " << step;
    const auto lone = std::find_if(failures.begin(), failures.end(), [&](const FailureEvent& e) { return e.step == step; });
    const Vec3 at(lone->position[0], lone->position[1], lone->position[2]);
    EXPECT_TRUE(std::any_of(failures.begin(), lone, [&](const FailureEvent& e) {
      return (Vec3(e.position[0], e.position[1], e.position[2]) - at).norm() < neighbourhood;
    })) << "step " << step;
  }
  return straight;
}

TEST(EncounterStage, CriticalDistanceRuleFailsWholeSegmentsAndResumesBitIdentically) {
  expect_whole_segments_and_a_bitwise_resume<CriticalDistanceFailureRule>(FailureRuleKind::critical_distance, 2.0,
                                                                          "encounter_critical_distance");
}

// The nonlocal rule: a neighbourhood of 1 L_S leaves room for the fit at a crack's tip (half a
// segment, 0.4 R, against r_ex + L_S = 0.30 R).
// Then the same neighbourhood given as a length (encounter.exclusion_distance, R): the record stores
// that length and the encounter is the same bit for bit. Then nonlocal_principal with the same
// neighbourhood.
TEST(EncounterStage, NonlocalRulesFailWholeSegmentsAndResumeBitIdentically) {
  const Checkpoint in_spacings =
      expect_whole_segments_and_a_bitwise_resume<NonlocalFailureRule>(FailureRuleKind::nonlocal, 1.0, "encounter_nonlocal");
  const double r_ex =
      std::get<NonlocalFailureRule>(in_spacings.stage.as<EncounterRecord>().failure_rule).shadow.local.exclusion_distance;
  EXPECT_NEAR(r_ex, 0.150, 0.005);  // 1 L_S of the quick body (level 3)
  const Checkpoint as_length = expect_whole_segments_and_a_bitwise_resume<NonlocalFailureRule>(
      FailureRuleKind::nonlocal, EncounterDefaults{}.exclusion_radius, "encounter_nonlocal_length", r_ex);
  EXPECT_EQ(std::get<NonlocalFailureRule>(as_length.stage.as<EncounterRecord>().failure_rule).shadow.local.exclusion_distance,
            r_ex);
  EXPECT_EQ(state_hash(as_length.state), state_hash(in_spacings.state));
  expect_same_failures(as_length.observables.failures, in_spacings.observables.failures);
  // nonlocal_principal on the same body and neighbourhood: whole segments and a bitwise resume,
  // with segments across the crust's principal direction, not the lattice's: other springs fail.
  const Checkpoint principal = expect_whole_segments_and_a_bitwise_resume<PrincipalNonlocalFailureRule>(
      FailureRuleKind::nonlocal_principal, 1.0, "encounter_nonlocal_principal");
  std::vector<std::int32_t> a, b;
  for (const auto& e : principal.observables.failures) a.push_back(e.spring);
  for (const auto& e : in_spacings.observables.failures) b.push_back(e.spring);
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_NE(a, b);
}

// A crust that varies (docs/crust.md): the quick body's crust given a strength dichotomy (weak toward
// the perturber, s11 = -0.3) and a weak great circle through the subsatellite point. The encounter
// reads each spring's factor from the body (stored in the mid-stage file: format 8) and resumes bit
// for bit; the weak parts take more than their share of the failures.
TEST(EncounterStage, AVaryingCrustResumesBitIdenticallyAndItsWeakPartsFailMore) {
  const Config config = quick_config();
  Checkpoint parent = quick_parent();
  CrustConfig crust;
  crust.strength_harmonics = "s11 = -0.3";
  crust.weak_lines = "pole_lon = 0, pole_lat = 0, half_width = 6, factor = 0.5";
  const CrustField field = make_crust_field(crust, "crust");
  for (std::size_t n = 0; n < parent.body.spring_count(); ++n)
    if (parent.body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell))
      parent.body.strength_factor[n] = field.strength_factor(
          0.5 * (vec3_at(parent.state.position, static_cast<std::size_t>(parent.body.springs[n][0])) +
                 vec3_at(parent.state.position, static_cast<std::size_t>(parent.body.springs[n][1]))));
  const Checkpoint done = run_and_check_resume(config, "encounter_varying_crust", parent);
  const CrustStatistics stats = crust_statistics(done.body, analyze_fractures(done));
  EXPECT_TRUE(stats.varies);
  EXPECT_GT(stats.weak.capture_ratio, 1.2) << stats.weak.failure_share << " of the failures on " << stats.weak.spring_share;
}

}  // namespace
}  // namespace tidalcrust
