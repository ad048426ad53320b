#pragma once
// Continuum-elasticity results that `tidalcrust validate` compares the spring network with
// (docs/validation.md). Pure functions of the material; units G = M = R = 1 unless a
// parameter says otherwise (moduli in e_g = GM^2/R^4, densities in M/R^3, times in t_grav).
//
//  - Lamb (1882) breathing mode: the fundamental radial vibration of a homogeneous elastic sphere
//    with a free surface, without self-gravity (Love 1927, "A Treatise on the Mathematical
//    Theory of Elasticity", sec. 195; also Aki & Richards 2002, "Quantitative Seismology").
//  - Static degree-n Love numbers of a homogeneous, compressible, self-gravitating elastic
//    sphere: the spheroidal equations y1..y6 of Takeuchi & Saito (1972, eq. 82) with omega = 0,
//    integrated with RK4 from the centre; and the incompressible closed form (Love 1911).
//  - A thin plate under a sinusoidal load (Timoshenko & Woinowsky-Krieger 1959, "Theory of
//    Plates and Shells", Navier's solution) and
//    the flexural rigidity of Bridson's hinges on a triangular lattice.
#include <vector>

namespace tidalcrust {

/// P-wave speed sqrt((lambda + 2 mu)/rho) = sqrt(E/rho) sqrt((1-nu)/((1+nu)(1-2nu))) (paper eq. 16)
/// for Young's modulus E, Poisson ratio nu in (-1, 1/2) and density rho. InputError otherwise.
double p_wave_speed(double youngs_modulus, double poisson_ratio, double density);

/// The smallest positive root x = omega a / V_P of the frequency equation of the radial (n = 0)
/// vibrations of a free homogeneous sphere of radius a (Love sec. 195):
///   tan x / x = 1 / (1 - x^2 (lambda + 2 mu) / (4 mu)),  (lambda + 2 mu)/(4 mu) = (1-nu)/(2(1-2nu)),
/// solved as (1 - c x^2) sin x - x cos x = 0 by a scan and bisection to ~1e-14.
/// nu = 1/4 gives x = 0.8160 pi (Love's table). InputError unless -1 < nu < 1/2.
double lamb_breathing_root(double poisson_ratio);

/// Period 2 pi a / (x V_P) of the fundamental breathing mode (t_grav for a in R, E in e_g, rho in
/// M/R^3), x = lamb_breathing_root(nu); self-gravity is left out (docs/validation.md says how much
/// it changes).
double lamb_breathing_period(double youngs_modulus, double poisson_ratio, double density, double radius);

/// Period of the same mode of a self-gravitating homogeneous sphere (G = 1). For n = 0 the
/// potential terms of Takeuchi & Saito's equations cancel (y5 = r y6 = 4 pi G rho int_0^r y1), and
/// what remains of gravity is the constant -4 rho g / r = -(16 pi / 3) G rho^2 in the radial
/// equation: the eigenfunction is Lamb's and omega^2 = omega_Lamb^2 - (16 pi / 3) G rho. InputError
/// when that is <= 0 (the sphere is too soft to hold itself up).
double self_gravitating_breathing_period(double youngs_modulus, double poisson_ratio, double density, double radius);

/// Static Love numbers of one degree n: h (radial displacement u_r = h W / g at the surface),
/// k (induced potential k W at the surface) and l (Shida: tangential displacement l grad W / g).
struct LoveNumbers {
  double h = 0;
  double k = 0;
  double l = 0;
};

/// Static Love numbers of degree n >= 2 of a homogeneous, compressible, self-gravitating elastic
/// sphere: Young's modulus E (e_g), Poisson ratio nu (-1 < nu < 1/2), density rho and radius a,
/// with G = 1. The three regular solutions of Takeuchi & Saito's y1..y6 (their eq. 82 at
/// omega = 0) start at r = 0.005 a from the no-gravity polynomial solutions and are
/// integrated with `steps` RK4 steps to the surface, where y2 = y4 = 0 and y6 = (2n+1)/a (a
/// unit external potential W at r = a) fix their combination; h = g y1, k = y5 - 1, l = g y3.
/// As nu -> 1/2 it tends to incompressible_love_h2 (tests/physics/test_continuum_elasticity.cpp).
LoveNumbers homogeneous_sphere_love_numbers(int degree, double youngs_modulus, double poisson_ratio, double density,
                                            double radius, int steps = 20000);

/// One spherical layer of a radially layered elastic sphere: from the previous layer's outer
/// radius (0 for the first) to `outer_radius` (R), with Young's modulus (e_g), Poisson ratio and
/// density (M/R^3).
struct ElasticLayer {
  double outer_radius = 0;
  double youngs_modulus = 0;
  double poisson_ratio = 0.25;
  double density = 0;
};

/// The degree-0 compliance of a sphere of welded homogeneous layers (innermost first): under a
/// uniform pressure p on its surface a the surface moves by u(a) = -c p a; returns c (1/e_g). No
/// gravity. In each layer u = A r + B / r^2 and sigma_rr = 3 K A - 4 mu B / r^3 (Love 1927 sec. 98),
/// with B = 0 in the first; u and sigma_rr are continuous at each boundary. One layer gives
/// c = 1 / (3 K); a core of volume fraction f in a mantle gives Hashin's composite sphere. InputError
/// for no layer, radii that do not increase, or a modulus or Poisson ratio out of range.
double layered_sphere_compression(const std::vector<ElasticLayer>& layers);

/// Static Love numbers of degree n >= 2 of a self-gravitating sphere of welded homogeneous layers
/// (innermost first): the same TS72 equations, with each layer's lambda, mu, rho and the gravity
/// g(r) = m(r)/r^2 of the mass inside r, integrated through the layers with y1..y6 continuous at
/// their boundaries; the surface is the last layer's outer radius. `steps` RK4 steps over the
/// radius, shared by thickness (at least 100 per layer). One layer gives
/// homogeneous_sphere_love_numbers exactly. `self_gravity` false drops the body's own gravity
/// (g(r) and the perturbation of its potential: k = 0) but keeps the external potential's body force
/// and normalises h, l by the surface gravity m/a^2 as before (nongravitating_sphere_love_numbers
/// is its closed form). InputError for no layer, radii that do not increase, or a layer value out
/// of range.
LoveNumbers layered_sphere_love_numbers(int degree, const std::vector<ElasticLayer>& layers, int steps = 20000,
                                        bool self_gravity = true);

/// Angular frequency omega (1/t_grav, G = 1) of the fundamental spheroidal free oscillation of
/// degree n >= 2 (for n = 2: 0S2, the football mode) of the layered sphere: TS72 eq. 82 with the
/// inertia -omega^2 rho u, regular at the centre, free surface (y2 = y4 = 0) and no external
/// potential (y6 = 0); the lowest omega above 0.05 V_S / a (V_S the largest sqrt(mu/rho) of the
/// layers) where the 3x3 boundary determinant changes sign, by a scan in steps of 0.02 V_S / a and
/// bisection. `self_gravity` false: Lamb's (1882) elastic sphere without gravity, for which nu = 1/4
/// gives omega a / V_S = 2.640 (tests/physics/test_continuum_elasticity.cpp). InputError as
/// layered_sphere_love_numbers, or when no root lies below 30 V_S / a.
double spheroidal_fundamental_frequency(int degree, const std::vector<ElasticLayer>& layers, bool self_gravity,
                                        int steps = 1000);

/// Degree-2 Love numbers h2, l2 of a homogeneous compressible elastic sphere without self-gravity
/// under an external potential W = A r^2 P2 (body force rho grad W), k2 = 0; h, l normalised by
/// g = (4 pi / 3) rho a (G = 1). Closed form (derived in docs/validation.md from Love's (1927,
/// Treatise sec. 174-175) regular solutions grad phi, r^2 grad phi + beta x phi of the Navier
/// equation):
///   h2 = (rho g a / mu) (5 lambda + 4 mu) / (19 lambda + 14 mu),
///   l2 = (rho g a / mu) (3 lambda + 2 mu) / (2 (19 lambda + 14 mu)),
/// so l2 / h2 = 5/18 at nu = 1/4; lambda -> infinity gives Love's incompressible 5/19 and 3/38.
LoveNumbers nongravitating_sphere_love_numbers(double youngs_modulus, double poisson_ratio, double density,
                                               double radius);

/// h2 of a homogeneous incompressible self-gravitating sphere (Love 1911; e.g. Murray & Dermott
/// 1999, "Solar System Dynamics", with k2 = (3/5) h2): h2 = (5/2) / (1 + 19 mu / (2 rho g a)), G = 1.
double incompressible_love_h2(double shear_modulus, double density, double radius);

/// l2 of the same sphere: l2 = (3/4) / (1 + 19 mu / (2 rho g a)) = (3/10) h2 (Love 1911).
double incompressible_love_l2(double shear_modulus, double density, double radius);

/// Amplitude w0 (R) of the deflection w0 sin(k x) of a thin plate of flexural rigidity D
/// (G M^2/R) under the load q0 sin(k x) per unit area (G M^2/R^3), from D d^4w/dx^4 = q
/// (Timoshenko & Woinowsky-Krieger 1959, Navier's solution; also the simply supported strip of
/// length pi/k):
/// w0 = q0 / (D k^4).
double plate_sinusoidal_deflection(double load_amplitude, double wavenumber, double flexural_rigidity);


}  // namespace tidalcrust
