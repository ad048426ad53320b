#pragma once
// All accelerations of one step: springs (eqs. 12-14, optional eq. 26 for cross springs),
// hinges (eq. 22), self-gravity (direct sum or tree code, Plummer softening) and the perturber, which
// pulls every particle and is pulled back; and the potential energy of each of these laws.
// Units: G = M = R = 1, accelerations G M / R^2, energies G M^2/R.
//
// Each law is an evaluator of force AND energy for one element (SpringEvaluator,
// HingeEvaluator, PlummerPairEvaluator); the loops over springs and hinges are written once
// here and serve both the forces of a step and the energies. The textbook step
// (integrate/textbook_step.hpp) evaluates the same laws in its own plain loops.
//
// Determinism: every spring and hinge force is computed into its own slot, then each particle
// GATHERS its forces over a fixed incidence list (springs in index order, then hinges in
// index order), divides by its mass and adds gravity, then the perturber's pull. No atomics,
// no scatter: the result is bitwise independent of the thread count.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "model/body.hpp"
#include "model/config.hpp"
#include "forces/gravity.hpp"
#include "forces/hinge_force.hpp"
#include "forces/liquid_pressure.hpp"
#include "forces/spring_force.hpp"
#include "forces/tree_gravity.hpp"
#include "model/state.hpp"

namespace tidalcrust {

/// Switches of the force model that come from the configuration rather than the State.
struct ForceOptions {
  double damping = 0.0;               ///< gamma of every spring, 1/t_grav (eq. 14, with the reduced mass)
  bool cross_nonlinear = false;       ///< apply f(eps) of eq. 26 to cross springs
  double cross_strain_scale = 0.03;   ///< eps_C
  double cross_min_force_factor = 0.1;///< F_Ck
  bool self_gravity = true;           ///< false only for tests of the other forces
  GravityKernel gravity_kernel = GravityKernel::fast;  ///< [gravity] kernel (DirectGravity)
  /// [gravity] method: DirectGravity, or TreeGravity at target relative error `force_error`.
  GravityMethod gravity_method = GravityMethod::direct;
  double force_error = 1e-4;
  /// A pass with less work than this (N^2/128 + springs + 4 hinges) runs on one thread:
  /// below it the fork/join costs more than it saves, and far more when the cores are
  /// oversubscribed. Results never depend on it (tests set 1 to exercise the threads).
  std::size_t min_parallel_items = 16384;
};

/// The options of a configuration ([cross] nonlinear, strain_scale, min_force_factor; [gravity]
/// kernel, method, force_error) for a stage that damps its springs at rate `damping` (1/t_grav).
ForceOptions force_options(const Config& config, double damping);

/// Accelerations of the body particles and of the perturber.
struct Accelerations {
  std::vector<double> body;                ///< [N*3] G M / R^2
  std::array<double, 3> perturber{0, 0, 0};///< zero when no perturber is present
};

/// What the force pass noticed that means the run is blowing up (cheap, computed in the
/// force loops; lowest index of each kind, -1 if none).
struct ForceAlarms {
  std::int64_t collapsed_hinge = -1;     ///< a face with |N| < collapsed_face_fraction L^2
  std::int64_t nonfinite_particle = -1;  ///< NaN or infinite acceleration
  bool any() const { return collapsed_hinge >= 0 || nonfinite_particle >= 0; }
};

/// Potential energy of each force law for one configuration (G M^2/R), and the power the spring
/// damping removes. Without damping, kinetic (body and perturber) + potential() is conserved by
/// the leapfrog up to its O(dt^2) error and the small work of the hinge force's non-conservative
/// part (HingeEvaluator).
struct Energies {
  double spring = 0;        ///< elastic energy of the springs (eq. 12, eq. 26 integrated for softened cross springs)
  double hinge = 0;         ///< bending energy of the hinges (HingeEvaluator)
  double self_gravity = 0;  ///< sum over pairs of -m_i m_j / sqrt(r^2 + eps^2); 0 with self-gravity off
  double perturber = 0;     ///< sum over particles of -M2 m_i / sqrt(r^2 + eps^2); 0 without a perturber
  double liquid = 0;        ///< volumetric energy of a liquid layer and its support's (LiquidPressure); 0 without one
  double damping_power = 0; ///< sum over springs of gamma mu (d.dv)^2/L^2 >= 0, G M^2/R per t_grav
  double potential() const { return spring + hinge + self_gravity + perturber + liquid; }
};

/// Work done in one leapfrog step by the forces that have no potential (docs/energy-budget.md),
/// G M^2/R. Both are measured as the integrator applies the forces: the step's force F at the
/// half-step positions times the step's displacement Delta x = x_end - x_start.
struct StepWork {
  /// Energy the spring damping took out of the motion: sum over springs of
  /// c_d (d_half . Delta d), c_d = gamma mu (d_half . dv_start)/L_half^2 the damping coefficient
  /// of the step (start-of-step velocities, as the kick uses them); >= 0 up to O(dt^2).
  double damping_removed = 0;
  /// Work of the hinge forces beyond minus the change of the hinge energy E_h: sum over hinges
  /// of (E_h/C)(half step) * (C(end) - C(start)), the midpoint rule for the integral of (E_h/C) dC.
  double hinge_added = 0;
};

class ForceField {
 public:
  /// Keeps a reference to `body`, which must outlive the ForceField.
  explicit ForceField(const Body& body, ForceOptions options = {});

  /// Accelerations at positions [N*3] (R) and velocities [N*3] (sqrt(GM/R); they enter
  /// only through damping). `liquid_rest_volume` [N] (State::liquid_rest_volume; empty without a
  /// liquid layer), `liquid_support` [N*3] (State::liquid_support; empty: none). Returns the
  /// blow-up alarms of this pass.
  ForceAlarms compute(const double* position, const double* velocity, const SpringState& springs,
                      const HingeState& hinges, const Perturber& perturber,
                      const std::vector<double>& liquid_rest_volume, const std::vector<double>& liquid_support,
                      Accelerations& out);
  ForceAlarms compute(const State& state, Accelerations& out) {
    return compute(state.position.data(), state.velocity.data(), state.springs, state.hinges,
                   state.perturber, state.liquid_rest_volume, state.liquid_support, out);
  }

  /// Potential energies at positions [N*3] (R) and the damping power at velocities [N*3]
  /// (sqrt(GM/R)), each law's elements summed in index order on one thread (self-gravity is
  /// O(N^2): for diagnostics, not every step). Checks the sizes like compute().
  Energies energies(const double* position, const double* velocity, const SpringState& springs,
                    const HingeState& hinges, const Perturber& perturber,
                    const std::vector<double>& liquid_rest_volume, const std::vector<double>& liquid_support);
  Energies energies(const State& state) {
    return energies(state.position.data(), state.velocity.data(), state.springs, state.hinges, state.perturber,
                    state.liquid_rest_volume, state.liquid_support);
  }

  /// The work of the non-conservative forces in the step from positions `start` to `end` [N*3]
  /// (R) whose forces the last compute() evaluated at `half` (the half-step positions; it must
  /// have been called with exactly these). Sums in index order on one thread: deterministic.
  StepWork work_of_step(const double* start, const double* half, const double* end) const;

  // The pieces of compute(), public for tests and micro-benchmarks.
  /// Fills spring_forces(): force on the first particle of each spring (the second feels -F).
  void compute_spring_forces(const double* position, const double* velocity, const SpringState& springs);
  /// Fills hinge_forces(): the four forces of each hinge. Returns the lowest collapsed hinge or -1.
  std::int64_t compute_hinge_forces(const double* position, const HingeState& hinges);
  /// Self-gravity accelerations [N*3].
  void compute_gravity(const double* position, double* acceleration) {
    if (tree_) tree_->accelerations(position, acceleration);
    else gravity_->accelerations(position, acceleration);
  }

  /// Springs and hinges per unit of parallel work.
  static constexpr std::size_t spring_chunk = 2048;
  static constexpr std::size_t hinge_chunk = 512;

  const std::vector<double>& spring_forces() const { return spring_force_; }  ///< [Ns*3] G M^2/R^2
  const std::vector<double>& hinge_forces() const { return hinge_force_; }    ///< [Nh*4*3] G M^2/R^2

  /// A sentence naming the element that went wrong at positions [N*3], for SimulationError
  /// (integrate/blow_up.hpp adds the likely cause).
  std::string describe(const ForceAlarms& alarms, const double* position) const;

  const Body& body() const { return body_; }
  const ForceOptions& options() const { return options_; }

 private:
  /// TIDALCRUST_ASSERT that the state's per-spring and per-hinge arrays match the body (the
  /// checkpoint reader has checked them: a mismatch is a bug).
  void check_sizes(const SpringState& springs, const HingeState& hinges) const;
  void refresh_half_rest_angles(const HingeState& hinges);
  /// THE loop over springs [begin, end): builds each spring's evaluator from the body and the
  /// state and calls visit(s, d, result) with d = x_i - x_j (double[3]) and its SpringForceEnergy.
  template <typename Visit>
  void for_each_spring(std::size_t begin, std::size_t end, const double* position, const double* velocity,
                       const SpringState& springs, Visit&& visit) const;
  /// THE loop over hinges [begin, end): calls visit(h, HingeForces) with each hinge's forces and
  /// energy. Needs refresh_half_rest_angles() first.
  template <typename Visit>
  void for_each_hinge(std::size_t begin, std::size_t end, const double* position, Visit&& visit) const;
  void spring_range(std::size_t begin, std::size_t end, const double* position, const double* velocity,
                    const SpringState& springs);
  /// Returns the lowest collapsed hinge in [begin, end), or -1 (rest angles: half_rest_).
  std::int64_t hinge_range(std::size_t begin, std::size_t end, const double* position);
  /// Acceleration of particle p into acceleration[3p..3p+2]: spring forces, then hinge forces
  /// (each in index order), divided by the mass, plus self-gravity when `with_gravity`.
  void gather(std::size_t p, bool with_gravity, double* acceleration) const;

  const Body& body_;
  ForceOptions options_;
  std::optional<DirectGravity> gravity_;  ///< the self-gravity method in use: one of the two
  std::optional<TreeGravity> tree_;
  std::optional<LiquidPressure> liquid_;  ///< present for a body with a liquid layer
  std::vector<double> reduced_mass_;    ///< [Ns] m_i m_j/(m_i+m_j)
  std::vector<std::uint8_t> nonlinear_; ///< [Ns] 1 where eq. 26 applies
  CrossSoftening cross_;                ///< eq. 26 parameters
  // Incidence (CSR): for particle p, entries [offset[p], offset[p+1]) list the slots whose
  // forces act on it, in increasing order. Spring entry 2s+0 / 2s+1: +F / -F of spring s.
  // Hinge entry 4h+v: force on vertex v of hinge h.
  std::vector<std::int32_t> spring_offset_, spring_entry_;
  std::vector<std::int32_t> hinge_offset_, hinge_entry_;
  std::vector<double> spring_force_;
  std::vector<double> hinge_force_;
  std::vector<double> spring_damping_;      ///< [Ns] damping coefficient of the last pass (work_of_step)
  std::vector<double> hinge_work_rate_;     ///< [Nh] E_h/C of the last pass (work_of_step)
  std::vector<double> cached_rest_angle_;  ///< rest angles the half-angle table was made from
  std::vector<HalfRestAngle> half_rest_;
};

}  // namespace tidalcrust
