#include "stages/encounter_stage.hpp"

#include "stages/child_checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "io/checkpoint_names.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "physics/orbital_frame.hpp"
#include "physics/shell_failure.hpp"
#include "io/state_hash.hpp"
#include "physics/timeseries_sample.hpp"
#include "physics/two_body_orbit.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {
namespace {

/// Hemisphere-view snapshots one t_grav before and after pericenter (paper Figure 6).
constexpr double snapshot_offset = 1.0;  // t_grav
constexpr double body_shape_interval = 0.5;  // t_grav, between the shape snapshots of a body without a crust

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

/// The most snapshot files one encounter may write (encounter.snapshot_interval): a level-4 body's
/// snapshot is ~1 MB.
constexpr double max_snapshots = 1000;

/// The interval of the snapshot series (t_grav): encounter.snapshot_interval, else for a body
/// without a crust (the paper's run N) body_shape_interval, else none (0).
double snapshot_series_interval(const Config& config, bool interior_only) {
  if (config.encounter.snapshot_interval > 0) return config.encounter.snapshot_interval;
  return interior_only ? body_shape_interval : 0.0;
}

/// Snapshot steps: one t_grav before pericenter, pericenter, one after, and the end; with a series
/// interval (snapshot_series_interval) also every interval counted from pericenter, before and
/// after, for the body's shape over time (Figure 5, analysis/body_shape.hpp; a snapshot of run N's
/// 798 particles is ~0.4 MB), except where one of the four lies within half an interval (+-1
/// t_grav need not be a whole number of intervals in steps: no pairs one step apart). The
/// interval becomes steps here, once. Kept inside (start_step, end_step], without duplicates.
std::vector<std::int64_t> plan_snapshots(std::int64_t start_step, std::int64_t pericenter_step,
                                         std::int64_t end_step, double dt, double series_interval) {
  const std::int64_t offset = steps_for_duration(snapshot_offset, dt);
  std::vector<std::int64_t> steps;
  for (std::int64_t s : {pericenter_step - offset, pericenter_step, pericenter_step + offset, end_step})
    steps.push_back(std::clamp(s, start_step + 1, end_step));
  if (series_interval > 0) {
    const std::int64_t interval = std::max<std::int64_t>(1, steps_for_duration(series_interval, dt));
    const std::vector<std::int64_t> figure6 = steps;
    auto near_figure6 = [&](std::int64_t s) {
      return std::any_of(figure6.begin(), figure6.end(), [&](std::int64_t f) { return 2 * std::abs(f - s) < interval; });
    };
    for (std::int64_t s = pericenter_step - (pericenter_step - start_step - 1) / interval * interval; s <= end_step;
         s += interval)
      if (s > start_step && !near_figure6(s)) steps.push_back(s);
  }
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  return steps;
}

}  // namespace

void check_encounter(const Config& config, const Encounter& spec, const std::string& source) {
  if (!source.empty()) {
    try {
      check_encounter(config, spec);
    } catch (const InputError& err) {
      throw InputError(fmt::format("{}: {}", source, err.what()));
    }
    return;
  }
  // validate_encounter checks the spec (finite M2 > 0, q > 1 outside the body, V_q > 0, eps_S > 0);
  // the configuration was validated as a whole before (no copy of it here: O(1) per encounter).
  validate_encounter(spec, "encounter parameters");
  const std::string what = fmt::format("encounter '{}' (M2 = {:g}, q = {:g}, V_q = {:g})", spec.name,
                                       spec.perturber_mass, spec.pericenter, spec.pericenter_speed);
  const double dt = config.integrator.dt;
  const double passage = spec.pericenter / spec.pericenter_speed;
  const double per_passage = passage / dt;
  // The passage first: it needs no orbit, and an orbit of an unresolvable speed (V_q = 1e308)
  // has no finite energy to compute.
  if (!(per_passage >= min_steps_per_pericenter_passage))
    throw InputError(fmt::format("{} is not resolved by dt = {:g}: the pericenter passage q/V_q = {:.3g} t_grav spans "
                                 "{:.3g} steps, at least {:g} needed (lower integrator.dt or V_q)",
                                 what, dt, passage, per_passage, min_steps_per_pericenter_passage));
  const double specific_energy = 0.5 * spec.pericenter_speed * spec.pericenter_speed -
                                 (1.0 + spec.perturber_mass) / spec.pericenter;
  if (!std::isfinite(specific_energy))
    throw InputError(fmt::format("{}: encounters.perturber_mass, pericenter and pericenter_speed give an orbit whose "
                                 "energy is not a finite number",
                                 what));
  double duration = 0;
  try {
    const TwoBodyOrbit orbit = perturber_orbit(spec.perturber_mass, spec.pericenter, spec.pericenter_speed, portable_mode(config));
    duration = encounter_start(orbit, config.encounter.start_distance).time_to_pericenter +
               orbit.time_to_pericenter(config.encounter.end_distance);
  } catch (const InputError& err) {
    // The orbit's own words, with the keys that made it.
    throw InputError(fmt::format("{}: {} (encounters.perturber_mass, pericenter, pericenter_speed; "
                                 "encounter.start_distance, end_distance)",
                                 what, err.what()));
  }
  const double interval = config.encounter.snapshot_interval;
  if (interval > 0 && !(duration / interval <= max_snapshots))
    throw InputError(fmt::format("{}: encounter.snapshot_interval = {:g} t_grav gives {:.3g} snapshots over the "
                                 "encounter's {:.3g} t_grav, at most {:g} (choose a longer interval)",
                                 what, interval, duration / interval, duration, max_snapshots));
  const double in_encounter = duration / dt;
  if (!(in_encounter >= min_steps_per_pericenter_passage))
    throw InputError(fmt::format(
        "{} is not resolved by dt = {:g}: the pericenter passage "
        "q/V_q = {:.3g} t_grav spans {:.3g} steps and the whole encounter {:.3g} steps, at least {:g} needed "
        "(lower integrator.dt or V_q)",
        what, dt, passage, per_passage, in_encounter, min_steps_per_pericenter_passage));
}

Checkpoint begin_encounter(const Checkpoint& parent, const Config& config, const Encounter& spec) {
  const bool usable_stage = std::holds_alternative<RelaxRecord>(parent.stage.record) ||
                            std::holds_alternative<EncounterRecord>(parent.stage.record);
  if (!usable_stage || !parent.stage.complete)
    throw InputError(fmt::format(
        "an encounter starts from a complete 'relax' or 'encounter' checkpoint, got {} '{}' checkpoint",
        parent.stage.complete ? "a complete" : "an unfinished (mid-stage)", parent.stage.name()));
  check_encounter(config, spec);
  if (spec.after && !std::holds_alternative<EncounterRecord>(parent.stage.record))
    throw InputError(fmt::format("encounter '{}' comes after '{}' and starts from its final 'encounter' checkpoint, got "
                                 "a '{}' checkpoint",
                                 spec.name, *spec.after, parent.stage.name()));

  const double start_distance = config.encounter.start_distance;
  const double end_distance = config.encounter.end_distance;
  const TwoBodyOrbit orbit = perturber_orbit(spec.perturber_mass, spec.pericenter, spec.pericenter_speed, portable_mode(config));
  const EncounterStart start = encounter_start(orbit, start_distance);
  const double time_after_pericenter = orbit.time_to_pericenter(end_distance);  // the orbit is symmetric

  // Body particles untouched; failed springs of an earlier pass stay failed. Observables belong
  // to this stage: a fresh failure log and timeseries (the parent's stay in the parent's file).
  Checkpoint c = child_checkpoint(parent, EncounterRecord{}, config);
  State& state = c.state;
  const double dt = c.stage.clock.dt;  // config.integrator.dt, as check_encounter used

  // The two-body orbit is relative to the body's centre of mass (a second pass replaces the
  // earlier perturber), turned to the encounter's orientation (none for the paper's orbit).
  const OrbitOrientation orientation = orbit_orientation(spec);
  const Vec3 com = body_center_of_mass(c.body, state);
  const Vec3 vcom = body_center_of_mass_velocity(c.body, state);
  Vec3 position = com + start.relative.position;
  Vec3 velocity = vcom + start.relative.velocity;
  if (!orientation.is_default()) {
    const Matrix3 rotation = orbit_rotation(orientation);
    position = com + rotation * start.relative.position;
    velocity = vcom + rotation * start.relative.velocity;
  }
  state.perturber.present = true;
  state.perturber.mass = spec.perturber_mass;
  state.perturber.position = {position.x(), position.y(), position.z()};
  state.perturber.velocity = {velocity.x(), velocity.y(), velocity.z()};

  StageInfo& stage = c.stage;
  stage.end_step = state.step + steps_for_duration(start.time_to_pericenter + time_after_pericenter, dt);
  const Separation initial = separation(c.body, state);
  EncounterRecord& record = stage.as<EncounterRecord>();
  record.encounter = spec;
  record.orbit = orientation;
  // Which encounter it continues, as the parent says (also for `encounter --from` an encounter file).
  if (const auto* before = std::get_if<EncounterRecord>(&parent.stage.record)) record.encounter.after = before->encounter.name;
  record.failure_strain = spec.failure_strain.value_or(config.shell.failure_strain);
  record.failed_stiffness_factor = config.shell.failed_stiffness_factor;
  record.damping = config.encounter.damping;
  record.failure_rule = make_failure_rule(config, spec.relaxation_crossings, c.body, state, dt);
  record.sample_interval = config.encounter.sample_interval;
  record.start_distance = start_distance;
  record.end_distance = end_distance;
  record.pericenter_time = state.time + start.time_to_pericenter;
  record.pericenter_step = state.step + steps_for_duration(start.time_to_pericenter, dt);
  const bool interior_only = c.body.count_species(Species::shell) == 0;
  record.snapshot_steps = plan_snapshots(stage.clock.start_step, record.pericenter_step, stage.end_step, dt,
                                         snapshot_series_interval(config, interior_only));
  record.min_distance = initial.distance;
  record.speed_at_min = initial.speed;
  record.time_of_min = state.time;
  record.step_of_min = state.step;

  ForceField forces(c.body, force_options(config, record.damping));
  c.observables.timeseries.push_back(sample_timeseries(c.body, state, forces, record.energy));
  return c;
}

LoopOutcome run_encounter(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options,
                          const std::filesystem::path& output) {
  if (!std::holds_alternative<EncounterRecord>(checkpoint.stage.record))
    throw InputError(fmt::format("run_encounter needs an 'encounter' checkpoint, got '{}'", checkpoint.stage.name()));
  if (!checkpoint.state.perturber.present)
    throw InputError("encounter checkpoint: /checkpoint/perturber is missing");
  // The schedule is the one the encounter began with (its record), not the configuration's.
  const EncounterRecord& schedule = checkpoint.stage.as<EncounterRecord>();
  const StoredFailureRule stored = stored_failure_rule(schedule.failure_rule);
  for (auto [name, steps] : {std::pair{"fail_interval", stored.fail_interval}, {"sample_interval", schedule.sample_interval}})
    if (steps < 1)
      throw InputError(fmt::format("encounter checkpoint: /checkpoint/record@{} = {} must be >= 1", name, steps));
  if (stored.kind != FailureRuleKind::paper && stored.relaxation_steps < 1)
    throw InputError(fmt::format("encounter checkpoint: /checkpoint/record@relaxation_steps = {} must be >= 1 for "
                                 "the {} failure rule",
                                 stored.relaxation_steps, choice_name(stored.kind)));
  const std::int64_t start_step = checkpoint.stage.clock.start_step;
  const std::int64_t end_step = checkpoint.stage.end_step;
  const FailureRule rule = schedule.failure_rule;
  const FailureThreshold threshold{schedule.failure_strain, schedule.failed_stiffness_factor};
  const std::int64_t sample_interval = schedule.sample_interval;
  const std::vector<std::int64_t> snapshots = schedule.snapshot_steps;

  ForceField forces(checkpoint.body, force_options(config, schedule.damping));
  Leapfrog leapfrog(forces, checkpoint.stage.clock);
  leapfrog.measure_work(true);

  // The energy budget's accumulators live in the record, so a resumed run continues them bit
  // for bit (docs/energy-budget.md).
  auto advance = [&](State& state) {
    leapfrog.step(state);
    EnergyLedger& ledger = checkpoint.stage.as<EncounterRecord>().energy;
    ledger.damping_dissipated += leapfrog.last_work().damping_removed;
    ledger.hinge_residual_work += leapfrog.last_work().hinge_added;
  };
  auto after_step = [&](Checkpoint& c) {
    State& state = c.state;
    EnergyLedger& ledger = c.stage.as<EncounterRecord>().energy;
    const std::int64_t done = state.step - start_step;
    const std::size_t logged = c.observables.failures.size();
    apply_failure_rule(rule, threshold, c.body, state, start_step, c.observables.failures);
    for (std::size_t k = logged; k < c.observables.failures.size(); ++k)
      ledger.failure_released += c.observables.failures[k].released_energy;
    if (done % sample_interval == 0 || state.step == end_step)
      c.observables.timeseries.push_back(sample_timeseries(c.body, state, forces, ledger));

    // Closest approach, sampled every step (the error of a step-sampled minimum is ~(V dt)^2/(8 q)).
    const Separation now = separation(c.body, state);
    auto& record = c.stage.as<EncounterRecord>();
    if (now.distance < record.min_distance) {
      record.min_distance = now.distance;
      record.speed_at_min = now.speed;
      record.time_of_min = state.time;
      record.step_of_min = state.step;
    }

    if (!output.empty() && std::binary_search(snapshots.begin(), snapshots.end(), state.step))
      write_checkpoint(snapshot_path(output, state.step), c);
  };
  return run_step_loop(checkpoint, advance, after_step, options);
}

}  // namespace tidalcrust
