#pragma once
// The gravity kernel probe: a fixed particle set and the XXH3-128 of what DirectGravity and
// self_gravity_energy, and TreeGravity (accelerations and potential energy), compute for it,
// shared by tools/kernel_probe.cpp (built without AVX-512, target
// tidalcrust_kernel_probe_generic) and tests/forces/test_gravity_kernels.cpp (the native build),
// which compare the two. Depends on forces/gravity.cpp, forces/tree_gravity.cpp, SLEEF,
// support/random_ball.hpp and the standard library only.
#include <xxhash.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "base/random.hpp"
#include "forces/gravity.hpp"
#include "forces/tree_gravity.hpp"
#include "support/random_ball.hpp"

namespace tidalcrust::test_support {

/// 389 particles (not a multiple of the 8 lanes: padding is exercised) with unequal masses in a
/// cube of side 2 R, softening 0.01 R, from seed 2024.
struct ProbeCloud {
  std::vector<double> mass, position;
  double softening = 0.01;
};

inline ProbeCloud probe_cloud() {
  constexpr std::size_t n = 389;
  Random random(2024);
  ProbeCloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.mass.push_back(random.uniform(0.5, 1.5) / static_cast<double>(n));
    for (int k = 0; k < 3; ++k) c.position.push_back(random.uniform(-1, 1));
  }
  return c;
}

/// "xxh3:" + 32 hex digits of raw IEEE bytes: equal text means bitwise equal results.
inline std::string hash_text(const std::vector<double>& bits) {
  const XXH128_hash_t h = XXH3_128bits(bits.data(), bits.size() * sizeof(double));
  char text[64];
  std::snprintf(text, sizeof text, "xxh3:%016llx%016llx", static_cast<unsigned long long>(h.high64),
                static_cast<unsigned long long>(h.low64));
  return text;
}

/// The hash of the accelerations [N*3] by DirectGravity with `kernel` followed by the
/// self-gravity energy.
inline std::string probe_hash(GravityKernel kernel) {
  const ProbeCloud c = probe_cloud();
  DirectGravity gravity(c.mass, c.softening, kernel);
  std::vector<double> bits(c.position.size());
  gravity.accelerations(c.position.data(), bits.data());
  bits.push_back(self_gravity_energy(c.mass, c.softening, c.position.data()));
  return hash_text(bits);
}

/// 6,000 particles (enough for a tree of many levels, the moment tasks, and groups not filling
/// the last vector) of the same law as probe_cloud(), from seed 2025, in a ball of radius 1 R.
inline ProbeCloud tree_probe_cloud() {
  ProbeCloud c;
  fill_random_ball(6001, 2025, c.mass, c.position);
  c.softening = 0.002;
  return c;
}

/// The hash of TreeGravity's accelerations [N*3] (force_error 1e-4) by `kernel` followed by its
/// potential energy and opening angle.
inline std::string tree_probe_hash(GravityKernel kernel) {
  const ProbeCloud c = tree_probe_cloud();
  TreeGravity tree(c.mass, c.softening, 1e-4, kernel);
  std::vector<double> bits(c.position.size());
  tree.accelerations(c.position.data(), bits.data());
  bits.push_back(tree.potential_energy(c.position.data()));
  bits.push_back(tree.opening_angle());
  return hash_text(bits);
}

}  // namespace tidalcrust::test_support
