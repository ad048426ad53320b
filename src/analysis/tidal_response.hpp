#pragma once
// The body's response to a static degree-2 tide and its free degree-2 oscillation after the tide
// is released (`tidalcrust validate --measure tide,ringdown`, docs/validation.md): Love numbers
// h2 and l2 fitted from the shell's displacements, every crust spring's strain against the
// continuum surface strain of an elastic sphere, and the period of 0S2. Units G = M = R = 1;
// strains are given per unit tidal strength eps (W = eps r^2 P2, eps in G M / R^3).
#include <cstdint>
#include <vector>

#include "analysis/elastic_validation.hpp"
#include "base/vec3.hpp"
#include "model/body.hpp"
#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "model/state.hpp"
#include "physics/continuum_elasticity.hpp"

namespace tidalcrust {

/// h2 and l2 of a displacement field of the shell nodes under W = eps r^2 P2(cos theta) about the
/// z axis. With u the displacement (displaced - rest, each about its own centre of mass) of a node
/// at rest position x (r = |x|, theta from +z) and g = 1/r^2:
///   u_r = a0 + h2 eps r^4 P2(cos theta),   u_theta = l2 eps r^3 dP2/dtheta
/// (u = h2 W/g r_hat + l2 grad W / g); a0 (a uniform radial shift) and h2 by least squares on
/// u_r, l2 by least squares on u_theta. Exact for a field of that form.
struct DegreeTwoFit {
  double h2 = 0;
  double l2 = 0;
  double uniform = 0;       ///< a0, R
  double mean_radius = 0;   ///< of the fitted nodes at rest, R
  double rms_azimuthal = 0; ///< rms of u_phi over eps, R (0 for an axisymmetric response)
};
/// The fit over the shell nodes; displacement = (plus - minus)/2 when `minus` is given (the
/// relaxed state's own offsets cancel), else plus - rest. InputError without shell nodes.
DegreeTwoFit fit_degree_two_displacement(const Body& body, const State& rest, const State& plus, const State* minus,
                                         double eps);

/// The continuum surface strain (per unit eps) at angle gamma from the tidal axis of a sphere with
/// Love numbers h, l, at r = 1 and g = 1 (u_r = h W/g, u_t = l grad W/g):
///   eps_psipsi = h P2(cos gamma) + l d^2P2/dgamma^2 = h P2 - 3 l cos 2gamma   (meridional),
///   eps_lamlam = h P2 + l cot(gamma) dP2/dgamma      = h P2 - 3 l cos^2 gamma (azimuthal).
struct SurfaceStrain {
  double meridional = 0;
  double azimuthal = 0;
};
SurfaceStrain continuum_surface_strain(double h2, double l2, double gamma);

/// One band of angle from the tidal axis (the nearer of the two sub-perturber points).
struct TidalStrainBin {
  double gamma_low = 0, gamma_high = 0;  ///< degrees
  std::int64_t springs = 0;
  /// The fit strain = A cos^2(alpha) + B sin^2(alpha) over the band's crust springs (alpha the
  /// angle of a spring from the meridian): A = eps_psipsi, B = eps_lamlam, per unit eps.
  double measured_meridional = 0, measured_azimuthal = 0;
  double theory_meridional = 0, theory_azimuthal = 0;  ///< the same fit of the springs' continuum strains
};

/// The spring-by-spring ratio measured / continuum strain over the springs whose continuum strain
/// is at least `floor` x rms(continuum) (the ratio of a near-zero prediction says nothing): its
/// median and its scatter, half the 16th-84th percentile range (a normal distribution's sigma),
/// percentiles interpolated linearly between ranks. InputError when no spring qualifies or the
/// lengths differ.
struct StrainRatioSpread {
  double median = 0;
  double scatter = 0;
  std::int64_t springs = 0;  ///< the springs counted
};
StrainRatioSpread strain_ratio_spread(const std::vector<double>& measured, const std::vector<double>& theory,
                                      double floor = 0.5);

/// What measure_tide found.
struct TideResult {
  double tidal_strength = 0;  ///< eps, G M / R^3
  double drag = 0;            ///< 1/t_grav
  double duration = 0;        ///< t_grav
  DegreeTwoFit fit;           ///< at the end
  DegreeTwoFit early_fit;     ///< at 2/3 of the duration (how far it has settled)
  LoveNumbers theory;         ///< the continuum the strains are compared with (h, l)
  std::int64_t springs = 0;   ///< intact crust springs compared
  // Every crust spring's strain change (per unit eps) against the chord strain the continuum
  // surface displacement (theory.h, theory.l) gives it:
  double correlation = 0;     ///< Pearson
  double slope = 0;           ///< least squares measured = slope x theory
  double rms_residual = 0;    ///< rms(measured - theory) / rms(theory)
  /// The same against the strain of the body's own fitted h2, l2 (is the crust consistent with
  /// the displacements it was fitted from?).
  double own_correlation = 0, own_slope = 0;
  StrainRatioSpread ratio;    ///< measured / continuum, spring by spring (strain_ratio_spread)
  /// Meridional tension near the equator of the tide (gamma 75-90 deg): the A of the band fit,
  /// measured and theory, per unit eps.
  double peak_tension = 0, theory_peak_tension = 0;
  /// Mean strain change of the springs within 15 deg of the axis, measured and theory, per unit eps.
  double subsatellite_strain = 0, theory_subsatellite_strain = 0;
  std::vector<TidalStrainBin> bins;  ///< 15 bands of 6 deg
  std::vector<double> spring_gamma;  ///< per compared spring: degrees from the axis
  std::vector<double> spring_strain; ///< measured, per unit eps
  std::vector<double> spring_theory; ///< continuum, per unit eps
  State plus, minus;                 ///< the settled states under +eps and -eps (ring-down starts here)
};

/// The static tide: W = eps r^2 P2(cos theta) about the centre of mass (+z the tidal axis),
/// applied with the drag of measure_love_h2 (rate `drag`, for `duration`; 0 chooses omega_L and
/// max(3, 30/omega_L) from Lamb's breathing frequency of `material`) once with +eps and once with
/// -eps; eps gives the continuum `theory` a surface displacement `surface_displacement`. Fits h2,
/// l2 (fit_degree_two_displacement) and compares every intact crust spring's strain change
/// (L+ - L-) / (2 L_rest) / eps with the continuum's chord strain ((u(b) - u(a)).(x_b - x_a)/L^2,
/// u the surface field of theory.h, theory.l at the rest positions).
/// `progress`: a progress line (io/progress.hpp) on stderr while it runs.
TideResult measure_tide(const Checkpoint& relaxed, const Config& config, const BodyMaterial& material,
                        const LoveNumbers& theory, double surface_displacement = 1e-3, double drag = 0,
                        double duration = 0, bool progress = false);

/// The free degree-2 oscillation after the tide is switched off: the settled tidal states of
/// measure_tide are integrated with Leapfrog without tide, drag or spring damping for `duration`
/// t_grav, and the signal is the P2 coefficient of the shell's radial displacement,
/// (plus - minus)/2 against the relaxed state. Its period: the best least-squares sinusoid between
/// half and twice `expected_omega`.
struct RingdownResult {
  double period = 0;           ///< t_grav
  double amplitude = 0;        ///< of the fitted sinusoid, R
  double initial = 0;          ///< the signal at release, R
  std::vector<double> time;    ///< t_grav since the release
  std::vector<double> signal;  ///< R
};
RingdownResult measure_ringdown(const Checkpoint& relaxed, const Config& config, const TideResult& tide,
                                double expected_omega, double duration, bool progress = false);

}  // namespace tidalcrust
