#pragma once
// An ocean under the crust (docs/ocean.md; issue 26): the interior nodes nearest the shell become
// the particles of a liquid layer (Species::liquid; forces/liquid_pressure.hpp) that carries
// pressure and no shear: the crust floats.
#include "bodies/build_body.hpp"

namespace tidalcrust {

/// Turns every interior node farther than 1 - thickness from the centre into a liquid particle;
/// every spring with a liquid end becomes a liquid spring (SpringKind::liquid) keeping
/// shear_fraction of its stiffness (a small static shear modulus that holds the liquid's
/// zero-energy modes, which otherwise drift and tangle its tetrahedra; docs/ocean.md), every other
/// cross spring goes (it would cross the ocean); Body::liquid gets K = bulk_modulus (e_g) and the
/// layer's tetrahedra: the Delaunay tetrahedra (CGAL) of the liquid particles, the crust's nodes and
/// the interior nodes within 1.5 mean liquid spacings of a liquid particle, those with a liquid or
/// crust corner and no edge longer than 3 spacings, canonical order, positive orientation. The
/// liquid's mass is lumped onto the tetrahedra's corners, V_t / 4 each at the liquid's mean density
/// (the crust's and floor's nodes carry their share). State::liquid_rest_volume: the nodal volumes
/// as built (zero pressure; the stretch stage sets the hydrostatic ones). thickness in R, in (0,
/// 1). InputError when no interior node lies that shallow, or a liquid particle lies in no
/// tetrahedron.
void add_ocean(BuiltBody& built, double thickness, double bulk_modulus, double shear_fraction);

}  // namespace tidalcrust
