#include "stages/encounter_stage.hpp"

#include "stages/child_checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "model/encounter_snapshot_steps.hpp"
#include "io/snapshot_files.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "physics/orbital_frame.hpp"
#include "model/recorded_encounter.hpp"
#include "physics/shell_failure.hpp"
#include "io/state_hash.hpp"
#include "physics/timeseries_sample.hpp"
#include "physics/two_body_orbit.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {
namespace {

// StageInfo scalars of an encounter beyond the shared encounter_keys (recorded_encounter.hpp)
// and the snapshot steps (snapshot_files.hpp). The run reads its schedule from here, not
// from the configuration, so a resumed run follows exactly the schedule it began with.
namespace key {
constexpr const char* failure_strain = "failure_strain";                    ///< eps_S used
constexpr const char* failed_stiffness_factor = "failed_stiffness_factor";  ///< F_Sk used
constexpr const char* fail_interval = "fail_interval";                      ///< t_fail, steps
constexpr const char* sample_interval = "sample_interval";                  ///< steps
constexpr const char* start_time = "start_time";                            ///< t_grav at start_step
constexpr const char* start_distance = "start_distance";                    ///< R
constexpr const char* end_distance = "end_distance";                        ///< R
constexpr const char* pericenter_step = "pericenter_step";                  ///< step nearest the analytic pericenter
constexpr const char* time_of_min = "time_of_min";                          ///< t_grav of the closest approach
constexpr const char* step_of_min = "step_of_min";
}  // namespace key

/// Hemisphere-view snapshots one t_grav before and after pericenter (paper Figure 6).
constexpr double snapshot_offset = 1.0;  // t_grav

double required_scalar(const Checkpoint& checkpoint, const char* name) {
  const auto it = checkpoint.stage.scalars.find(name);
  if (it == checkpoint.stage.scalars.end())
    throw InputError(fmt::format("encounter checkpoint: scalar '{}' (/checkpoint/scalars) is missing", name));
  return it->second;
}

std::int64_t required_step_count(const Checkpoint& checkpoint, const char* name) {
  const double value = required_scalar(checkpoint, name);
  if (!(value >= 1) || value != std::floor(value))
    throw InputError(fmt::format("encounter checkpoint: scalar '{}' = {} must be a whole number >= 1", name, value));
  return static_cast<std::int64_t>(value);
}

/// Perturber relative to the body's centre of mass: distance (R) and speed (sqrt(GM/R)).
struct Separation {
  double distance = 0;
  double speed = 0;
};

Separation separation(const Body& body, const State& state) {
  const Vec3 com = body_center_of_mass(body, state);
  const Vec3 vcom = body_center_of_mass_velocity(body, state);
  const auto& p = state.perturber;
  const Vec3 r = Vec3(p.position[0], p.position[1], p.position[2]) - com;
  const Vec3 v = Vec3(p.velocity[0], p.velocity[1], p.velocity[2]) - vcom;
  return {r.norm(), v.norm()};
}

/// Snapshot steps: one t_grav before pericenter, pericenter, one after, and the end, kept
/// inside (start_step, end_step] and without duplicates.
std::vector<std::int64_t> plan_snapshots(std::int64_t start_step, std::int64_t pericenter_step,
                                         std::int64_t end_step, double dt) {
  const std::int64_t offset = steps_for_duration(snapshot_offset, dt);
  std::vector<std::int64_t> steps;
  for (std::int64_t s : {pericenter_step - offset, pericenter_step, pericenter_step + offset, end_step})
    steps.push_back(std::clamp(s, start_step + 1, end_step));
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  return steps;
}

}  // namespace

Checkpoint begin_encounter(const Checkpoint& parent, const Config& config, const EncounterSpec& spec) {
  const bool usable_stage = parent.stage.stage == "relax" || parent.stage.stage == "encounter";
  if (!usable_stage || !parent.stage.complete)
    throw InputError(fmt::format(
        "an encounter starts from a complete 'relax' or 'encounter' checkpoint, got {} '{}' checkpoint",
        parent.stage.complete ? "a complete" : "an unfinished (mid-stage)", parent.stage.stage));
  {
    // validate() checks the spec (finite M2 > 0, q > 1 outside the body, V_q > 0, eps_S > 0).
    Config checked = config;
    checked.encounters = {spec};
    validate(checked, "encounter parameters");
  }

  const double dt = config.integrator.dt;
  const double start_distance = config.encounter.start_distance;
  const double end_distance = config.encounter.end_distance;
  const TwoBodyOrbit orbit = perturber_orbit(spec.perturber_mass, spec.pericenter, spec.pericenter_speed);
  const EncounterStart start = encounter_start(orbit, start_distance);
  const double time_after_pericenter = orbit.time_to_pericenter(end_distance);  // the orbit is symmetric

  // Body particles untouched; failed springs of an earlier pass stay failed. Observables belong
  // to this stage: a fresh failure log and timeseries (the parent's stay in the parent's file).
  Checkpoint c = child_checkpoint(parent, "encounter", config);
  State& state = c.state;
  state.dt = dt;
  std::fill(state.springs.damping.begin(), state.springs.damping.end(), config.encounter.damping);

  // The two-body orbit is relative to the body's centre of mass (a second pass replaces the
  // earlier perturber).
  const Vec3 com = body_center_of_mass(c.body, state);
  const Vec3 vcom = body_center_of_mass_velocity(c.body, state);
  const Vec3 position = com + start.relative.position;
  const Vec3 velocity = vcom + start.relative.velocity;
  state.perturber.present = true;
  state.perturber.mass = spec.perturber_mass;
  state.perturber.position = {position.x(), position.y(), position.z()};
  state.perturber.velocity = {velocity.x(), velocity.y(), velocity.z()};

  StageInfo& stage = c.stage;
  stage.end_step = state.step + steps_for_duration(start.time_to_pericenter + time_after_pericenter, dt);
  const std::int64_t pericenter_step = state.step + steps_for_duration(start.time_to_pericenter, dt);
  const Separation initial = separation(c.body, state);
  stage.scalars = {
      {encounter_keys::perturber_mass, spec.perturber_mass},
      {encounter_keys::pericenter, spec.pericenter},
      {encounter_keys::pericenter_speed, spec.pericenter_speed},
      {encounter_keys::pericenter_time, state.time + start.time_to_pericenter},
      {encounter_keys::perturber_min_distance, initial.distance},
      {encounter_keys::perturber_speed_at_min, initial.speed},
      {key::failure_strain, spec.failure_strain.value_or(config.shell.failure_strain)},
      {key::failed_stiffness_factor, config.shell.failed_stiffness_factor},
      {key::fail_interval, static_cast<double>(config.encounter.fail_interval)},
      {key::sample_interval, static_cast<double>(config.encounter.sample_interval)},
      {key::start_time, state.time},
      {key::start_distance, start_distance},
      {key::end_distance, end_distance},
      {key::pericenter_step, static_cast<double>(pericenter_step)},
      {key::time_of_min, state.time},
      {key::step_of_min, static_cast<double>(state.step)},
  };
  store_snapshot_steps(stage, plan_snapshots(stage.start_step, pericenter_step, stage.end_step, dt));
  stage.labels = {{encounter_keys::name_label, spec.name}};

  c.observables.timeseries.push_back(sample_timeseries(c.body, state));
  return c;
}

LoopOutcome run_encounter(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options,
                          const std::filesystem::path& output) {
  if (checkpoint.stage.stage != "encounter")
    throw InputError(fmt::format("run_encounter needs an 'encounter' checkpoint, got '{}'", checkpoint.stage.stage));
  if (!checkpoint.state.perturber.present)
    throw InputError("encounter checkpoint: /checkpoint/perturber is missing");
  const std::int64_t start_step = checkpoint.stage.start_step;
  const std::int64_t end_step = checkpoint.stage.end_step;
  const double failure_strain = required_scalar(checkpoint, key::failure_strain);
  const double failed_stiffness_factor = required_scalar(checkpoint, key::failed_stiffness_factor);
  const std::int64_t fail_interval = required_step_count(checkpoint, key::fail_interval);
  const std::int64_t sample_interval = required_step_count(checkpoint, key::sample_interval);
  const StepClock clock{required_scalar(checkpoint, key::start_time), start_step, checkpoint.state.dt};
  const std::vector<std::int64_t> snapshots = snapshot_steps(checkpoint.stage);
  // Fail the run early rather than at the first lookup inside the loop.
  for (const char* name : {encounter_keys::perturber_min_distance, encounter_keys::perturber_speed_at_min,
                           key::time_of_min, key::step_of_min})
    required_scalar(checkpoint, name);

  ForceField forces(checkpoint.body, force_options(config));
  Leapfrog leapfrog(forces, clock);

  auto advance = [&](State& state) { leapfrog.step(state); };
  auto after_step = [&](Checkpoint& c) {
    State& state = c.state;
    const std::int64_t done = state.step - start_step;
    if (done % fail_interval == 0) {
      if (auto event = fail_most_strained_shell_spring(c.body, state, failure_strain, failed_stiffness_factor))
        c.observables.failures.push_back(*event);
    }
    if (done % sample_interval == 0 || state.step == end_step) c.observables.timeseries.push_back(sample_timeseries(c.body, state));

    // Closest approach, sampled every step (the error of a step-sampled minimum is ~(V dt)^2/(8 q)).
    const Separation now = separation(c.body, state);
    auto& scalars = c.stage.scalars;
    if (now.distance < scalars[encounter_keys::perturber_min_distance]) {
      scalars[encounter_keys::perturber_min_distance] = now.distance;
      scalars[encounter_keys::perturber_speed_at_min] = now.speed;
      scalars[key::time_of_min] = state.time;
      scalars[key::step_of_min] = static_cast<double>(state.step);
    }

    if (!output.empty() && std::binary_search(snapshots.begin(), snapshots.end(), state.step))
      write_checkpoint(snapshot_path(output, state.step), c);
  };
  return run_step_loop(checkpoint, advance, after_step, options);
}

}  // namespace tidalcrust
