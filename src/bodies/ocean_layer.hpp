#pragma once
// An ocean under the crust (docs/ocean.md; issue 26): the interior nodes nearest the shell become
// the particles of a liquid layer (Species::liquid; forces/liquid_pressure.hpp) whose springs carry
// pressure and no shear: the crust floats.
#include "bodies/build_body.hpp"

namespace tidalcrust {

/// Turns every interior node farther than 1 - thickness from the centre into a liquid particle;
/// every spring with a liquid end becomes a liquid spring (SpringKind::liquid, stiffness 0: the
/// volumetric energy of forces/liquid_pressure.hpp instead), every other cross spring goes (it
/// would cross the ocean); Body::liquid gets K = bulk_modulus (e_g) and each liquid particle's
/// share of the layer's volume between r = 1 - thickness and the crust's mean radius (R^3). The
/// stretch stage sets the liquid springs' rest lengths for the hydrostatic pressure. thickness in
/// R, in (0, 1). InputError when no interior node lies that shallow, or a liquid particle has no
/// spring.
void add_ocean(BuiltBody& built, double thickness, double bulk_modulus);

}  // namespace tidalcrust
