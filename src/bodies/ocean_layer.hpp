#pragma once
// An ocean under the crust (docs/ocean.md; issue 26): the interior nodes nearest the shell become
// the particles of a liquid layer (Species::liquid; forces/liquid_pressure.hpp) that carries
// pressure and no shear: the crust floats.
#include "bodies/build_body.hpp"

namespace tidalcrust {

/// The liquid springs keep this fraction of their stiffness: a shear modulus that small (a nearly
/// fluid layer) holds the liquid's zero-energy modes, which otherwise drift and tangle its
/// tetrahedra (measured: docs/ocean.md).
inline constexpr double liquid_shear_fraction = 1e-3;

/// Turns every interior node farther than 1 - thickness from the centre into a liquid particle;
/// every spring with a liquid end becomes a liquid spring (SpringKind::liquid, stiffness 0: it only
/// damps), every other cross spring goes (it would cross the ocean); Body::liquid gets K =
/// bulk_modulus (e_g) and the layer's tetrahedra: the Delaunay tetrahedra (CGAL) of the liquid
/// particles and the solid ones within 1.5 mean liquid spacings of one, those with a liquid corner
/// and no edge longer than 3 spacings, canonical order, positive orientation.
/// State::liquid_rest_volume: the volumes as built (zero pressure; the stretch stage sets the
/// hydrostatic ones). thickness in R, in (0, 1). InputError when no interior node lies that
/// shallow, or a liquid particle lies in no tetrahedron.
void add_ocean(BuiltBody& built, double thickness, double bulk_modulus);

}  // namespace tidalcrust
