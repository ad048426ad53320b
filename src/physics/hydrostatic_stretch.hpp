#pragma once
// The stretch of paper section 2.3: one common factor f on every rest length so that the mean
// radial acceleration of the surface vanishes, then either strengthening of the interior
// springs toward the hydrostatic P(r) = (2/3) pi G rho^2 (R^2 - r^2) (the paper's method,
// stretch.hydrostatic_support = "strengthen"), or each interior spring compressed to carry its
// own pressure at its built stiffness ("compress", docs/material.md); cross springs start
// stretch.cross_compression longer than f L. A layered body ([core]) uses the layered P(r).
#include "model/body.hpp"
#include "model/config.hpp"
#include "model/stage_records.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// Solves the stretch of `body` at rest at the positions of `built` (forces with self-gravity
/// and without damping). `stretched`: on entry the built springs [Ns]; on return their rest
/// lengths and stiffnesses as stretched (failure flags untouched). Returns every StretchRecord
/// field except dt_max. Throws InputError when the springs cannot hold the body (rest lengths
/// would have to change by more than 2x, or central springs be strengthened more than 100x),
/// SimulationError when stretch.max_iterations force evaluations do not reach stretch.tolerance.
StretchRecord stretch_springs(const Body& body, const State& built, const Config& config, SpringState& stretched);

/// Sets the rest volume V0 of every pressure node of the liquid layer (State::liquid_rest_volume;
/// forces/liquid_pressure.hpp) so that at the positions of `state` its pressure -K (V - V0)/V0 is
/// hydrostatic: P_top + rho int_r^{r_c} g(s) ds (rho the liquid's density, g(s) = m(< s)/s^2 of
/// everything under the crust, r_c the crust's mean radius; crust nodes P_top), with P_top chosen
/// so that the layer's radial push on the crust equals the crust nodes' weight (docs/ocean.md).
/// V0 = V / (1 - P/K). Body::liquid must be present; r from the centre of mass. InputError when
/// the deepest pressure reaches K/2 (ocean.bulk_modulus too small).
void set_hydrostatic_liquid_rest_volumes(const Body& body, State& state);

}  // namespace tidalcrust
