#pragma once
// n particles uniform in the unit ball with unequal masses (0.5-1.5)/n, from one seed: the clouds
// of the tree code's tests and of the gravity kernel probe (tests/support/kernel_probe.hpp).
// Depends on base/random.hpp and the standard library only.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "base/random.hpp"

namespace tidalcrust::test_support {

inline void fill_random_ball(std::size_t n, std::uint64_t seed, std::vector<double>& mass, std::vector<double>& position) {
  Random random(seed);
  while (mass.size() < n) {
    const double p[3] = {random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)};
    if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] > 1) continue;
    mass.push_back(random.uniform(0.5, 1.5) / static_cast<double>(n));
    position.insert(position.end(), p, p + 3);
  }
}

}  // namespace tidalcrust::test_support
