#include "forces/gravity.hpp"

#include "base/portable_math.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace tidalcrust {
namespace {

constexpr std::size_t lanes = 8;         ///< SIMD width in doubles (one AVX-512 register)
constexpr std::size_t chunk_size = 512;  ///< j-range swept at a time: 7 arrays x 4 KB stay in L1

/// Where padding particles sit: far from everything and from each other, with zero mass.
constexpr double padding_distance = 1e10;

/// Pointers of one block's accumulation buffer.
struct Accumulator {
  double* x;
  double* y;
  double* z;
};

#if defined(__AVX512F__)
inline __m512d inverse_cube(__m512d s) {
  // y ~ 1/sqrt(s) to 14 bits, then two Newton steps y <- y (3/2 - s/2 y^2): ~1 ulp.
  const __m512d three_halves = _mm512_set1_pd(1.5);
  const __m512d half_s = _mm512_mul_pd(_mm512_set1_pd(0.5), s);
  __m512d y = _mm512_maskz_rsqrt14_pd(0xFF, s);  // maskz: avoids a GCC 12 header warning
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(half_s, _mm512_mul_pd(y, y), three_halves));
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(half_s, _mm512_mul_pd(y, y), three_halves));
  return _mm512_mul_pd(y, _mm512_mul_pd(y, y));
}

/// Sum of the lanes in lane order (_mm512_reduce_add_pd trips a GCC 12 header warning).
inline double lane_sum(__m512d v) {
  alignas(64) double lane[lanes];
  _mm512_store_pd(lane, v);
  double sum = 0;
  for (double l : lane) sum += l;
  return sum;
}

/// Lanes of the vector starting at j that hold partners j' > row.
inline __mmask8 partners_after(std::size_t row, std::size_t j) {
  return row < j ? static_cast<__mmask8>(0xFF) : static_cast<__mmask8>(0xFFu << std::min<std::size_t>(row - j + 1, 8));
}

/// The pairs of rows i and i+1 (i even) with j in [j_begin, j_end), j > row: the pull of j on
/// a row is summed in `lanes` partial sums (lane = j mod lanes), which are then added to
/// acc[row]; the pulls of the rows on j are subtracted from acc[j], row i first. j_begin is a
/// multiple of `lanes`; lanes with j <= row are masked out. Two rows share every load and
/// store of the j side (register blocking: ~20% faster than one row).
void pair_rows_fast(std::size_t i, std::size_t j_begin, std::size_t j_end, const double* x, const double* y,
                    const double* z, const double* m, double eps2, Accumulator acc) {
  const __m512d e2 = _mm512_set1_pd(eps2);
  const __m512d xa = _mm512_set1_pd(x[i]), ya = _mm512_set1_pd(y[i]), za = _mm512_set1_pd(z[i]);
  const __m512d xb = _mm512_set1_pd(x[i + 1]), yb = _mm512_set1_pd(y[i + 1]), zb = _mm512_set1_pd(z[i + 1]);
  const __m512d ma = _mm512_set1_pd(m[i]), mb = _mm512_set1_pd(m[i + 1]);
  __m512d sxa = _mm512_setzero_pd(), sya = sxa, sza = sxa, sxb = sxa, syb = sxa, szb = sxa;
  for (std::size_t j = j_begin; j < j_end; j += lanes) {
    const __m512d xj = _mm512_loadu_pd(x + j), yj = _mm512_loadu_pd(y + j), zj = _mm512_loadu_pd(z + j);
    const __m512d mj = _mm512_loadu_pd(m + j);
    const __m512d dxa = _mm512_sub_pd(xj, xa), dya = _mm512_sub_pd(yj, ya), dza = _mm512_sub_pd(zj, za);
    const __m512d dxb = _mm512_sub_pd(xj, xb), dyb = _mm512_sub_pd(yj, yb), dzb = _mm512_sub_pd(zj, zb);
    __m512d fa = inverse_cube(_mm512_fmadd_pd(dza, dza, _mm512_fmadd_pd(dya, dya, _mm512_fmadd_pd(dxa, dxa, e2))));
    __m512d fb = inverse_cube(_mm512_fmadd_pd(dzb, dzb, _mm512_fmadd_pd(dyb, dyb, _mm512_fmadd_pd(dxb, dxb, e2))));
    if (j <= i + 1) {
      fa = _mm512_maskz_mov_pd(partners_after(i, j), fa);
      fb = _mm512_maskz_mov_pd(partners_after(i + 1, j), fb);
    }
    const __m512d fja = _mm512_mul_pd(mj, fa), fia = _mm512_mul_pd(ma, fa);
    const __m512d fjb = _mm512_mul_pd(mj, fb), fib = _mm512_mul_pd(mb, fb);
    sxa = _mm512_fmadd_pd(fja, dxa, sxa);
    sya = _mm512_fmadd_pd(fja, dya, sya);
    sza = _mm512_fmadd_pd(fja, dza, sza);
    sxb = _mm512_fmadd_pd(fjb, dxb, sxb);
    syb = _mm512_fmadd_pd(fjb, dyb, syb);
    szb = _mm512_fmadd_pd(fjb, dzb, szb);
    _mm512_storeu_pd(acc.x + j, _mm512_fnmadd_pd(fib, dxb, _mm512_fnmadd_pd(fia, dxa, _mm512_loadu_pd(acc.x + j))));
    _mm512_storeu_pd(acc.y + j, _mm512_fnmadd_pd(fib, dyb, _mm512_fnmadd_pd(fia, dya, _mm512_loadu_pd(acc.y + j))));
    _mm512_storeu_pd(acc.z + j, _mm512_fnmadd_pd(fib, dzb, _mm512_fnmadd_pd(fia, dza, _mm512_loadu_pd(acc.z + j))));
  }
  acc.x[i] += lane_sum(sxa);
  acc.y[i] += lane_sum(sya);
  acc.z[i] += lane_sum(sza);
  acc.x[i + 1] += lane_sum(sxb);
  acc.y[i + 1] += lane_sum(syb);
  acc.z[i + 1] += lane_sum(szb);
}
#endif

/// The portable kernel: the pairs, lanes and order of rows of pair_rows_fast(), in plain
/// arithmetic: s = ((dx dx + dy dy) + dz dz) + eps^2, y = portable_math::inverse_sqrt(s) (an
/// integer guess and four Newton steps), f = y (y y), every product and sum rounded on its own
/// (-ffp-contract=off). Only integer and correctly rounded IEEE operations, so any x86-64 build
/// gives the same bits whether the compiler vectorises it with SSE2 or AVX-512 (lane l always
/// takes j = l mod lanes); no division or sqrt, which share the slow divider unit.
void pair_rows_portable(std::size_t i, std::size_t j_begin, std::size_t j_end, const double* x, const double* y,
                        const double* z, const double* m, double eps2, Accumulator acc) {
  for (std::size_t row = i; row < i + 2; ++row) {
    const double xi = x[row], yi = y[row], zi = z[row], mi = m[row];
    double sx[lanes] = {}, sy[lanes] = {}, sz[lanes] = {};
    for (std::size_t j0 = j_begin; j0 < j_end; j0 += lanes) {
      // Three lane loops (differences, inverse square roots, sums), each one vector loop (in one
      // loop GCC 12 left the integer guess scalar; the sums need `omp simd`, as it cannot tell
      // that acc does not alias the positions). Lane-wise operations: the same roundings scalar
      // or vectorised.
      double dx[lanes], dy[lanes], dz[lanes], r[lanes];
      for (std::size_t l = 0; l < lanes; ++l) {
        dx[l] = x[j0 + l] - xi, dy[l] = y[j0 + l] - yi, dz[l] = z[j0 + l] - zi;
        r[l] = dx[l] * dx[l] + dy[l] * dy[l] + dz[l] * dz[l] + eps2;
      }
      for (std::size_t l = 0; l < lanes; ++l) r[l] = portable_math::inverse_sqrt(r[l]);
#pragma omp simd
      for (std::size_t l = 0; l < lanes; ++l) {
        const std::size_t j = j0 + l;
        const double f = j > row ? r[l] * (r[l] * r[l]) : 0.0;
        const double fj = m[j] * f, fi = mi * f;
        sx[l] += fj * dx[l];
        sy[l] += fj * dy[l];
        sz[l] += fj * dz[l];
        acc.x[j] -= fi * dx[l];
        acc.y[j] -= fi * dy[l];
        acc.z[j] -= fi * dz[l];
      }
    }
    for (std::size_t l = 0; l < lanes; ++l) {
      acc.x[row] += sx[l];
      acc.y[row] += sy[l];
      acc.z[row] += sz[l];
    }
  }
}

}  // namespace

double self_gravity_energy(const std::vector<double>& mass, double softening, const double* position) {
  const std::size_t n = mass.size();
  const double eps2 = softening * softening;
  // Structure of arrays, so the inner loop vectorises: the paper-T body has ~10^7 pairs and the
  // encounter samples them every sample_interval steps.
  std::vector<double> x(n), y(n), z(n), row(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) x[i] = position[3 * i], y[i] = position[3 * i + 1], z[i] = position[3 * i + 2];
#pragma omp parallel for schedule(dynamic, 64) if (n >= 512)
  for (std::size_t i = 0; i < n; ++i) {
    const double xi = x[i], yi = y[i], zi = z[i];
    // sum over j > i of m_j / sqrt(r^2 + eps^2) in `lanes` partial sums, lane l taking
    // j = i + 1 + l (mod lanes): the order depends on the indices only, never on addresses.
    double part[lanes] = {};
    std::size_t j = i + 1;
    for (; j + lanes <= n; j += lanes) {
#pragma omp simd
      for (std::size_t l = 0; l < lanes; ++l) {
        const double dx = x[j + l] - xi, dy = y[j + l] - yi, dz = z[j + l] - zi;
        part[l] += mass[j + l] / std::sqrt(dx * dx + dy * dy + dz * dz + eps2);
      }
    }
    double sum = 0;
    for (; j < n; ++j) {
      const double dx = x[j] - xi, dy = y[j] - yi, dz = z[j] - zi;
      sum += mass[j] / std::sqrt(dx * dx + dy * dy + dz * dz + eps2);
    }
    for (std::size_t l = 0; l < lanes; ++l) sum += part[l];
    row[i] = -mass[i] * sum;  // PlummerPairEvaluator's energy, -m_i m_j / sqrt(r^2 + eps^2), summed over j
  }
  double energy = 0;
  for (std::size_t i = 0; i < n; ++i) energy += row[i];
  return energy;
}

const char* gravity_kernel_label(GravityKernel kernel) {
  switch (kernel) {
    case GravityKernel::portable: return "portable";
#if defined(__AVX512F__)
    case GravityKernel::fast: return "fast/avx512";
#else
    case GravityKernel::fast: return "fast/generic";
#endif
  }
  return "";
}

bool same_gravity_bits(std::string_view a, std::string_view b) {
  // Without AVX-512 the fast kernel IS the portable one (pair_rows_portable). The labels are
  // build labels of a checkpoint, not the configuration's choice.
  auto bits = [](std::string_view label) { return label == "fast/generic" ? std::string_view("portable") : label; };
  return bits(a) == bits(b);
}

DirectGravity::DirectGravity(const std::vector<double>& mass, double softening, GravityKernel kernel)
    : kernel_(kernel),
      count_(mass.size()),
      padded_((mass.size() + 1 + lanes - 1) / lanes * lanes),  // room for row i+1 of the last pair
      eps2_(softening * softening),
      x_(padded_),
      y_(padded_, 0.0),
      z_(padded_, 0.0),
      m_(padded_, 0.0),
      buffers_(static_cast<std::size_t>(block_count) * 3 * padded_) {
  std::copy(mass.begin(), mass.end(), m_.begin());
  for (std::size_t i = count_; i < padded_; ++i) x_[i] = padding_distance * static_cast<double>(i + 1);
}

void DirectGravity::load_positions(const double* position) {
  for (std::size_t i = 0; i < count_; ++i) {
    x_[i] = position[3 * i];
    y_[i] = position[3 * i + 1];
    z_[i] = position[3 * i + 2];
  }
}

void DirectGravity::accumulate_block(int block) {
  // Rows go in pairs (i, i+1), i even. Block b owns the pairs p = i/2 with p mod 2B in
  // {b, 2B-1-b}: a long and a short pair in each period, so all blocks get nearly the same
  // number of interactions.
  const std::size_t n = count_, padded = padded_, b = static_cast<std::size_t>(block);
  constexpr std::size_t blocks = static_cast<std::size_t>(block_count);
  const double *x = x_.data(), *y = y_.data(), *z = z_.data(), *m = m_.data();
  double* buffer = buffers_.data() + b * 3 * padded;
  const Accumulator acc{buffer, buffer + padded, buffer + 2 * padded};
  std::fill(buffer, buffer + 3 * padded, 0.0);
  for (std::size_t c0 = 0; c0 < padded; c0 += chunk_size) {
    const std::size_t c1 = std::min(padded, c0 + chunk_size);
    for (std::size_t period = 0; 2 * period < n && 2 * period < c1; period += 2 * blocks) {
      for (std::size_t pair : {period + b, period + 2 * blocks - 1 - b}) {
        const std::size_t i = 2 * pair;
        if (i >= n || i >= c1) continue;
        const std::size_t j_begin = std::max(c0, i / lanes * lanes);
#if defined(__AVX512F__)
        if (kernel_ == GravityKernel::fast) {
          pair_rows_fast(i, j_begin, c1, x, y, z, m, eps2_, acc);
          continue;
        }
#endif
        pair_rows_portable(i, j_begin, c1, x, y, z, m, eps2_, acc);
      }
    }
  }
}

void DirectGravity::accelerations(const double* position, double* acceleration, bool parallel) {
  load_positions(position);
#pragma omp parallel if (parallel)
  {
#pragma omp for schedule(dynamic, 1)
    for (int b = 0; b < block_count; ++b) accumulate_block(b);
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < count_; ++i) sum_blocks(i, acceleration + 3 * i);
  }
}

}  // namespace tidalcrust
