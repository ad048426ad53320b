#pragma once
// The time step a body can take (issue 12): the workflow's dt checked against the stability
// bound of springs and hinges with the node masses (integrate/stability_bound.hpp), or, when a
// [material] workflow gives no integrator.dt, chosen from it. Done on the stretched body (the
// strengthened core is the stiffest it gets) before relaxing; docs/material.md.
#include <string>

#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

/// The largest spring damping rate gamma (1/t_grav) of the relax, its probe and the encounters:
/// the one dt of a body must be stable under each.
double strongest_damping(const Config& config);

/// Sets config.integrator.dt when config.choose_dt (chosen_dt_fraction of the safe bound, two
/// significant digits, rounded down) and clears choose_dt; then checks it: InputError (exit 2,
/// one line naming the bound and the limiting node) when dt exceeds the bound above which
/// leapfrog is certainly unstable. Returns the line to print: the chosen dt, or a warning when
/// dt lies between the safe and the unstable bound, or "" when dt is safe.
std::string settle_time_step(Config& config, const Checkpoint& body, const std::string& origin);

}  // namespace tidalcrust
