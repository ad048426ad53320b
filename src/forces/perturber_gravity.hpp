#pragma once
// The point-mass perturber: it pulls every body particle and every particle pulls it back, each
// pair by the Plummer-softened law of the body's self-gravity (PlummerPairEvaluator; the
// softening is irrelevant at the encounter distances q >= 1.4 R, but it keeps one pair law).
// Units: G = M = R = 1, masses M, lengths R, accelerations G M/R^2, energies G M^2/R.
#include <array>
#include <vector>

#include "model/state.hpp"

namespace tidalcrust {

/// Adds the perturber's pull to the body accelerations [N*3] and returns the perturber's
/// acceleration, sum_i m_i (x_i - X) / (|x_i - X|^2 + eps^2)^(3/2), summed in particle order
/// (one thread: N terms cost ~10 us, less than a fork/join). mass [N] in M, softening eps in R,
/// position [N*3] in R.
std::array<double, 3> add_perturber_gravity(const std::vector<double>& mass, double softening,
                                            const double* position, const Perturber& perturber,
                                            double* acceleration);

/// Potential energy of the perturber in the body's field, sum_i -M2 m_i / sqrt(|x_i - X|^2 + eps^2)
/// in particle order (G M^2/R); 0 without a perturber. Arguments as add_perturber_gravity().
double perturber_energy(const std::vector<double>& mass, double softening, const double* position,
                        const Perturber& perturber);

}  // namespace tidalcrust
