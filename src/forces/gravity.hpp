#pragma once
// Self-gravity of the body by direct summation over all pairs with Plummer softening (Plummer
// 1911; Aarseth, Gravitational N-Body Simulations, 2003). Units: G = M = R = 1, masses M,
// lengths R, accelerations G M/R^2, energies G M^2/R.
#include <cmath>
#include <cstddef>
#include <string_view>
#include <vector>

#include "model/choices.hpp"

namespace tidalcrust {

// GravityKernel, the `[gravity] kernel` that DirectGravity evaluates the pairs with, is a closed
// choice of the configuration (model/choices.hpp).

/// The kernel as this build computes it, for the checkpoint: its name, and for fast the code
/// this build runs: "fast/avx512", "fast/generic" (a build without AVX-512) or "portable".
const char* gravity_kernel_label(GravityKernel kernel);

/// Whether two kernel labels give the same bits: equal labels, or "fast/generic" and "portable"
/// (without AVX-512 the fast kernel is the portable code).
bool same_gravity_bits(std::string_view a, std::string_view b);

/// Plummer-softened inverse cube: 1 / (r^2 + eps^2)^(3/2), for r2 = r^2 and eps2 = eps^2
/// (R^-3). The pull on i from j is m_j (x_j - x_i) times this.
inline double plummer_inverse_cube(double r2, double eps2) {
  const double s = r2 + eps2;
  return 1.0 / (s * std::sqrt(s));
}

/// What PlummerPairEvaluator::force_and_energy returns for the pair (i, j).
struct PairForceEnergy {
  /// f = 1/(r^2 + eps^2)^(3/2) (R^-3): the acceleration of i is m_j f (x_j - x_i), that of j is
  /// -m_i f (x_j - x_i); kept per unit mass so callers multiply by one mass, not divide.
  double inverse_cube = 0;
  /// -m_i m_j / sqrt(r^2 + eps^2) (G M^2/R), the pair's potential energy; its gradient with
  /// respect to x_i is minus the force m_i m_j f (x_j - x_i).
  double energy = 0;
};

/// One pair of point masses under Newtonian gravity with Plummer softening eps: the textbook
/// pair law, evaluated like HOOMD-blue's pair evaluators (built from one pair's parameters).
/// The body's self-gravity pairs and the perturber-particle pairs both follow it. DirectGravity
/// computes the same law for all pairs at once with SIMD (its last bits differ).
struct PlummerPairEvaluator {
  double mass_i;      ///< m_i (M)
  double mass_j;      ///< m_j (M)
  double softening2;  ///< eps^2 (R^2)

  /// r2 = |x_j - x_i|^2 (R^2).
  PairForceEnergy force_and_energy(double r2) const {
    const double s = r2 + softening2;
    return {plummer_inverse_cube(r2, softening2), -mass_i * mass_j / std::sqrt(s)};
  }
};

/// Potential energy of the body's self-gravity, sum over pairs i < j of
/// -m_i m_j / sqrt(r_ij^2 + eps^2) (G M^2/R): mass [N] in M, softening eps in R, position [N*3]
/// in R. O(N^2), for diagnostics such as the energy budget's samples, not for every step. Each
/// row i sums its j > i in 8 SIMD lanes fixed by the indices, the rows run in parallel and are
/// added in index order: the same bits for any thread count and any run. Only correctly rounded
/// operations (no estimates, no fused multiply-adds): the same bits in every x86-64 build, so
/// it has no fast variant.
double self_gravity_energy(const std::vector<double>& mass, double softening, const double* position);

/// a_i = sum_j m_j (x_j - x_i) / (|x_j - x_i|^2 + eps^2)^(3/2) for every particle.
///
/// Each pair is evaluated once and acts on both particles (Newton's third law). For speed the
/// pairs are split into a FIXED number of blocks (interleaved pairs of rows, balanced in pair
/// count), each accumulating into its own buffer while sweeping j in L1-sized chunks, two rows
/// at a time with 8-wide SIMD over j; the buffers are then added per particle in block order.
/// Every particle's sum therefore has one fixed order, whatever the number of threads: the
/// result is bitwise independent of it.
///
/// GravityKernel::fast with AVX-512: the inverse cube comes from the hardware reciprocal square root estimate
/// (vrsqrt14pd, exactly specified, 14 bits) refined by two Newton steps (~1 ulp) instead of a
/// square root and a division, which share one slow divider unit (that is most of the speed).
/// GravityKernel::portable (and fast without AVX-512) takes the inverse square root from
/// portable_math::inverse_sqrt (an integer guess and Newton steps in plain IEEE arithmetic): the
/// same bits in every x86-64 build (bench: `portable_ms_per_step`), its last bits other than the
/// AVX-512 fast kernel's.
class DirectGravity {
 public:
  /// mass [N] in M; softening eps in R (Body::softening).
  DirectGravity(const std::vector<double>& mass, double softening, GravityKernel kernel = GravityKernel::fast);

  /// Writes accelerations [N*3] (G M/R^2) for positions [N*3] (R). `parallel` false keeps
  /// the work on the calling thread (same result).
  void accelerations(const double* position, double* acceleration, bool parallel = true);

  // accelerations() in pieces, so a caller can schedule the blocks among its own work:
  // load_positions(), then accumulate_block(b) for every b (any order, any threads), then
  // sum_blocks(i) for every particle.
  void load_positions(const double* position);
  void accumulate_block(int block);
  /// a[3] = acceleration of particle i: the block buffers added in block order.
  void sum_blocks(std::size_t i, double* a) const {
    double sum[3] = {0, 0, 0};
    for (std::size_t b = 0; b < static_cast<std::size_t>(block_count); ++b)
      for (std::size_t k = 0; k < 3; ++k) sum[k] += buffers_[(3 * b + k) * padded_ + i];
    for (std::size_t k = 0; k < 3; ++k) a[k] = sum[k];
  }

  std::size_t particle_count() const { return count_; }
  GravityKernel kernel() const { return kernel_; }
  /// Number of pair blocks (fixed; the unit of parallel work).
  static constexpr int block_count = 16;

 private:
  GravityKernel kernel_;
  std::size_t count_;
  std::size_t padded_;  ///< count_ rounded up to the SIMD width
  double eps2_;
  // Structure-of-arrays copy; padding particles have zero mass and sit far away.
  std::vector<double> x_, y_, z_, m_;
  std::vector<double> buffers_;  ///< [block_count][3][padded_]
};

}  // namespace tidalcrust
