#pragma once
// The layer under the crust measured as the springs see it: the affine moduli of the springs that
// cross each sphere about the centre (`validate --measure tide`, docs/crust-support.md). A random
// network has the same value at every radius; the paper's cross springs make a layer 25-40x softer
// than the interior, the welded coupling one equal to it. Units e_g.
#include <array>
#include <cstdint>
#include <vector>

#include "base/vec3.hpp"

namespace tidalcrust {

/// The affine moduli of the springs crossing the sphere of radius r about `center` (the traction
/// they carry across it per strain; the crossing-spring form of eq. 15): with n the unit vector of
/// a crossing spring pointing outward at the crossing and n_r its radial part,
///   compression M(r) = (1 / 4 pi r^2) sum k L n_r^3             (lambda + 2 mu; 6 E / 5 at nu = 1/4),
///   shear       G(r) = (1 / 4 pi r^2) sum k L n_r (1 - n_r^2) / 2 (mu; 2 E / 5 at nu = 1/4),
/// for an isotropic network of eq. 15's modulus E. positions [N*3] (R), springs (i, j), their
/// stiffness and rest length; only springs with `use[s]` true.
struct CrossingModuli {
  double radius = 0;
  double compression = 0;  ///< M, e_g
  double shear = 0;        ///< G, e_g
};
std::vector<CrossingModuli> crossing_moduli(const std::vector<double>& positions, const Vec3& center,
                                            const std::vector<std::array<std::int32_t, 2>>& springs,
                                            const std::vector<double>& stiffness,
                                            const std::vector<double>& rest_length, const std::vector<bool>& use,
                                            const std::vector<double>& radii);

}  // namespace tidalcrust
