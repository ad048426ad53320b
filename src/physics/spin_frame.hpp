#pragma once
// A spinning body (docs/spin.md): the body spins at Omega (rad/t_grav; the breakup rate
// sqrt(GM/R^3) is 1) about its z axis, the body frame's north. The relax stage relaxes it in the
// co-rotating frame, which turns as Rz(Omega t) (t the stage clocks' time, continuous over the
// pipeline), and hands the encounter a body spinning in the inertial frame; the maps are drawn in
// the body frame, x_body = Rz(Omega t)^T (x - x_cm). With Omega = 0 every function here is the
// identity (or adds nothing).
#include <vector>

#include "base/vec3.hpp"
#include "model/body.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// Rz(Omega t): the body frame's axes at time t (t_grav) in the inertial frame, for a body that
/// spins at Omega (rad/t_grav) about +z and whose frame was the inertial frame at t = 0. Exactly
/// the identity for Omega t = 0.
Matrix3 spin_rotation(double angular_velocity, double time, bool portable = false);

/// Adds the fictitious accelerations of the frame co-rotating at Omega about +z through the
/// mass-weighted centre c of `x` (model/center_of_mass.hpp; one pass in index order):
/// centrifugal -Omega x (Omega x (x_i - c)) = Omega^2 ((x_i - c)_x, (x_i - c)_y, 0) and, when `v`
/// is given, Coriolis -2 Omega x v_i = 2 Omega (v_iy, -v_ix, 0). x, v [N*3] (R, sqrt(GM/R)),
/// a [N*3] (G M/R^2), changed in place.
void add_rotating_frame_acceleration(const Body& body, double angular_velocity, const double* x, const double* v,
                                     std::vector<double>& a);

/// A state relaxed in the frame co-rotating since t = 0 turned into the inertial frame at its
/// time t: positions about the centre of mass c turned by Rz(Omega t), velocities
/// Rz(Omega t) (v + Omega z x (x - c)); the perturber is left alone. Nothing changes for Omega = 0.
void rotating_to_inertial(const Body& body, State& state, double angular_velocity, bool portable = false);

/// The fit r_i = a0 + a2 P2(cos theta_i) of the shell nodes' distances from the centre of mass
/// (least squares, theta from the body frame's +z after `to_body` is applied to x - c) and the
/// flattening it gives: equatorial radius a = a0 - a2/2, polar radius c = a0 + a2,
/// f = (a - c)/a. NaN values without shell nodes.
struct ShellFlattening {
  double mean_radius = 0;        ///< a0, R
  double p2_amplitude = 0;       ///< a2, R
  double equatorial_radius = 0;  ///< a, R
  double polar_radius = 0;       ///< c, R
  double flattening = 0;         ///< (a - c)/a
  double rms_residual = 0;       ///< of the fit, R
};
ShellFlattening shell_flattening(const Body& body, const State& state, const Matrix3& to_body = Matrix3::Identity());

/// The body's angular velocity omega = I^-1 L about its centre of mass (I the inertia tensor of
/// the particles about it, L their angular momentum relative to its motion), rad/t_grav: the
/// measured spin of a slightly deformable body. Zero for fewer than three particles.
Vec3 body_angular_velocity(const Body& body, const State& state);

/// Removes the body's rigid rotation about its centre of mass: v_i -= omega x (x_i - c) with
/// omega = body_angular_velocity, so that its angular momentum about c is 0 (to rounding). The
/// relax stage of a spinning body does it after every step in the co-rotating frame: the spring
/// damping cannot stop a rigid rotation relative to the frame, and the Coriolis force turns the
/// body's centrifugal expansion into one (the body would lag the frame by Omega dI/I).
void remove_rigid_rotation(const Body& body, State& state);

/// The flattening of a body of radial Love number h2 spinning at Omega (G = M = R = 1): the
/// degree-2 part of the centrifugal potential, W2 = -(1/3) Omega^2 r^2 P2(cos theta), raises the
/// surface by h2 W2 / g (g = 1), so f = h2 q / 2 with q = Omega^2 R^3/(G M) (to first order in q;
/// a fluid body's h2 = 5/2 gives Maclaurin's 5 q / 4). docs/spin.md derives it.
double centrifugal_flattening(double h2, double angular_velocity);

}  // namespace tidalcrust
