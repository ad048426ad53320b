#pragma once
// The crust failure rule (paper section 2.6): only shell springs fail, only in tension, and in
// one check only the single most strained unfailed shell spring beyond eps_S fails, keeping
// the fraction F_Sk of its stiffness. Used by the encounter stage and the stability probe.
#include <optional>

#include "model/body.hpp"
#include "model/checkpoint.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// Strain (L - L0)/L0 of spring `n` (dimensionless) at the current positions.
double spring_strain(const Body& body, const State& state, std::size_t n);

/// Largest |strain| over the unfailed shell springs (0 without shell springs): how far the
/// crust is from its stress-free state.
double max_abs_shell_strain(const Body& body, const State& state);

/// Largest tensile strain over the unfailed shell springs (0 if none is stretched): the
/// quantity the failure rule compares with eps_S.
double max_shell_tension(const Body& body, const State& state);

/// One failure check: among the unfailed shell springs with strain > failure_strain (eps_S),
/// the most strained one (lowest index on ties) fails: stiffness *= failed_stiffness_factor
/// (F_Sk), failed = 1. Returns the event (time, step, strain, midpoint, the elastic energy
/// (1 - F_Sk) k (L - L0)^2/2 the drop removed) or nothing when no
/// spring exceeds eps_S. The caller decides when to check (every t_fail steps).
std::optional<FailureEvent> fail_most_strained_shell_spring(const Body& body, State& state, double failure_strain,
                                                            double failed_stiffness_factor);

}  // namespace tidalcrust
