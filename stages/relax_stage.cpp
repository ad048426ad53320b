#include "stages/relax_stage.hpp"

#include "stages/child_checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "physics/conservation.hpp"
#include "physics/crust_relaxation.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "physics/shell_failure.hpp"
#include "stages/stability_probe.hpp"
#include "io/state_hash.hpp"
#include "physics/timeseries_sample.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {
namespace {

/// eps_S of the weaker crust of encounter T1 (Table 4): the probe also checks it.
constexpr double weak_crust_failure_strain = 0.002;

/// Scalar names of the stage bookkeeping.
constexpr const char* start_time_key = "start_time";  ///< time at start_step (the step clock)
constexpr const char* relaxed_key = "relaxed";        ///< 1: relaxation done, probe pending or done
constexpr const char* creep_end_key = "creep_end_step";  ///< last step of the creep phase

double scalar(const Checkpoint& c, const char* key) {
  const auto it = c.stage.scalars.find(key);
  if (it == c.stage.scalars.end())
    throw InputError(fmt::format("relax checkpoint lacks the stage scalar '{}' (/checkpoint scalars)", key));
  return it->second;
}

/// Removes the crust stress exactly: shell rest lengths = current lengths, hinge rest angles =
/// current angles.
void zero_crust_stress(const Body& body, State& state) {
  creep_shell_rest_lengths(body, state, 1.0);
  reset_hinge_rest_angles(body, state);
}

/// The relaxation proper: leapfrog at damping relax.damping, all schedules counted in steps
/// from start_step. Creep phase: every rest_length_interval steps the shell rest lengths creep
/// toward the current lengths, every hinge_reset_interval steps the hinge rest angles are
/// reset; at its last step the crust stress is zeroed exactly. Settle phase (the last
/// settle_duration): no creep, no resets.
///
/// Why the settle phase: a stress-free crust is not an equilibrium. The cross springs that
/// carry the shell are oblique, so each shell node also feels a tangential push of the order
/// of its weight, and nodes with fewer than three cross springs need the crust to hold them
/// up at all; only the crust can take these loads. While the creep runs the crust keeps
/// yielding and the shell keeps flowing (it never comes to rest), and a crust reset to zero
/// stress at the very end starts moving as soon as the damping is lowered: the probe then
/// sees strains of order eps_S. After the exact reset the settle phase lets the body find its
/// static equilibrium under the heavy damping, with the crust carrying only these loads (a
/// strain well below eps_S for the paper's T body), so the relaxed state is at rest and stays
/// at rest.
LoopOutcome relax_loop(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options) {
  ForceField forces(checkpoint.body, force_options(config));
  const StepClock clock{scalar(checkpoint, start_time_key), checkpoint.stage.start_step, checkpoint.state.dt};
  Leapfrog leapfrog(forces, clock);
  const RelaxConfig& relax = config.relax;
  const std::int64_t start = checkpoint.stage.start_step;
  const auto creep_end = static_cast<std::int64_t>(scalar(checkpoint, creep_end_key));
  auto after_step = [&](Checkpoint& c) {
    const std::int64_t done = c.state.step - start;
    if (c.state.step < creep_end) {
      if (done % relax.rest_length_interval == 0) creep_shell_rest_lengths(c.body, c.state, relax.rest_length_rate);
      if (done % relax.hinge_reset_interval == 0) reset_hinge_rest_angles(c.body, c.state);
    } else if (c.state.step == creep_end) {
      zero_crust_stress(c.body, c.state);
    }
    if (done % config.encounter.sample_interval == 0)
      c.observables.timeseries.push_back(sample_timeseries(c.body, c.state));
  };
  return run_step_loop(checkpoint, [&](State& s) { leapfrog.step(s); }, after_step, options);
}

/// Records the relaxed body's state.
void finish_relaxation(Checkpoint& checkpoint) {
  auto& scalars = checkpoint.stage.scalars;
  const Body& body = checkpoint.body;
  const State& state = checkpoint.state;
  scalars["max_shell_strain"] = max_abs_shell_strain(body, state);
  scalars["max_shell_tension"] = max_shell_tension(body, state);
  scalars["internal_kinetic_energy"] = internal_kinetic_energy(body, state);
  scalars["mean_shell_radius"] = mean_shell_radius(body, state);
  scalars[relaxed_key] = 1.0;
}

/// The failure strains to probe besides eps_S: T1's weaker crust and every encounter override.
std::set<double> extra_failure_strains(const Config& config) {
  std::set<double> strains{weak_crust_failure_strain};
  for (const auto& e : config.encounters)
    if (e.failure_strain) strains.insert(*e.failure_strain);
  strains.erase(config.shell.failure_strain);
  return strains;
}

/// Runs the stability probe(s) and stores their results; false if interrupted.
bool probe_stability(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options) {
  auto& scalars = checkpoint.stage.scalars;
  const double eps_s = config.shell.failure_strain;
  const ProbeResult main = run_stability_probe(checkpoint, config, eps_s, options);
  if (main.interrupted) return false;
  std::int64_t runs = 1;
  std::map<std::string, double> extra;
  for (double strain : extra_failure_strains(config)) {
    std::int64_t failures = 0;
    // Without failures the probe's trajectory is the failure-free one; if no shell strain
    // ever exceeded `strain` on it, a probe at `strain` would have run identically.
    if (main.failures == 0 && main.max_shell_tension <= strain) {
      failures = 0;
    } else {
      const ProbeResult other = run_stability_probe(checkpoint, config, strain, options);
      if (other.interrupted) return false;
      failures = other.failures;
      ++runs;
    }
    extra[fmt::format("stability_failures_at_{}", strain)] = static_cast<double>(failures);
  }
  scalars["stability_failures"] = static_cast<double>(main.failures);
  scalars["stability_max_shell_strain"] = main.max_shell_tension;
  scalars["stability_failure_strain"] = eps_s;
  scalars["stability_probe_runs"] = static_cast<double>(runs);
  scalars.insert(extra.begin(), extra.end());
  return true;
}

}  // namespace

Checkpoint begin_relax(const Checkpoint& stretched, const Config& config) {
  if (stretched.stage.stage != "stretch" || !stretched.stage.complete)
    throw InputError(fmt::format("relax needs a complete 'stretch' checkpoint, got {} '{}' checkpoint",
                                 stretched.stage.complete ? "a complete" : "an incomplete", stretched.stage.stage));
  Checkpoint c = child_checkpoint(stretched, "relax", config);
  c.state.dt = config.integrator.dt;
  c.stage.end_step = c.state.step + steps_for_duration(config.relax.duration, c.state.dt);
  c.stage.scalars[start_time_key] = c.state.time;
  const std::int64_t creep_end =
      std::max(c.stage.start_step, c.stage.end_step - steps_for_duration(config.relax.settle_duration, c.state.dt));
  c.stage.scalars[creep_end_key] = static_cast<double>(creep_end);
  if (creep_end == c.stage.start_step) zero_crust_stress(c.body, c.state);  // settle only
  std::fill(c.state.springs.damping.begin(), c.state.springs.damping.end(), config.relax.damping);
  c.observables.timeseries.push_back(sample_timeseries(c.body, c.state));
  return c;
}

LoopOutcome run_relax(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options) {
  if (checkpoint.stage.stage != "relax")
    throw InputError(fmt::format("run_relax needs a 'relax' checkpoint (from begin_relax or a mid-stage relax "
                                 "checkpoint), got '{}'",
                                 checkpoint.stage.stage));
  if (checkpoint.stage.complete) return LoopOutcome::finished;
  if (checkpoint.config_toml != to_toml(config))
    throw InputError("relax: the configuration differs from the one this relax stage started with (stored in "
                     "/parameters/config); resume with the stored configuration or start again from the stretch "
                     "checkpoint");
  const bool relaxed = checkpoint.stage.scalars.count(relaxed_key) && scalar(checkpoint, relaxed_key) == 1.0;
  if (!relaxed) {
    if (relax_loop(checkpoint, config, options) == LoopOutcome::interrupted) return LoopOutcome::interrupted;
    finish_relaxation(checkpoint);
    // "Relaxed, probe pending": the state is final, so an interrupted probe is simply rerun
    // from here and gives the same results.
    if (config.relax.stability_probe && !options.mid_checkpoint.empty()) {
      checkpoint.stage.complete = false;
      write_checkpoint(options.mid_checkpoint, checkpoint);
    }
  }
  if (config.relax.stability_probe && !probe_stability(checkpoint, config, options)) {
    checkpoint.stage.complete = false;
    return LoopOutcome::interrupted;
  }
  checkpoint.stage.complete = true;
  return LoopOutcome::finished;
}

}  // namespace tidalcrust
