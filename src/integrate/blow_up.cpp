#include "integrate/blow_up.hpp"

#include <fmt/format.h>

#include "model/derived_quantities.hpp"
#include "integrate/stability_bound.hpp"

namespace tidalcrust {

namespace {

std::string time_step_cause(const Body& body, const State& state, double dt) {
  const double bound = derive_quantities(body, state, 1.0).dt_max;
  if (bound > 0 && dt > bound)
    return fmt::format("likely cause: dt = {:.4g} is larger than the stability bound of the stiffest spring "
                       "(eq. 13: dt_max = {:.4g})",
                       dt, bound);
  // The bound with hinges and node masses (stability_bound.hpp): above it no step is stable.
  const StabilityBound full = stability_bound(body, state);
  if (full.unstable_dt > 0 && dt > full.unstable_dt)
    return fmt::format("dt = {:.4g} is within the spring stability bound (eq. 13: dt_max = {:.4g}); likely cause: dt "
                       "is larger than the bound with hinges, {:.4g} (docs/material.md), at {}",
                       dt, bound, full.unstable_dt, full.unstable_limit.describe(body, state));
  return fmt::format("dt = {:.4g} is within the spring stability bound (eq. 13: dt_max = {:.4g}); likely cause: "
                     "a collapsing shell triangle (perturber too close or too massive, or failed springs) "
                     "or dt too close to the bound",
                     dt, bound);
}

}  // namespace

std::string likely_blow_up_cause(const Body& body, const State& state, double dt) {
  if (!state.liquid_support.empty())
    return "likely cause: the Maxwell liquid's growing modes (ocean.maxwell_time: left alone, its body breaks "
           "after tens of t_grav; docs/ocean.md, \"A Maxwell liquid\"); about the time step: " +
           time_step_cause(body, state, dt);
  return time_step_cause(body, state, dt);
}

}  // namespace tidalcrust
