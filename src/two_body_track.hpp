#pragma once
// The perturber's path relative to the body (Figure 7) when no sampled positions are stored:
// the two-body orbit (G = M = 1, mu = 1 + M2) in the map frame, pericenter q on +y at time
// t_peri, moving along -x there (orbital angular momentum along +z). Works for ellipses,
// parabolas and hyperbolas alike.
#include <vector>

#include "vec3.hpp"

namespace tidalcrust {

/// Perturber minus body centre of mass (R) at each of `times` (t_grav, any order).
/// Integrated with RK4 steps of at most 1e-3 t_grav outward from pericenter.
std::vector<Vec3> two_body_track(double perturber_mass, double pericenter, double pericenter_speed,
                                 double pericenter_time, const std::vector<double>& times);

}  // namespace tidalcrust
