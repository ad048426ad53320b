#pragma once
// The body's centre of mass and its velocity: the origin of the fracture-map frame, of the blow-up
// check and of the shell radius. One summation, in particle index order, so that every caller
// gets the same bits for the same state.
#include "base/vec3.hpp"
#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// sum_i m_i a_i / sum_i m_i over the body particles (perturber excluded), summed in index
/// order; `flat` [N*3] holds a_i (positions in R, velocities in sqrt(GM/R), ...). Zero for a body
/// without mass.
Vec3 mass_weighted_mean(const Body& body, const double* flat);

/// Centre of mass of the body particles, R.
Vec3 body_center_of_mass(const Body& body, const State& state);

/// Velocity of the body's centre of mass, sqrt(GM/R).
Vec3 body_center_of_mass_velocity(const Body& body, const State& state);

}  // namespace tidalcrust
