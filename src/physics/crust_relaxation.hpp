#pragma once
// How the relax stage (paper section 2.8) takes the stress out of the crust: shell spring rest
// lengths creep toward the current lengths, hinge rest angles are reset to the current angles.
// Interior and cross springs are left alone: they carry the body's weight.
#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// Shell springs only: L0 += rate (L - L0), rate in [0, 1] (1: exactly stress-free).
void creep_shell_rest_lengths(const Body& body, State& state, double rate);

/// Every hinge's rest angle becomes its current angle (hinge_angle of hinge_geometry.hpp):
/// no flexural stress left.
void reset_hinge_rest_angles(const Body& body, State& state);

/// Mean distance of the shell nodes from the body's centre of mass (R); 0 without shell.
double mean_shell_radius(const Body& body, const State& state);

}  // namespace tidalcrust
