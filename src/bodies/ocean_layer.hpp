#pragma once
// An ocean under the crust (docs/ocean.md; issue 26): the interior nodes nearest the shell become
// the particles of a liquid layer (Species::liquid; forces/liquid_pressure.hpp); the springs that
// held them and every spring between the crust and the interior go: the crust floats.
#include "bodies/build_body.hpp"

namespace tidalcrust {

/// The kernel support H in mean liquid spacings (V_layer / N_L)^(1/3): about 65 neighbours in
/// reach, where the Wendland C2 kernel's density sum follows a uniform compression to 4%
/// (tests/forces/test_liquid_pressure.cpp) and does not pair (Dehnen & Aly 2012).
inline constexpr double liquid_support_spacings = 2.5;

/// A solid particle closer than this many mean liquid spacings to a liquid particle as built
/// touches the liquid (Body::liquid.contact_radius): the crust's nodes (1.03 d_IS above the
/// liquid) and the floor's outer nodes.
inline constexpr double liquid_contact_reach = 1.3;

/// Turns every interior node farther than 1 - thickness from the centre into a liquid particle,
/// removes every spring with a liquid end and every cross spring (with their strength factors),
/// and sets Body::liquid:
/// H = liquid_support_spacings mean spacings s, K = bulk_modulus (e_g) divided by the mean response
/// d ln n / d ln rho of the liquid particles' kernel sums to a uniform compression of the body
/// (so that the layer's bulk modulus is bulk_modulus), density weight 1 for the liquid particles,
/// contact radius for every solid particle within liquid_contact_reach s of one (its distance to
/// the closest), contact stiffness bulk_modulus s; State::liquid_reference_density is each liquid particle's number density as built (zero
/// pressure; the stretch stage sets the hydrostatic one). thickness in R, in (0, 1).
/// InputError when no interior node lies that shallow.
void add_ocean(BuiltBody& built, double thickness, double bulk_modulus);

}  // namespace tidalcrust
