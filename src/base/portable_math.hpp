#pragma once
// Transcendental functions whose bits do not depend on the CPU, for the portable mode
// (`[gravity] kernel = "portable"`, docs/determinism.md). glibc's libm picks variants of sin,
// cos, atan2, pow, exp, ... by CPU at load time (builds with FMA for CPUs that have it), and
// their last bits can differ; SLEEF's scalar functions (Debian's libsleef3, `Sleef_sin_u10`
// etc., error bound 1 ulp) are plain code with no CPU dispatch (no FMA or AVX instructions in
// Debian's build): the same bits on every x86-64 CPU. Each function takes `portable` and calls
// the standard library otherwise, so the fast mode keeps its bits.
#include <sleef.h>

#include <cmath>

namespace tidalcrust::portable_math {

inline double sin(double x, bool portable) { return portable ? Sleef_sin_u10(x) : std::sin(x); }
inline double cos(double x, bool portable) { return portable ? Sleef_cos_u10(x) : std::cos(x); }
inline double pow(double x, double y, bool portable) { return portable ? Sleef_pow_u10(x, y) : std::pow(x, y); }
inline double tan(double x, bool portable) { return portable ? Sleef_tan_u10(x) : std::tan(x); }
inline double atan(double x, bool portable) { return portable ? Sleef_atan_u10(x) : std::atan(x); }
inline double atan2(double y, double x, bool portable) { return portable ? Sleef_atan2_u10(y, x) : std::atan2(y, x); }
inline double sinh(double x, bool portable) { return portable ? Sleef_sinh_u10(x) : std::sinh(x); }
inline double cbrt(double x, bool portable) { return portable ? Sleef_cbrt_u10(x) : std::cbrt(x); }

}  // namespace tidalcrust::portable_math
