#include "stages/relax_stage.hpp"

#include "stages/child_checkpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <vector>

#include "physics/conservation.hpp"
#include "physics/crust_relaxation.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "forces/maxwell_liquid.hpp"
#include "integrate/leapfrog.hpp"
#include "physics/shell_failure.hpp"
#include "physics/spin_frame.hpp"
#include "stages/stability_probe.hpp"
#include "io/state_hash.hpp"
#include "physics/timeseries_sample.hpp"
#include "io/checkpoint_file.hpp"

namespace tidalcrust {
namespace {

/// eps_S of the weaker crust of encounter T1 (Table 4): the probe also checks it.
constexpr double weak_crust_failure_strain = 0.002;

/// Removes the crust stress exactly: shell rest lengths = current lengths, hinge rest angles =
/// current angles.
void zero_crust_stress(const Body& body, State& state, bool portable) {
  creep_shell_rest_lengths(body, state, 1.0);
  reset_hinge_rest_angles(body, state, portable);
}

/// The "balanced" support: the crust stress removed exactly, then the cross springs' rest
/// lengths chosen so that they alone carry every shell node's weight (balance_cross_springs).
/// The "lithostatic" support: every shell spring set to eps_L (lithostatic_crust_strain, the
/// compression its weight gives on the welded interior), hinges at rest, and the cross springs
/// carry the weight less the crust's outward push. The welded coupling's springs span orders of
/// magnitude in stiffness: the balance then moves every rest length alike (stiffness_weighted).
/// A spinning body (docs/spin.md) relaxes in the co-rotating frame: a node's weight is then
/// gravity plus the centrifugal acceleration.
void support_crust_by_cross_springs(ForceField& forces, const Body& body, State& state, const Config& config) {
  zero_crust_stress(body, state, portable_mode(config));
  std::vector<double> gravity(state.position.size());
  forces.compute_gravity(state.position.data(), gravity.data());
  add_rotating_frame_acceleration(body, config.spin.rate(), state.position.data(), nullptr, gravity);
  const bool weighted = config.cross.coupling == CrossCoupling::welded;
  if (config.relax.crust_support != CrustSupport::lithostatic) {
    balance_cross_springs(body, state, gravity, weighted);
    return;
  }
  set_shell_strain(body, state,
                   lithostatic_crust_strain(body, state, gravity, config.interior.radius, config.interior.spring_distance));
  const std::vector<double> crust_force = shell_spring_forces(body, state);
  balance_cross_springs(body, state, gravity, weighted, &crust_force);
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
///
/// A spinning body (spin.angular_velocity, docs/spin.md) relaxes in the frame co-rotating with
/// it: the step adds the centrifugal and Coriolis accelerations (add_rotating_frame_acceleration),
/// so that the body settles into its flattened equilibrium, which the spring damping (along
/// springs, blind to a rigid rotation) could not reach in the inertial frame. After every step
/// the body's rigid rotation relative to the frame is removed (remove_rigid_rotation): the
/// damping cannot stop it, and without it the body ends spinning at Omega (1 - dI/I), 0.7% slow
/// at Omega = 0.3 on welded-L3.
LoopOutcome relax_loop(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options) {
  const RelaxRecord& record = checkpoint.stage.as<RelaxRecord>();
  ForceField forces(checkpoint.body, force_options(config, record.damping));
  Leapfrog leapfrog(forces, checkpoint.stage.clock);
  if (const double spin = config.spin.rate(); spin != 0)
    leapfrog.set_extra_acceleration([&body = checkpoint.body, spin](const double* x, const double* v,
                                                                    std::vector<double>& a) {
      add_rotating_frame_acceleration(body, spin, x, v, a);
    });
  const RelaxConfig& relax = config.relax;
  const std::int64_t start = checkpoint.stage.clock.start_step;
  const std::int64_t creep_end = record.creep_end_step;
  // balanced or lithostatic; a floating crust creeps as the paper's (no cross springs to balance).
  const bool balanced = relax.crust_support == CrustSupport::balanced || relax.crust_support == CrustSupport::lithostatic;
  const bool spinning = config.spin.rate() != 0;
  auto after_step = [&](Checkpoint& c) {
    const std::int64_t done = c.state.step - start;
    if (spinning) remove_rigid_rotation(c.body, c.state);
    if (balanced) {
      if (c.state.step <= creep_end && (done % relax.rest_length_interval == 0 || c.state.step == creep_end))
        support_crust_by_cross_springs(forces, c.body, c.state, config);
    } else if (c.state.step < creep_end) {
      if (done % relax.rest_length_interval == 0) creep_shell_rest_lengths(c.body, c.state, relax.rest_length_rate);
      if (done % relax.hinge_reset_interval == 0) reset_hinge_rest_angles(c.body, c.state, portable_mode(config));
    } else if (c.state.step == creep_end) {
      zero_crust_stress(c.body, c.state, portable_mode(config));
    }
    if (done % config.encounter.sample_interval == 0)
      c.observables.timeseries.push_back(sample_timeseries(c.body, c.state));
  };
  return run_step_loop(checkpoint, [&](State& s) { leapfrog.step(s); }, after_step, options);
}

/// Records the relaxed body's state (a spinning body's kinetic energy in its co-rotating frame),
/// then turns a spinning body into the inertial frame (rotating_to_inertial): the relaxed state
/// spins, and its body frame at time t is Rz(Omega t) of the inertial one. A Maxwell liquid's
/// springs hand their resting forces to its support here (set_liquid_support), so that the
/// probe and every later stage start from this equilibrium while the liquid's shear relaxes.
void finish_relaxation(Checkpoint& checkpoint, const Config& config) {
  auto& record = checkpoint.stage.as<RelaxRecord>();
  const Body& body = checkpoint.body;
  State& state = checkpoint.state;
  record.max_shell_strain = max_abs_shell_strain(body, state);
  record.max_shell_tension = max_shell_tension(body, state);
  record.internal_kinetic_energy = internal_kinetic_energy(body, state);
  record.mean_shell_radius = mean_shell_radius(body, state);
  rotating_to_inertial(body, state, config.spin.rate(), portable_mode(config));
  if (body.liquid.present() && body.liquid.maxwell_time > 0) set_liquid_support(body, state);
  record.relaxed = true;
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
  const double eps_s = config.shell.failure_strain;
  const ProbeResult main = run_stability_probe(checkpoint, config, eps_s, options);
  if (main.interrupted) return false;
  std::int64_t runs = 1;
  std::vector<double> other_strains;
  std::vector<std::int64_t> other_failures;
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
    other_strains.push_back(strain);
    other_failures.push_back(failures);
  }
  auto& record = checkpoint.stage.as<RelaxRecord>();
  record.probe_failures = main.failures;
  record.probe_max_shell_strain = main.max_shell_tension;
  record.probe_failure_strain = eps_s;
  record.probe_runs = runs;
  record.probe_other_strains = std::move(other_strains);
  record.probe_other_failures = std::move(other_failures);
  return true;
}

}  // namespace

Checkpoint begin_relax(const Checkpoint& stretched, const Config& config) {
  require_complete<StretchRecord>(stretched, "relax");
  Checkpoint c = child_checkpoint(stretched, RelaxRecord{}, config);
  const StepClock& clock = c.stage.clock;
  // The Maxwell liquid creeps from the end of this stage on, by dt / tau_M a step (Leapfrog).
  maxwell_creep_rate(c.body, clock.dt);  // refuses a tau_M shorter than dt now, naming the workflow
  c.stage.end_step = c.state.step + steps_for_duration(config.relax.duration, clock.dt);
  auto& record = c.stage.as<RelaxRecord>();
  record.damping = config.relax.damping;
  record.creep_end_step =
      std::max(clock.start_step, c.stage.end_step - steps_for_duration(config.relax.settle_duration, clock.dt));
  if (record.creep_end_step == clock.start_step) {  // settle only
    if (config.relax.crust_support == CrustSupport::balanced || config.relax.crust_support == CrustSupport::lithostatic) {
      ForceField forces(c.body, force_options(config, record.damping));
      support_crust_by_cross_springs(forces, c.body, c.state, config);
    } else {
      zero_crust_stress(c.body, c.state, portable_mode(config));
    }
  }
  c.observables.timeseries.push_back(sample_timeseries(c.body, c.state));
  return c;
}

LoopOutcome run_relax(Checkpoint& checkpoint, const Config& config, const StepLoopOptions& options) {
  if (!std::holds_alternative<RelaxRecord>(checkpoint.stage.record))
    throw InputError(fmt::format("run_relax needs a 'relax' checkpoint (from begin_relax or a mid-stage relax "
                                 "checkpoint), got '{}'",
                                 checkpoint.stage.name()));
  if (checkpoint.stage.complete) return LoopOutcome::finished;
  if (checkpoint.config_toml != to_toml(config))
    throw InputError("relax: the configuration differs from the one this relax stage started with (stored in "
                     "/parameters/config); resume with the stored configuration or start again from the stretch "
                     "checkpoint");
  if (!checkpoint.stage.as<RelaxRecord>().relaxed) {
    if (relax_loop(checkpoint, config, options) == LoopOutcome::interrupted) return LoopOutcome::interrupted;
    finish_relaxation(checkpoint, config);
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
