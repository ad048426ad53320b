#pragma once
// Blow-up diagnosis: what most likely made a run blow up, for the messages of SimulationError.
// It is about the time step, so it lives with the integrator; ForceField::describe names the
// element that went wrong.
#include <string>

#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// The likely cause of a blow-up: compares the time step dt (t_grav, the stage's clock) with the
/// stability bound of the stiffest spring (eq. 13, derive_quantities().dt_max) and names it when
/// dt exceeds it; otherwise points at a collapsing shell triangle or a dt too close to the bound.
/// A state with a Maxwell liquid's support (State::liquid_support) names the liquid's growing modes
/// first: left alone such a body breaks after tens of t_grav (docs/ocean.md, "A Maxwell liquid").
std::string likely_blow_up_cause(const Body& body, const State& state, double dt);

}  // namespace tidalcrust
