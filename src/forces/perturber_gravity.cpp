#include "forces/perturber_gravity.hpp"

#include "forces/gravity.hpp"

namespace tidalcrust {

std::array<double, 3> add_perturber_gravity(const std::vector<double>& mass, double softening,
                                            const double* position, const Perturber& perturber,
                                            double* acceleration) {
  const double eps2 = softening * softening;
  std::array<double, 3> back{0, 0, 0};
  for (std::size_t i = 0; i < mass.size(); ++i) {
    double d[3];  // from particle i to the perturber
    for (std::size_t k = 0; k < 3; ++k) d[k] = perturber.position[k] - position[3 * i + k];
    const double f = plummer_inverse_cube(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], eps2);
    for (std::size_t k = 0; k < 3; ++k) {
      acceleration[3 * i + k] += perturber.mass * f * d[k];
      back[k] -= mass[i] * f * d[k];
    }
  }
  return back;
}

}  // namespace tidalcrust
