#pragma once
// The gravity kernel probe: a fixed particle set and the XXH3-128 of what DirectGravity and
// self_gravity_energy compute for it, shared by tools/kernel_probe.cpp (built without AVX-512,
// target tidalcrust_kernel_probe_generic) and tests/forces/test_gravity_kernels.cpp (the native
// build), which compare the two. Depends on forces/gravity.cpp and the standard library only.
#include <xxhash.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "base/random.hpp"
#include "forces/gravity.hpp"

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

/// "xxh3:" + 32 hex digits of the accelerations [N*3] by `kernel` followed by the self-gravity
/// energy, as raw IEEE bytes: equal text means bitwise equal results.
inline std::string probe_hash(GravityKernel kernel) {
  const ProbeCloud c = probe_cloud();
  DirectGravity gravity(c.mass, c.softening, kernel);
  std::vector<double> bits(c.position.size());
  gravity.accelerations(c.position.data(), bits.data());
  bits.push_back(self_gravity_energy(c.mass, c.softening, c.position.data()));
  const XXH128_hash_t h = XXH3_128bits(bits.data(), bits.size() * sizeof(double));
  char text[64];
  std::snprintf(text, sizeof text, "xxh3:%016llx%016llx", static_cast<unsigned long long>(h.high64),
                static_cast<unsigned long long>(h.low64));
  return text;
}

}  // namespace tidalcrust::test_support
