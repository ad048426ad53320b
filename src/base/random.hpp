#pragma once
// Random numbers whose values are fixed by the C++ standard: std::mt19937_64 bits turned into
// doubles by our own code (std:: distributions differ between standard libraries).
#include <cstdint>
#include <random>

namespace tidalcrust {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1): the top 53 bits of one 64-bit draw.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace tidalcrust
