#pragma once
// The integrator: REBOUND's leapfrog, drift-kick-drift, second order and symplectic
// (design.md). Units: time t_grav, lengths R, velocities sqrt(GM/R).
#include <cstdint>
#include <vector>

#include "forces/force_field.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// Time as a function of the step count, never accumulated by t += dt, so a resumed run and
/// a straight run agree bit for bit: time(step) = start_time + (step - start_step) * dt.
/// A stage makes one clock when it starts (StepClock::starting_at(state)) and must rebuild the
/// same clock (same start_time, start_step, dt) when it resumes from a mid-stage checkpoint.
struct StepClock {
  double start_time = 0;         ///< t_grav at start_step
  std::int64_t start_step = 0;
  double dt = 0;                 ///< t_grav
  double time_at(std::int64_t step) const { return start_time + static_cast<double>(step - start_step) * dt; }
  static StepClock starting_at(const State& state) { return {state.time, state.step, state.dt}; }
};

/// A particle farther than this from the body's centre of mass means the run has blown up (R).
inline constexpr double blow_up_distance = 100.0;

class Leapfrog {
 public:
  /// Keeps a reference to `forces` (and through it to the Body).
  Leapfrog(ForceField& forces, StepClock clock);

  /// One step of clock.dt (state.dt must equal it):
  ///   x_half = x + v dt/2;  a = forces(x_half, v);  v += a dt;  x = x_half + v dt/2,
  /// the perturber moved the same way with the acceleration the body exerts on it. Damping uses
  /// the start-of-step velocities v. Then step += 1 and time = clock.time_at(step).
  /// Blow-up (non-finite acceleration or position, a collapsed shell triangle, a particle more
  /// than blow_up_distance from the centre of mass) throws SimulationError naming the step, the
  /// element and a likely cause; the state is then left unchanged at the start of the failing
  /// step (a valid step boundary, for the diagnostic checkpoint).
  void step(State& state);

  /// `count` steps.
  void advance(State& state, std::int64_t count);

  /// Accelerations of the last step (at its half-step positions).
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
};

}  // namespace tidalcrust
