#pragma once
// Transcendental functions whose bits do not depend on the CPU, for the portable mode
// (`[gravity] kernel = "portable"`, docs/determinism.md). glibc's libm picks variants of sin,
// cos, atan2, pow, exp, ... by CPU at load time (builds with FMA for CPUs that have it), and
// their last bits can differ; SLEEF's scalar functions (Debian's libsleef3, `Sleef_sin_u10`
// etc., error bound 1 ulp) are plain code with no CPU dispatch (no FMA or AVX instructions in
// Debian's build): the same bits on every x86-64 CPU. Each function takes `portable` and calls
// the standard library otherwise, so the fast mode keeps its bits.
#include <sleef.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>

namespace tidalcrust::portable_math {

inline double sin(double x, bool portable) { return portable ? Sleef_sin_u10(x) : std::sin(x); }
inline double cos(double x, bool portable) { return portable ? Sleef_cos_u10(x) : std::cos(x); }
inline double pow(double x, double y, bool portable) { return portable ? Sleef_pow_u10(x, y) : std::pow(x, y); }
inline double tan(double x, bool portable) { return portable ? Sleef_tan_u10(x) : std::tan(x); }
inline double atan(double x, bool portable) { return portable ? Sleef_atan_u10(x) : std::atan(x); }
inline double atan2(double y, double x, bool portable) { return portable ? Sleef_atan2_u10(y, x) : std::atan2(y, x); }
inline double sinh(double x, bool portable) { return portable ? Sleef_sinh_u10(x) : std::sinh(x); }
inline double cbrt(double x, bool portable) { return portable ? Sleef_cbrt_u10(x) : std::cbrt(x); }

/// 1/sqrt(s) for a normal s > 0 (float or double) from integer and IEEE + and * operations
/// alone: the exponent-halving integer guess (relative error < 3.5e-2; Lomont 2003, "Fast
/// inverse square root") and Newton steps y <- y (3/2 - (s/2) y^2), each squaring the error:
/// three in float, four in double (within 1.6 ulp of the exact value in both; test
/// PortableMath.InverseSqrtIsWithinTwoUlpOfTheExactValue). The same operations in
/// the same order on every CPU, whatever the compiler vectorises them with (-ffp-contract=off),
/// and cheaper than a correctly rounded sqrt and division, which share one slow divider unit:
/// the portable gravity kernels (direct sum and tree) compute their inverse cubes with it.
template <class T>
[[gnu::always_inline]] inline T inverse_sqrt(T s) {
  static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>);
  using Bits = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  constexpr Bits magic = sizeof(T) == 4 ? Bits(0x5f375a86u) : Bits(0x5fe6eb50c7b537a9ull);
  constexpr int steps = sizeof(T) == 4 ? 3 : 4;
  T y = std::bit_cast<T>(Bits(magic - (std::bit_cast<Bits>(s) >> 1)));
  for (int k = 0; k < steps; ++k) y = y * (T(1.5) - (T(0.5) * s) * (y * y));
  return y;
}

}  // namespace tidalcrust::portable_math
