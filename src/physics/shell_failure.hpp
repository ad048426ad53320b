#pragma once
// The crust failure rules. Only shell springs fail, only in tension beyond eps_S, keeping the
// fraction F_Sk of their stiffness. "paper" (section 2.6): in one check only the single most
// strained one fails, one check every t_fail steps. "local" (docs/failure-rule.md): every
// over-strained spring may fail, most strained first, but at most one per crack neighbourhood
// (radius r_ex) per relaxation interval (set in time from the shell's elastic crossing time).
// "shadow", "griffith", "critical_distance", "nonlocal" and "nonlocal_principal" add a crack spacing, flaws and averaging segments
// in R (model/failure_rule.hpp). Used by the encounter stage and the stability probe. A crust that varies (docs/crust.md): every
// rule compares a shell spring's strain with f eps_S (f = Body::failure_strain_factor) and orders
// candidates by strain / f; for f = 1 exactly as before.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/config.hpp"
#include "model/failure_rule.hpp"

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

/// One failure check: among the unfailed shell springs with strain > f failure_strain (eps_S times
/// the spring's strength factor f), the most over-strained one (strain / f; lowest index on ties) fails: stiffness *= failed_stiffness_factor
/// (F_Sk), failed = 1. Returns the event (time, step, strain, midpoint, the elastic energy
/// (1 - F_Sk) k (L - L0)^2/2 the drop removed) or nothing when no
/// spring exceeds eps_S. The caller decides when to check (every t_fail steps).
std::optional<FailureEvent> fail_most_strained_shell_spring(const Body& body, State& state, double failure_strain,
                                                            double failed_stiffness_factor);

/// What makes a shell spring fail and what is left of it (model/failure_rule.hpp: which springs
/// fail when).
struct FailureThreshold {
  double failure_strain = 0;           ///< eps_S
  double failed_stiffness_factor = 0;  ///< F_Sk
};

/// r_ex, the crack neighbourhood's radius (R): encounter.exclusion_distance when given, else
/// encounter.exclusion_radius * L_S, L_S the mean shell rest length (R) of the body (docs/failure-rule.md).
double crack_neighbourhood_radius(const Config& config, double L_S);

/// The rule config.encounter.failure_rule names, for a body: paper: fail_interval =
/// encounter.fail_interval. local: relaxation_steps = max(1, round(relaxation_crossings * L_S /
/// V_SP / dt)) (relaxation_crossings: the encounter's override, else
/// encounter.relaxation_crossings) and exclusion_distance = crack_neighbourhood_radius (r_ex), with L_S the
/// mean shell rest length and V_SP = sqrt(k_S 4 pi / M_S) the shell P-wave speed (eq. 19) of this
/// body; shadow and griffith the same; critical_distance and both nonlocal rules with flaw_length / 2 in place of L_S in
/// the relaxation interval. The one place where these times become steps. InputError for the local rule on a body
/// without a shell.
FailureRule make_failure_rule(const Config& config, std::optional<double> relaxation_crossings, const Body& body,
                              const State& state, double dt);

/// "warning: ..." naming each length of the configured rule (shadow_distance, flaw_length) shorter
/// than 3 L_S on this body, where the lattice cannot draw it, and for the nonlocal rules a half
/// segment shorter than r_ex + L_S (docs/failure-rule.md); "" when all are resolved, for the other
/// rules, or without a shell.
std::string unresolved_rule_lengths(const Config& config, const Body& body, const State& state);

/// Applies `rule` after a step: whether this step checks (paper: (step - start_step) %
/// fail_interval == 0; local: every step), and which springs fail. `log` is the stage's failure
/// log so far (step order); the new events are appended to it. Returns the number of new failures.
std::size_t apply_failure_rule(const FailureRule& rule, const FailureThreshold& threshold, const Body& body,
                               State& state, std::int64_t start_step, std::vector<FailureEvent>& log);

}  // namespace tidalcrust
