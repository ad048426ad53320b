#pragma once
// A Maxwell liquid (docs/ocean.md, "A Maxwell liquid"; LiquidLayer::maxwell_time > 0): the liquid
// layer's springs (SpringKind::liquid) give it a small shear stiffness that holds its zero-energy
// modes still, but a liquid carries no static shear. When the relaxation ends their static forces
// become a constant support force on each particle (State::liquid_support) and their rest lengths
// their lengths, so the body starts in the same equilibrium; from then on their rest lengths creep
// toward their lengths (a spring and a dashpot in series, relaxation time tau_M), so a load that
// lasts longer than tau_M is carried by the liquid's pressure alone. Subtracting the resting state's
// imbalance as a fixed force is how well-balanced schemes keep a discretised fluid at rest (Botta et
// al. 2004, J. Comput. Phys. 196, 539). The support is fixed in the inertial frame: a body that
// spins is refused (model/config.cpp).
// Units: G = M = R = 1. Forces G M^2/R^2, energies G M^2/R, tau_M t_grav.
#include <vector>

#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// The creep fraction per step, dt / tau_M (in (0, 1]), of a body whose liquid is a Maxwell liquid;
/// 0 for any other body. InputError naming ocean.maxwell_time when tau_M < dt (the explicit creep
/// would overshoot). dt in t_grav.
double maxwell_creep_rate(const Body& body, double dt);

/// Sets State::liquid_support [N*3] to the elastic forces of the liquid springs at the state's
/// positions (each spring's force on its two ends, springs in index order, no damping) and their
/// rest lengths to their lengths: the accelerations stay those of the state (up to rounding), the
/// springs now unstrained. The body must have a liquid layer.
void set_liquid_support(const Body& body, State& state);

/// One step of the Maxwell creep: every liquid spring's rest length L0 moves toward its length L
/// by the fraction `rate` = dt / tau_M (in (0, 1]; the explicit step of dL0/dt = (L - L0) / tau_M),
/// in index order. Returns the elastic energy this takes out of the springs, sum of
/// k (L - L0)^2 (1 - (1 - rate)^2) / 2 >= 0 (G M^2/R): the dashpot's dissipation.
double creep_liquid_springs(const Body& body, State& state, double rate);

/// Potential energy of the support, -sum_i F_i . x_i (G M^2/R) at positions [N*3] (R), in index
/// order; 0 for an empty support. The support sums to zero, so this does not depend on the origin.
double liquid_support_energy(const std::vector<double>& support, const double* position);

}  // namespace tidalcrust
