#pragma once
// The measurements of `tidalcrust validate` (docs/validation.md): the relaxed spring network
// against continuum elasticity (physics/continuum_elasticity.hpp). Each integrates copies of the
// relaxed state with the project's force field; the checkpoint itself is never changed.
// Units G = M = R = 1 (times t_grav, moduli e_g, rigidities G M^2/R).
#include <cstdint>
#include <functional>
#include <vector>

#include "base/vec3.hpp"
#include "forces/force_field.hpp"
#include "model/checkpoint.hpp"
#include "model/config.hpp"
#include "physics/continuum_elasticity.hpp"
#include "physics/network_moduli.hpp"

namespace tidalcrust {

/// The continuum material of a relaxed body, measured on its network.
struct BodyMaterial {
  /// E_I of eq. 15 from the relaxed state's interior springs, e_g; for a welded body
  /// (cross.coupling = "welded") over the springs deeper than d_I only (inside r_I - d_I)
  double youngs_modulus = 0;
  double poisson_ratio = 0.25; ///< of a random isotropic spring network (Kot et al. 2015)
  double density = 0;          ///< mean density 3/(4 pi radius^3), M/R^3
  double radius = 0;           ///< R = 1 with a crust; without one the outermost node's distance from the centre of mass
  double p_wave_speed = 0;     ///< V_IP of eq. 16, sqrt(GM/R)
  double shell_spacing = 0;    ///< L_S, mean shell rest length, R (0 without a shell)
  double shell_spring_constant = 0;  ///< k_S, mean shell stiffness, G M^2/R^3
  double hinge_stiffness = 0;  ///< mean k_e, G M^2/R^2 (0 without hinges)
};

BodyMaterial body_material(const Checkpoint& relaxed, const Config& config);

/// The relaxed interior network's own static moduli (physics/network_moduli.hpp), and the body
/// material they give. The interior springs and nodes of the relaxed state, about the centre of
/// mass; d the longest interior spring and r_out the outermost interior node: the nodes beyond
/// hold_radius = r_out - d/2 stay at the affine positions, the stress is taken over the sphere of
/// measure_radius = hold_radius - d/2. Measured twice:
///  - `geometric`: the network's geometry alone, every spring k = 1 at its current length (no
///    pre-stress): how far the random geometry relaxes off the affine deformation;
///  - `network`: the relaxed springs as they are (strengthened toward the centre, pre-stressed):
///    under the held boundary this also contains the continuum effect of the stiffness growing
///    inward (a stiff centre inside a softer shell strains less than the boundary), so it is
///    reported, not used.
/// The body's moduli are eq. 15's times the geometric non-affine factors K_relaxed / K_affine and
/// G_relaxed / G_affine (K_I = 2 E_I / 3, G_I = 2 E_I / 5 at nu = 1/4). InputError when the
/// interior is too small for a held layer and a measured sphere (measure_radius <= 0).
struct InteriorModuli {
  NetworkModuli geometric;   ///< uniform springs at their current lengths
  NetworkModuli network;     ///< the relaxed springs with their pre-stress
  double hold_radius = 0;    ///< R
  double measure_radius = 0; ///< R
  double bulk_factor = 0;    ///< K_relaxed / K_affine of `geometric`
  double shear_factor = 0;   ///< G_relaxed / G_affine of `geometric`
  double youngs_factor = 0;  ///< E of `material` / E_I
  BodyMaterial material;     ///< the body's material with E, nu, V_P from the measured moduli
};
InteriorModuli measure_interior_moduli(const Checkpoint& relaxed, const BodyMaterial& eq15_material);

/// Continuum predictions for a body material (theory only; the measurements stay as they are):
/// Lamb's breathing period with and without self-gravity, the static h2, the P-wave time over
/// `path_length` (R).
struct ContinuumPrediction {
  double breathing_period = 0;                  ///< Lamb (1882), t_grav
  double self_gravitating_breathing_period = 0; ///< t_grav
  double h2 = 0;                                ///< homogeneous_sphere_love_numbers(2, ...).h
  double p_wave_time = 0;                       ///< path_length / V_P, t_grav
};
ContinuumPrediction continuum_prediction(const BodyMaterial& material, double path_length);

/// (a) The fundamental radial mode: positions scaled about the centre of mass by 1 + amplitude,
/// integrated with Leapfrog (no damping, no perturber) beside an unscaled copy; the signal is the
/// difference of the two mean particle radii, its period the frequency of the best least-squares
/// sinusoid. Theory: lamb_breathing_period with the body's E, nu = 1/4, rho, and R = 1.
struct BreathingResult {
  double period = 0;         ///< measured, t_grav
  double lamb_period = 0;    ///< Lamb (1882), t_grav
  double self_gravitating_period = 0;  ///< the same sphere with self-gravity, t_grav
  double ratio = 0;          ///< period / lamb_period
  double amplitude = 0;      ///< fitted amplitude of the mean-radius oscillation, R
  std::vector<double> time;  ///< t_grav since the start
  std::vector<double> signal;///< mean radius difference, R
};
BreathingResult measure_breathing(const Checkpoint& relaxed, const Config& config, const BodyMaterial& material,
                                  double amplitude = 1e-3, double periods = 5);

/// (b) The degree-2 Love number h2: the static tidal potential W = eps r^2 P2(cos theta) (force
/// +grad W per unit mass, about the centre of mass) applied for `duration` t_grav with a drag
/// -`drag` v on every particle, once with +eps and once with -eps; h2 = u_r / (W/g) at the shell
/// from the least-squares fit u_r = a0 + a2 P2(cos theta) of half the shell nodes' radial
/// displacement difference, W/g = eps r_s^4 at the mean shell radius r_s. eps is chosen so that
/// theory's surface displacement is `surface_displacement`. Theory: homogeneous_sphere_love_numbers.
/// The drag, not the springs' damping, settles the body: a spring dashpot gamma mu acts on the
/// velocity difference of neighbours, about (L / wavelength)^2 of a long mode's velocity, so its
/// hold on the degree-2 deformation weakens 4x per shell level (level 6 did not settle in 3 t_grav
/// at gamma = 50); a drag damps every mode at the same rate at any resolution and leaves the static
/// equilibrium unchanged. drag = 0 and duration = 0 choose them from the body's Lamb frequency
/// omega_L: drag = omega_L (the degree-2 mode, near 0.6 omega_L, is then close to critically damped
/// and every faster mode decays as exp(-omega_L t / 2)), T = max(3, 30 / omega_L) t_grav.
struct LoveResult {
  double h2 = 0;             ///< measured at the end
  double h2_early = 0;       ///< measured at 2/3 of the duration (how far it has settled)
  double theory_h2 = 0;      ///< compressible self-gravitating homogeneous sphere (TS72 equations)
  double incompressible_h2 = 0;  ///< Love's closed form for the same shear modulus (for reference)
  double ratio = 0;          ///< h2 / theory_h2
  double tidal_strength = 0; ///< eps, G M / R^3
  double shell_radius = 0;   ///< r_s, R
  double drag = 0;           ///< drag rate used, 1/t_grav
  double duration = 0;       ///< t_grav
};
LoveResult measure_love_h2(const Checkpoint& relaxed, const Config& config, const BodyMaterial& material,
                           double surface_displacement = 1e-3, double drag = 0, double duration = 0);

/// Steps of dt that cover `duration` (t_grav): ceil(duration / dt), the one conversion of the
/// validation runs (measure_love_h2, measure_tide, the ring-downs).
std::int64_t step_count(double duration, double dt);

/// Relaxes `state` under the static tidal acceleration eps (-x, -y, 2z) (the force +grad W of
/// W = eps r^2 P2(cos theta) about `center`, per unit mass) with a drag -drag v on every particle
/// (v at the start of the step, as the spring damping takes it): the leapfrog of Leapfrog::step
/// (drift, kick with the forces at the half-step positions plus the field and the drag, drift),
/// for `steps` steps of clock.dt. Used by measure_love_h2 and measure_tide. `after_step`
/// (optional) is called after every step with the number of steps done (progress lines).
void relax_in_tidal_field(ForceField& forces, State& state, const Vec3& center, double eps, double drag,
                          const StepClock& clock, std::int64_t steps,
                          const std::function<void(std::int64_t)>& after_step = {});

/// Least-squares fit of s(t) = a cos(omega t) + b sin(omega t) + c: its amplitude sqrt(a^2 + b^2).
double sinusoid_amplitude(const std::vector<double>& t, const std::vector<double>& s, double omega);

/// The angular frequency in [low, high] of the best least-squares sinusoid (a scan of 600
/// frequencies, then golden-section refinement around the best).
double dominant_frequency(const std::vector<double>& t, const std::vector<double>& s, double low, double high);

/// (c) Flexural rigidity of the crust's lattice: a flat periodic equilateral triangular lattice
/// (spacing L_S, one spring k_S per edge and one hinge k_e per edge, the project's evaluators),
/// loaded by q0 sin(k x) per unit area with k = 2 pi / (16 L_S), relaxed to static equilibrium;
/// D = q0 / (w0 k^4) from the fitted deflection amplitude w0 (plate_sinusoidal_deflection).
struct FlexureResult {
  double rigidity = 0;          ///< measured D, G M^2/R
  double paper_rigidity = 0;    ///< eq. 23: D_F = k_e L_S / 2
  double lattice_rigidity = 0;  ///< hinge_lattice_flexural_rigidity: k_e / 4
  double early_rigidity = 0;    ///< D measured at 2/3 of the relaxation (how far it has settled)
  double ratio = 0;             ///< rigidity / paper_rigidity
  double lattice_ratio = 0;     ///< rigidity / lattice_rigidity
  double deflection = 0;        ///< w0, R
  double theory_deflection = 0; ///< q0 / (D_F k^4), R
  int nodes = 0;
};
FlexureResult measure_plate_flexure(double hinge_stiffness, double spacing, double spring_constant);

/// The body as radial layers for continuum theory (about `center`): `layers` layers of equal
/// thickness from the centre to the outermost interior node r_out, each with eq. 15 on the
/// interior springs whose midpoints lie in it, nu = 1/4, and the interior mass in it as density;
/// with `with_crust` and a shell, one more layer from r_out to R = 1 holding the crust: eq. 15 on
/// the cross springs over its volume, and the shell's mass. Innermost first. InputError for a
/// layer without springs or mass.
std::vector<ElasticLayer> body_layers(const Checkpoint& relaxed, const Vec3& center, int layers, bool with_crust);

/// The part of a body with an ocean (Body::liquid) above its solid interior, as two layers for
/// continuum theory: the liquid from the outermost interior node r_out to 1 - h, and the crust from
/// 1 - h to R = 1 (E = E_2D / h with E_2D = (2/sqrt 3) k_S of the shell springs, nu = 1/3 of a
/// triangular spring lattice). The liquid's bulk modulus is K of the layer plus its springs'; its
/// shear modulus that of its springs (eq. 15 over the layer's volume, nu = 1/4: the small static
/// shear the damping springs keep, ocean_layer.hpp) or, with `fluid`, K * fluid_shear_fraction
/// (the mu -> 0 limit of TS72's solid equations; docs/ocean.md). Densities: the particles' masses
/// (the liquid's lumped onto the crust and floor nodes included where they sit) over each layer's
/// volume. h: the crust thickness (R). InputError without a liquid layer or a shell.
std::vector<ElasticLayer> ocean_layers(const Checkpoint& relaxed, const Vec3& center, double crust_thickness, bool fluid);

/// mu / K of a fluid liquid layer in ocean_layers: h2 changes by < 0.5% between 1e-6 and 1e-8
/// (ocean-L3; the integration fails near 1e-9).
inline constexpr double fluid_shear_fraction = 1e-6;

/// Travel time along the z axis from z_from to z_to (about `center`, R) through the interior cut
/// into `layers` spherical layers, each with its own P-wave speed from eq. 15 and 16 applied to
/// the interior springs whose midpoints lie in it and the interior mass in it: the stretch stage
/// strengthens the springs toward the centre, where the pressure is highest, and the interior
/// nodes are denser than the body's mean 3/(4 pi) (the crust's mass lies outside r_I).
double layered_p_wave_time(const Checkpoint& relaxed, const Vec3& center, double z_from, double z_to, int layers = 6);

/// (d) P-wave travel time: the particles within `cap` of the top (largest z about the centre of
/// mass) get the inward velocity `pulse_speed`; beside an unpulsed copy (no damping), the
/// signal is the mean |velocity difference| (centre-of-mass motion removed) of the particles
/// within `cap` of the bottom. Arrival: the first time the signal exceeds `threshold_fraction`
/// of its maximum over the run (2 straight-path P times). Theory: path / V_IP, path = the
/// distance between the two caps along z.
struct PWaveResult {
  double arrival_time = 0;   ///< measured, t_grav
  double theory_time = 0;    ///< path / V_IP, t_grav
  double path_length = 0;    ///< R
  double ratio = 0;          ///< arrival_time / theory_time
  double layered_time = 0;   ///< layered_p_wave_time along the same path, t_grav
  double layered_ratio = 0;  ///< arrival_time / layered_time
  double threshold = 0;      ///< signal level of the arrival, sqrt(GM/R)
  std::vector<double> time;
  std::vector<double> signal;
};
PWaveResult measure_p_wave(const Checkpoint& relaxed, const Config& config, const BodyMaterial& material,
                           double pulse_speed = 1e-2, double cap = 0.15, double threshold_fraction = 0.1);

}  // namespace tidalcrust
