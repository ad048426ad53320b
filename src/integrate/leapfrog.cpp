#include "integrate/leapfrog.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <algorithm>

#include "base/errors.hpp"
#include "base/invariant.hpp"
#include "model/center_of_mass.hpp"
#include "integrate/blow_up.hpp"
#include "forces/maxwell_liquid.hpp"

namespace tidalcrust {

Leapfrog::Leapfrog(ForceField& forces, StepClock clock) : forces_(forces), clock_(clock) {
  // The configuration's range and the checkpoint reader have checked it.
  TIDALCRUST_ASSERT(clock.dt > 0 && std::isfinite(clock.dt),
                    fmt::format("time step dt must be a finite number > 0, got {}", clock.dt));
  creep_rate_ = maxwell_creep_rate(forces.body(), clock.dt);
}

void Leapfrog::step(State& state) {
  const std::size_t n3 = state.position.size();
  TIDALCRUST_ASSERT(state.velocity.size() == n3 && n3 == 3 * forces_.body().particle_count(),
                    fmt::format("state has {} position and {} velocity values for a body of {} particles", n3,
                                state.velocity.size(), forces_.body().particle_count()));
  const double dt = clock_.dt, half = 0.5 * dt;
  position_.resize(n3);
  velocity_.resize(n3);
  const double* x = state.position.data();
  const double* v = state.velocity.data();
  double* xw = position_.data();
  double* vw = velocity_.data();

  // Drift to the half step. The drift and kick loops and the checks are memory-light: one
  // thread, no fork/join.
  for (std::size_t k = 0; k < n3; ++k) xw[k] = x[k] + half * v[k];
  Perturber perturber = state.perturber;
  if (perturber.present)
    for (std::size_t k = 0; k < 3; ++k) perturber.position[k] += half * perturber.velocity[k];

  // Kick with forces at the half-step positions and start-of-step velocities.
  const ForceAlarms alarms = forces_.compute(xw, v, state.springs, state.hinges, perturber, state.liquid_rest_volume,
                                                 state.liquid_support, acc_);
  if (alarms.any())
    throw SimulationError(fmt::format("blow-up at step {} (t = {:.6g}): {}; {}", state.step + 1,
                                      clock_.time_at(state.step + 1), forces_.describe(alarms, xw),
                                      likely_blow_up_cause(forces_.body(), state, clock_.dt)));
  if (extra_) extra_(xw, v, acc_.body);
  if (measure_work_) half_.assign(xw, xw + n3);
  const double* a = acc_.body.data();
  for (std::size_t k = 0; k < n3; ++k) {
    vw[k] = v[k] + dt * a[k];
    xw[k] = xw[k] + half * vw[k];  // drift to the end of the step
  }
  if (perturber.present)
    for (std::size_t k = 0; k < 3; ++k) {
      perturber.velocity[k] += dt * acc_.perturber[k];
      perturber.position[k] += half * perturber.velocity[k];
    }

  // Commit only a healthy state: on failure the caller keeps the last good step boundary.
  check_positions(xw, perturber, state);
  work_ = measure_work_ ? forces_.work_of_step(x, half_.data(), xw) : StepWork{};
  // Copied, not swapped, so pointers into the state's arrays stay valid (~20 us a step).
  std::copy(position_.begin(), position_.end(), state.position.begin());
  std::copy(velocity_.begin(), velocity_.end(), state.velocity.begin());
  state.perturber = perturber;
  state.step += 1;
  state.time = clock_.time_at(state.step);
  if (!state.liquid_support.empty()) {
    const double creep = creep_liquid_springs(forces_.body(), state, creep_rate_);
    if (measure_work_) work_.damping_removed += creep;
  }
}

void Leapfrog::advance(State& state, std::int64_t count) {
  for (std::int64_t s = 0; s < count; ++s) step(state);
}

void Leapfrog::check_positions(const double* x, const Perturber& perturber, const State& state) const {
  const Body& body = forces_.body();
  const std::size_t n = body.particle_count();
  const Vec3 centre = mass_weighted_mean(body, x);
  const double limit2 = blow_up_distance * blow_up_distance;
  std::size_t far = n;
  for (std::size_t i = 0; i < n && far == n; ++i) {
    double r2 = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double d = x[3 * i + k] - centre[k];
      r2 += d * d;
    }
    if (!(r2 <= limit2)) far = i;  // also catches NaN
  }
  std::string what;
  if (far < n) {
    const std::size_t i = far;
    const double r = std::hypot(x[3 * i] - centre[0], x[3 * i + 1] - centre[1], x[3 * i + 2] - centre[2]);
    what = std::isfinite(r) ? fmt::format("particle {} is {:.3g} R from the body's centre of mass (limit {} R)", i, r,
                                          blow_up_distance)
                            : fmt::format("particle {} has a non-finite position", i);
  } else if (perturber.present &&
             !std::isfinite(perturber.position[0] + perturber.position[1] + perturber.position[2])) {
    what = "the perturber has a non-finite position";
  } else {
    return;
  }
  throw SimulationError(fmt::format("blow-up at step {} (t = {:.6g}): {}; {}", state.step + 1,
                                    clock_.time_at(state.step + 1), what, likely_blow_up_cause(body, state, clock_.dt)));
}

}  // namespace tidalcrust
