#pragma once
// Totals that the dynamics must conserve: body + perturber, about the origin.
#include <array>

#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// Gravitational binding energy of a uniform sphere of mass M and radius R, 3/5 G M^2/R: the
/// scale against which the energy budget's error is quoted.
inline constexpr double uniform_sphere_binding_energy = 0.6;

struct Conservation {
  std::array<double, 3> momentum{};          ///< M sqrt(GM/R)
  std::array<double, 3> angular_momentum{};  ///< about the origin, M R sqrt(GM/R)
  double kinetic_energy = 0;                 ///< G M^2 / R
};

/// Sums over all particles in index order, then the perturber (if present).
Conservation measure_conservation(const Body& body, const State& state);

/// Kinetic energy of the body particles relative to their centre-of-mass velocity
/// (G M^2 / R): the "internal" motion a relaxed body should have lost.
double internal_kinetic_energy(const Body& body, const State& state);

}  // namespace tidalcrust
