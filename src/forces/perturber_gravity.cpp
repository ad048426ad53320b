#include "forces/perturber_gravity.hpp"

#include "forces/gravity.hpp"

namespace tidalcrust {
namespace {

/// The pair (particle i, perturber): d = X - x_i, from the particle to the perturber, and the
/// pair law evaluated for it.
PairForceEnergy pair_with_perturber(double mass_i, const double* x_i, const Perturber& perturber, double eps2,
                                    double d[3]) {
  for (std::size_t k = 0; k < 3; ++k) d[k] = perturber.position[k] - x_i[k];
  return PlummerPairEvaluator{mass_i, perturber.mass, eps2}.force_and_energy(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

}  // namespace

std::array<double, 3> add_perturber_gravity(const std::vector<double>& mass, double softening,
                                            const double* position, const Perturber& perturber,
                                            double* acceleration) {
  const double eps2 = softening * softening;
  std::array<double, 3> back{0, 0, 0};
  for (std::size_t i = 0; i < mass.size(); ++i) {
    double d[3];
    const double f = pair_with_perturber(mass[i], position + 3 * i, perturber, eps2, d).inverse_cube;
    for (std::size_t k = 0; k < 3; ++k) {
      acceleration[3 * i + k] += perturber.mass * f * d[k];
      back[k] -= mass[i] * f * d[k];
    }
  }
  return back;
}

double perturber_energy(const std::vector<double>& mass, double softening, const double* position,
                        const Perturber& perturber) {
  if (!perturber.present) return 0;
  const double eps2 = softening * softening;
  double energy = 0;
  for (std::size_t i = 0; i < mass.size(); ++i) {
    double d[3];
    energy += pair_with_perturber(mass[i], position + 3 * i, perturber, eps2, d).energy;
  }
  return energy;
}

}  // namespace tidalcrust
