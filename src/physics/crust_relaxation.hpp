#pragma once
// How the relax stage (paper section 2.8) takes the stress out of the crust: shell spring rest
// lengths creep toward the current lengths, hinge rest angles are reset to the current angles.
// Interior and cross springs are left alone: they carry the body's weight.
#include "model/body.hpp"
#include "model/state.hpp"

#include <cstdint>
#include <vector>

namespace tidalcrust {

/// Shell springs only: L0 += rate (L - L0), rate in [0, 1] (1: exactly stress-free).
void creep_shell_rest_lengths(const Body& body, State& state, double rate);

/// Every hinge's rest angle becomes its current angle (hinge_angle of hinge_geometry.hpp):
/// no flexural stress left.
void reset_hinge_rest_angles(const Body& body, State& state, bool portable = false);

/// What balance_cross_springs() achieved.
struct CrossBalance {
  /// Largest |sum of cross-spring forces + weight (+ crust force)| over the shell nodes, relative
  /// to what they carry: 0 (to rounding) when every node has cross springs spanning three directions.
  double max_residual = 0;
  std::int64_t unbalanced_nodes = 0;  ///< shell nodes whose residual exceeds 1e-9 of their weight
};

/// Chooses the rest lengths of the cross springs so that at the current positions the
/// cross springs of each shell node s exactly carry its weight: sum_n t_n u_n = m_s g_s, with
/// t_n = k_n (L_n - L0_n) the tension of spring n and u_n the unit vector from its interior end
/// to s (so the crust, at rest lengths, carries nothing). Of all tensions that do so, the one
/// closest to the present ones (least squares) is taken: t = t0 + A^T (A A^T)^+ (m g - A t0),
/// A = [u_1 .. u_m]; a node whose springs do not span three directions gets the best it can
/// (residual reported). Linear cross springs only (eq. 12; the damping term vanishes at rest).
/// gravity: self-gravity accelerations [N*3] (G M/R^2) at the current positions.
/// With `stiffness_weighted` the change minimises sum (t - t0)^2 / k instead:
/// t = t0 + K A^T (A K A^T)^+ (m g - A t0), K = diag(k_n), i.e. every rest length changes by
/// u_n . y, as if the node sank by one common y against its springs (the welded coupling, whose
/// stiffnesses span orders of magnitude: equal tension changes would strain its softest springs most).
/// `crust_force` [N*3] (G M^2/R^2, optional): a force the crust puts on each shell node, carried
/// too (sum_n t_n u_n = m_s g_s + F_s); the lithostatic crust's compression pushes outward.
/// Throws InputError if a rest length would not stay positive. docs/crust-support.md.
CrossBalance balance_cross_springs(const Body& body, State& state, const std::vector<double>& gravity,
                                   bool stiffness_weighted = false, const std::vector<double>* crust_force = nullptr);

/// The horizontal strain (negative: compression) of a crust whose own weight rests on a welded
/// elastic interior, for the lithostatic support (docs/crust-support.md, "The lithostatic crust"):
///
///     eps_L = -w / (1/c + 2 C / R_S),
///
/// w = sum_s m_s |g_s| / (4 pi R_S^2) the crust's weight per area (G M^2/R^4); c the interior's
/// degree-0 compliance (layered_sphere_compression; 1/c = 3K for a homogeneous interior) of its
/// radial profile of eq. 15 (interior_modulus_profile in shells of d_I/2 out to r_I - d_I, the
/// outermost one continued to R_S, as the welded springs continue the network; nu = 1/4);
/// C = sum k L0^2 / (2 * 4 pi R_S^2) the membrane's stiffness in equal two-way stretch (e_g R;
/// sqrt(3) k for an equilateral triangular lattice); R_S the mean shell radius. Degree-0 load; the
/// change of the interior's own gravity as it compresses is neglected (relative size rho g R / K).
/// InputError when r_I - d_I leaves no interior springs to measure (it names the keys); internal
/// error (TIDALCRUST_ASSERT) without shell springs.
/// gravity: self-gravity accelerations [N*3] (G M/R^2) at the current positions.
double lithostatic_crust_strain(const Body& body, const State& state, const std::vector<double>& gravity,
                                double interior_radius, double interior_spring_distance);

/// Shell springs only: L0 = L / (1 + strain), so that every shell spring sits at `strain`.
void set_shell_strain(const Body& body, State& state, double strain);

/// The elastic force of the shell springs on each particle [N*3] (G M^2/R^2) at the current
/// positions and rest lengths (eq. 12 without damping): what the cross springs must carry besides
/// the weight when the crust is pre-stressed.
std::vector<double> shell_spring_forces(const Body& body, const State& state);

/// Mean distance of the shell nodes from the body's centre of mass (R); 0 without shell.
double mean_shell_radius(const Body& body, const State& state);

}  // namespace tidalcrust
