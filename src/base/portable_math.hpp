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

}  // namespace tidalcrust::portable_math
