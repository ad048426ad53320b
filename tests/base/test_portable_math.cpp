#include "base/portable_math.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

namespace tidalcrust {
namespace {

/// Distance in units in the last place between x and the exact 1/sqrt(s), computed
/// in long double (64-bit mantissa: 11 bits beyond a double's, 40 beyond a float's).
template <class T>
double ulps_from_exact(T x, T s) {
  const long double exact = 1.0L / std::sqrt(static_cast<long double>(s));
  const T rounded = static_cast<T>(exact);
  const long double ulp = std::nextafter(rounded, T(INFINITY)) - rounded;
  return static_cast<double>(std::fabs(static_cast<long double>(x) - exact) / ulp);
}

/// Every 1/256 of a binade from 2^-100 to 2^100 (the gravity kernels see s = r^2 + eps^2 from
/// ~1e-8 to ~1e22 with the padding particles), both odd and even exponents (the guess halves
/// the exponent).
template <class T>
double largest_ulps() {
  double worst = 0;
  for (int e = -100; e <= 100; ++e)
    for (int k = 0; k < 256; ++k) {
      const T s = std::ldexp(T(1) + T(k) / T(256), e);
      worst = std::max(worst, ulps_from_exact(portable_math::inverse_sqrt(s), s));
    }
  return worst;
}

TEST(PortableMath, InverseSqrtIsWithinTwoUlpOfTheExactValue) {
  // Measured at its introduction: 1.58 ulp in double, 1.48 in float (a correctly rounded result
  // would be within 0.5).
  EXPECT_LE(largest_ulps<double>(), 2.0);
  EXPECT_LE(largest_ulps<float>(), 2.0);
}

TEST(PortableMath, InverseSqrtGivesTheStoredBits) {
  // Computed by this function at its introduction (integer guess, four Newton steps in double,
  // three in float); any change of the operations or their order changes the portable kernels'
  // bits, which the stored checkpoints' values then also catch (tests/reference).
  EXPECT_EQ(std::bit_cast<std::uint64_t>(portable_math::inverse_sqrt(2.0)), 0x3fe6a09e667f3bccULL);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(portable_math::inverse_sqrt(3.0e-6)), 0x40820acd59eed1eaULL);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(portable_math::inverse_sqrt(2.0f)), 0x3f3504f3u);
}

}  // namespace
}  // namespace tidalcrust
