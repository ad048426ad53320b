#include "stages/time_step.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "base/errors.hpp"
#include "integrate/stability_bound.hpp"

namespace tidalcrust {

double strongest_damping(const Config& config) {
  return std::max({config.relax.damping, config.relax.probe_damping, config.encounter.damping});
}

std::string settle_time_step(Config& config, const Checkpoint& body, const std::string& origin) {
  // One dt for relax and encounters: safe under the strongest damping any of them applies.
  const StabilityBound bound = stability_bound(body.body, body.state, strongest_damping(config));
  if (!(bound.safe_dt > 0)) {
    config.choose_dt = false;
    return "";
  }
  std::string note;
  if (config.choose_dt) {
    // Two significant digits, rounded down: a dt that reads well in file names and logs.
    const double target = chosen_dt_fraction * bound.safe_dt;
    const double unit = std::pow(10.0, std::floor(std::log10(target)) - 1);
    config.integrator.dt = std::floor(target / unit) * unit;
    config.choose_dt = false;
    note = fmt::format("dt: chose {:.3g} t_grav ({} x the safe bound {:.4g} t_grav with damping gamma = {:g}, "
                       "limited by {})",
                       config.integrator.dt, chosen_dt_fraction, bound.safe_dt, bound.damping,
                       bound.safe_limit.describe(body.body, body.state));
  }
  const double dt = config.integrator.dt;
  if (dt > bound.unstable_dt)
    throw InputError(fmt::format(
        "{}: integrator.dt = {:.4g} cannot be stable: it exceeds 2/omega = {:.4g} t_grav (omega^2 the stiffness/mass of "
        "{}; docs/material.md); choose dt <= {:.3g}{}",
        origin, dt, bound.unstable_dt, bound.unstable_limit.describe(body.body, body.state),
        chosen_dt_fraction * bound.safe_dt,
        config.from_material() ? " or leave integrator.dt out to have it chosen" : ""));
  // The warning uses the undamped bound: the damped Gershgorin sum counts every spring of a node
  // as if all lay along one line, and the quick body relaxes stably at 3.2x its damped bound.
  if (note.empty() && dt > bound.undamped_safe_dt)
    note = fmt::format("warning: integrator.dt = {:.4g} is above the safe stability bound {:.4g} t_grav of springs and "
                       "hinges (below the certain-instability bound {:.4g}; limited by {})",
                       dt, bound.undamped_safe_dt, bound.unstable_dt,
                       bound.safe_limit.describe(body.body, body.state));
  return note;
}

}  // namespace tidalcrust
