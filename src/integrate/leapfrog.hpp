#pragma once
// The integrator: REBOUND's leapfrog, drift-kick-drift, second order and symplectic
// (Rein & Liu 2012, REBOUND; paper section 2). Units: time t_grav, lengths R, velocities sqrt(GM/R).
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "forces/force_field.hpp"
#include "model/stage_records.hpp"  // StepClock
#include "model/state.hpp"

namespace tidalcrust {

/// A particle farther than this from the body's centre of mass means the run has blown up (R).
inline constexpr double blow_up_distance = 100.0;

class Leapfrog {
 public:
  /// Keeps a reference to `forces` (and through it to the Body). A stage makes its clock once, when
  /// it begins, stores it in its checkpoint, and hands the same clock back when it resumes.
  /// clock.dt must be finite and > 0 (TIDALCRUST_ASSERT). InputError when the body's liquid is a
  /// Maxwell liquid whose tau_M is shorter than dt (its explicit creep would overshoot).
  Leapfrog(ForceField& forces, StepClock clock);

  /// One step of clock.dt (the stage's time step; model/stage_records.hpp):
  ///   x_half = x + v dt/2;  a = forces(x_half, v);  v += a dt;  x = x_half + v dt/2,
  /// the perturber moved the same way with the acceleration the body exerts on it. Damping uses
  /// the start-of-step velocities v. Then step += 1 and time = clock.time_at(step). A Maxwell
  /// liquid (State::liquid_support set) then creeps by dt / tau_M (forces/maxwell_liquid.hpp); the
  /// energy its dashpots take is in last_work().damping_removed.
  /// Blow-up (non-finite acceleration or position, a collapsed shell triangle, a particle more
  /// than blow_up_distance from the centre of mass) throws SimulationError naming the step, the
  /// element and a likely cause; the state is then left unchanged at the start of the failing
  /// step (a valid step boundary, for the diagnostic checkpoint).
  void step(State& state);

  /// `count` steps.
  void advance(State& state, std::int64_t count);

  /// Measure, in every step, the work of the forces that have no potential (spring damping and
  /// the hinges' residual; ForceField::work_of_step): one more pass over springs and hinges.
  /// Off by default; it never changes the step itself.
  void measure_work(bool on) { measure_work_ = on; }
  /// The work of the last step (zero unless measured), G M^2/R.
  const StepWork& last_work() const { return work_; }

  /// An acceleration beyond the body's forces (an external field, a drag): called in every step
  /// after the force pass with the half-step positions x [N*3] (R), the start-of-step velocities
  /// v [N*3] (sqrt(GM/R)) and the force pass's accelerations a [N*3] (G M/R^2), which it changes
  /// in place (it adds its own); the kick then uses a. Its work is not in last_work().
  using ExtraAcceleration = std::function<void(const double* x, const double* v, std::vector<double>& a)>;
  /// Adds `extra` to every following step (none by default: the step is then exactly as above).
  void set_extra_acceleration(ExtraAcceleration extra) { extra_ = std::move(extra); }

  /// Accelerations of the last step (at its half-step positions; with the extra acceleration).
  const Accelerations& accelerations() const { return acc_; }
  const StepClock& clock() const { return clock_; }
  ForceField& forces() { return forces_; }

 private:
  /// Throws SimulationError if the end-of-step positions x [N*3] or the perturber blew up;
  /// `state` is the start-of-step state (for the step number and the message).
  void check_positions(const double* x, const Perturber& perturber, const State& state) const;

  ForceField& forces_;
  StepClock clock_;
  Accelerations acc_;
  std::vector<double> position_;  ///< workspace: half-step, then end-of-step positions
  std::vector<double> velocity_;  ///< workspace: end-of-step velocities
  std::vector<double> half_;      ///< workspace: half-step positions, kept when measuring work
  ExtraAcceleration extra_;
  double creep_rate_ = 0;  ///< dt / tau_M of a Maxwell liquid, 0 without one
  bool measure_work_ = false;
  StepWork work_;
};

}  // namespace tidalcrust
