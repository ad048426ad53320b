#include "gravity.hpp"

#include <algorithm>

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

/// The pairs (i, j) of row i with j in [j_begin, j_end), j > i: the pull of j on i is summed in
/// `lanes` partial sums (lane = j mod lanes), then added to acc[i] lane by lane in order; the
/// pull of i on j is subtracted from acc[j]. j_begin is a multiple of `lanes`; lanes with
/// j <= i are masked out.
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

void pair_row(std::size_t i, std::size_t j_begin, std::size_t j_end, const double* x, const double* y,
              const double* z, const double* m, double eps2, Accumulator acc) {
  const __m512d xi = _mm512_set1_pd(x[i]), yi = _mm512_set1_pd(y[i]), zi = _mm512_set1_pd(z[i]);
  const __m512d mi = _mm512_set1_pd(m[i]), e2 = _mm512_set1_pd(eps2);
  __m512d sx = _mm512_setzero_pd(), sy = sx, sz = sx;
  for (std::size_t j = j_begin; j < j_end; j += lanes) {
    const __m512d dx = _mm512_sub_pd(_mm512_loadu_pd(x + j), xi);
    const __m512d dy = _mm512_sub_pd(_mm512_loadu_pd(y + j), yi);
    const __m512d dz = _mm512_sub_pd(_mm512_loadu_pd(z + j), zi);
    const __m512d s = _mm512_fmadd_pd(dz, dz, _mm512_fmadd_pd(dy, dy, _mm512_fmadd_pd(dx, dx, e2)));
    __m512d f = inverse_cube(s);
    if (j <= i) f = _mm512_maskz_mov_pd(static_cast<__mmask8>(0xFFu << (i - j + 1)), f);
    const __m512d fj = _mm512_mul_pd(_mm512_loadu_pd(m + j), f);
    const __m512d fi = _mm512_mul_pd(mi, f);
    sx = _mm512_fmadd_pd(fj, dx, sx);
    sy = _mm512_fmadd_pd(fj, dy, sy);
    sz = _mm512_fmadd_pd(fj, dz, sz);
    _mm512_storeu_pd(acc.x + j, _mm512_fnmadd_pd(fi, dx, _mm512_loadu_pd(acc.x + j)));
    _mm512_storeu_pd(acc.y + j, _mm512_fnmadd_pd(fi, dy, _mm512_loadu_pd(acc.y + j)));
    _mm512_storeu_pd(acc.z + j, _mm512_fnmadd_pd(fi, dz, _mm512_loadu_pd(acc.z + j)));
  }
  alignas(64) double px[lanes], py[lanes], pz[lanes];
  _mm512_store_pd(px, sx);
  _mm512_store_pd(py, sy);
  _mm512_store_pd(pz, sz);
  for (std::size_t l = 0; l < lanes; ++l) {
    acc.x[i] += px[l];
    acc.y[i] += py[l];
    acc.z[i] += pz[l];
  }
}
#else
void pair_row(std::size_t i, std::size_t j_begin, std::size_t j_end, const double* x, const double* y,
              const double* z, const double* m, double eps2, Accumulator acc) {
  const double xi = x[i], yi = y[i], zi = z[i], mi = m[i];
  double sx[lanes] = {}, sy[lanes] = {}, sz[lanes] = {};
  for (std::size_t j0 = j_begin; j0 < j_end; j0 += lanes) {
    for (std::size_t l = 0; l < lanes; ++l) {
      const std::size_t j = j0 + l;
      const double dx = x[j] - xi, dy = y[j] - yi, dz = z[j] - zi;
      const double f = j > i ? plummer_inverse_cube(dx * dx + dy * dy + dz * dz, eps2) : 0.0;
      const double fj = m[j] * f, fi = mi * f;
      sx[l] += fj * dx;
      sy[l] += fj * dy;
      sz[l] += fj * dz;
      acc.x[j] -= fi * dx;
      acc.y[j] -= fi * dy;
      acc.z[j] -= fi * dz;
    }
  }
  for (std::size_t l = 0; l < lanes; ++l) {
    acc.x[i] += sx[l];
    acc.y[i] += sy[l];
    acc.z[i] += sz[l];
  }
}
#endif

}  // namespace

DirectGravity::DirectGravity(const std::vector<double>& mass, double softening)
    : count_(mass.size()),
      padded_((mass.size() + lanes - 1) / lanes * lanes),
      eps2_(softening * softening),
      x_(padded_),
      y_(padded_, 0.0),
      z_(padded_, 0.0),
      m_(padded_, 0.0),
      buffers_(static_cast<std::size_t>(block_count) * 3 * padded_) {
  std::copy(mass.begin(), mass.end(), m_.begin());
  for (std::size_t i = count_; i < padded_; ++i) x_[i] = padding_distance * static_cast<double>(i + 1);
}

void DirectGravity::accelerations(const double* position, double* acceleration, bool parallel) {
  const std::size_t n = count_, padded = padded_;
  for (std::size_t i = 0; i < n; ++i) {
    x_[i] = position[3 * i];
    y_[i] = position[3 * i + 1];
    z_[i] = position[3 * i + 2];
  }
  const double *x = x_.data(), *y = y_.data(), *z = z_.data(), *m = m_.data();
  const double eps2 = eps2_;
  double* buffers = buffers_.data();
  constexpr std::size_t blocks = static_cast<std::size_t>(block_count);

#pragma omp parallel if (parallel)
  {
    // Block b owns the rows i with i mod 2B in {b, 2B-1-b}: a long and a short row in each
    // period, so all blocks get nearly the same number of pairs.
#pragma omp for schedule(dynamic, 1)
    for (std::size_t b = 0; b < blocks; ++b) {
      Accumulator acc{buffers + b * 3 * padded, buffers + b * 3 * padded + padded,
                      buffers + b * 3 * padded + 2 * padded};
      std::fill(acc.x, acc.x + 3 * padded, 0.0);
      for (std::size_t c0 = 0; c0 < padded; c0 += chunk_size) {
        const std::size_t c1 = std::min(padded, c0 + chunk_size);
        for (std::size_t period = 0; period < n && period < c1; period += 2 * blocks) {
          for (std::size_t i : {period + b, period + 2 * blocks - 1 - b}) {
            if (i >= n || i >= c1) continue;
            const std::size_t j_begin = std::max(c0, i / lanes * lanes);
            pair_row(i, j_begin, c1, x, y, z, m, eps2, acc);
          }
        }
      }
    }
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      double a[3] = {0, 0, 0};
      for (std::size_t b = 0; b < blocks; ++b)
        for (std::size_t k = 0; k < 3; ++k) a[k] += buffers[b * 3 * padded + k * padded + i];
      for (std::size_t k = 0; k < 3; ++k) acceleration[3 * i + k] = a[k];
    }
  }
}

}  // namespace tidalcrust
