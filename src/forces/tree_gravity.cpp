#include "forces/tree_gravity.hpp"

#include "base/portable_math.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace tidalcrust {
namespace {

constexpr std::size_t lanes = 8;    ///< particles per SIMD vector (one AVX-512 register of doubles)
constexpr int key_bits = 21;        ///< Morton key bits per axis (63-bit keys)
constexpr int deepest_level = key_bits - 1;

/// 21 bits of v spread to every third bit (bit k of v goes to bit 3k).
std::uint64_t spread_bits(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

/// Which of the 8 children of a node at `level` (0: the root) a key falls in.
unsigned octant(std::uint64_t key, int level) { return static_cast<unsigned>(key >> (3 * (deepest_level - level))) & 7u; }

// Vectors of `lanes` doubles (V) and 2 * lanes floats (F), in two kinds with the same interface
// (a struct of static functions plus free operators, fma, rsqrt and keep_lanes):
// * PlainMath: plain loops, lane by lane, with IEEE + and * only (fma(a, b, c) is a * b + c, two
//   roundings, as the project compiles with -ffp-contract=off; rsqrt an integer guess and Newton
//   steps): the same bits in every x86-64 build, whatever the compiler vectorises them with. The
//   portable kernel (GravityKernel::portable), and the fast one without AVX-512. Always inlined:
//   GCC 12 left some of them calls, which made the portable step 1.8x as long.
// * Avx512Math: AVX-512 intrinsics, explicit FMAs and the 14-bit reciprocal square root
//   estimate refined by Newton steps; deterministic, but its last bits differ from PlainMath's.
template <class T, std::size_t N>
struct Lanes {
  T v[N];
};
#define TIDALCRUST_LANEWISE(op)                                        \
  template <class T, std::size_t N>                                    \
  [[gnu::always_inline]] inline Lanes<T, N> operator op(Lanes<T, N> a, Lanes<T, N> b) {        \
    for (std::size_t l = 0; l < N; ++l) a.v[l] = a.v[l] op b.v[l];      \
    return a;                                                          \
  }
TIDALCRUST_LANEWISE(+)
TIDALCRUST_LANEWISE(-)
TIDALCRUST_LANEWISE(*)
#undef TIDALCRUST_LANEWISE
template <class T, std::size_t N>
[[gnu::always_inline]] inline Lanes<T, N> fma(Lanes<T, N> a, Lanes<T, N> b, Lanes<T, N> c) {
  return a * b + c;
}
/// 1/sqrt(s) lane by lane: portable_math::inverse_sqrt (an integer guess and Newton steps; the
/// same bits on every CPU, and cheaper than a correctly rounded sqrt and division).
template <class T, std::size_t N>
[[gnu::always_inline]] inline Lanes<T, N> rsqrt(Lanes<T, N> s) {
  for (std::size_t l = 0; l < N; ++l) s.v[l] = portable_math::inverse_sqrt(s.v[l]);
  return s;
}
template <class T, std::size_t N>
[[gnu::always_inline]] inline Lanes<T, N> keep_lanes(Lanes<T, N> a, unsigned keep) {
  for (std::size_t l = 0; l < N; ++l)
    if (!((keep >> l) & 1u)) a.v[l] = T(0);
  return a;
}

struct PlainMath {
  using V = Lanes<double, lanes>;
  using F = Lanes<float, 2 * lanes>;
  static V splat(double a) {
    V r;
    for (double& x : r.v) x = a;
    return r;
  }
  static V load(const double* p) {
    V r;
    for (std::size_t l = 0; l < lanes; ++l) r.v[l] = p[l];
    return r;
  }
  static void store(double* p, V a) {
    for (std::size_t l = 0; l < lanes; ++l) p[l] = a.v[l];
  }
  static F splat_f(float a) {
    F r;
    for (float& x : r.v) x = a;
    return r;
  }
  static F load_f(const float* p) {
    F r;
    for (std::size_t l = 0; l < 2 * lanes; ++l) r.v[l] = p[l];
    return r;
  }
  /// The first (half 0) or last (half 1) `lanes` floats of a, widened to doubles.
  static V widen(F a, int half) {
    V r;
    for (std::size_t l = 0; l < lanes; ++l) r.v[l] = static_cast<double>(a.v[static_cast<std::size_t>(half) * lanes + l]);
    return r;
  }
};

#if defined(__AVX512F__)
struct Vd {
  __m512d v;
};
inline Vd operator+(Vd a, Vd b) { return {_mm512_add_pd(a.v, b.v)}; }
inline Vd operator-(Vd a, Vd b) { return {_mm512_sub_pd(a.v, b.v)}; }
inline Vd operator*(Vd a, Vd b) { return {_mm512_mul_pd(a.v, b.v)}; }
/// a * b + c
inline Vd fma(Vd a, Vd b, Vd c) { return {_mm512_fmadd_pd(a.v, b.v, c.v)}; }
/// 1/sqrt(s): the 14-bit hardware estimate and two Newton steps (~1 ulp), as DirectGravity.
inline Vd rsqrt(Vd s) {
  const __m512d three_halves = _mm512_set1_pd(1.5);
  const __m512d half_s = _mm512_mul_pd(_mm512_set1_pd(0.5), s.v);
  __m512d y = _mm512_maskz_rsqrt14_pd(0xFF, s.v);
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(half_s, _mm512_mul_pd(y, y), three_halves));
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(half_s, _mm512_mul_pd(y, y), three_halves));
  return {y};
}
/// a with the lanes whose bit in `keep` is 0 set to zero.
inline Vd keep_lanes(Vd a, unsigned keep) { return {_mm512_maskz_mov_pd(static_cast<__mmask8>(keep), a.v)}; }

// The near field of a whole group: single precision, on positions relative to the group's first
// particle (so the differences keep ~1e-7 relative accuracy), summed in float and added to the
// double far field at the end.
struct Vf {
  __m512 v;
};
inline Vf operator+(Vf a, Vf b) { return {_mm512_add_ps(a.v, b.v)}; }
inline Vf operator-(Vf a, Vf b) { return {_mm512_sub_ps(a.v, b.v)}; }
inline Vf operator*(Vf a, Vf b) { return {_mm512_mul_ps(a.v, b.v)}; }
inline Vf fma(Vf a, Vf b, Vf c) { return {_mm512_fmadd_ps(a.v, b.v, c.v)}; }
/// 1/sqrt(s): the 14-bit estimate and one Newton step (~1 float ulp).
inline Vf rsqrt(Vf s) {
  const __m512 y = _mm512_maskz_rsqrt14_ps(0xFFFF, s.v);  // maskz: no GCC 12 false warning
  const __m512 half_s = _mm512_mul_ps(_mm512_set1_ps(0.5f), s.v);
  return {_mm512_mul_ps(y, _mm512_fnmadd_ps(half_s, _mm512_mul_ps(y, y), _mm512_set1_ps(1.5f)))};
}
inline Vf keep_lanes(Vf a, unsigned keep) { return {_mm512_maskz_mov_ps(static_cast<__mmask16>(keep), a.v)}; }

struct Avx512Math {
  using V = Vd;
  using F = Vf;
  static V splat(double a) { return {_mm512_set1_pd(a)}; }
  static V load(const double* p) { return {_mm512_loadu_pd(p)}; }
  static void store(double* p, V a) { _mm512_storeu_pd(p, a.v); }
  static F splat_f(float a) { return {_mm512_set1_ps(a)}; }
  static F load_f(const float* p) { return {_mm512_loadu_ps(p)}; }
  /// The first (half 0) or last (half 1) `lanes` floats of a, widened to doubles.
  static V widen(F a, int half) {
    alignas(64) float b[2 * lanes];  // through memory: the 256-bit casts trip GCC 12's warnings
    _mm512_store_ps(b, a.v);
    return {_mm512_maskz_cvtps_pd(0xFF, _mm256_load_ps(b + half * lanes))};
  }
};
using FastMath = Avx512Math;
#else
using FastMath = PlainMath;  // without AVX-512 the fast kernel is the portable code
#endif

/// Lanes of the vector of particles [first, first + lanes) other than particle j (self-pair).
inline unsigned all_but_self(std::uint32_t first, std::uint32_t j) {
  return j >= first && j < first + lanes ? 0xFFu & ~(1u << (j - first)) : 0xFFu;
}

/// Lanes of the group's 2 * lanes particles [first, first + 2 lanes) other than particle j.
inline unsigned all_but_self_group(std::uint32_t first, std::uint32_t j) {
  return j >= first && j < first + 2 * lanes ? 0xFFFFu & ~(1u << (j - first)) : 0xFFFFu;
}

/// Positions of the group's particles [first, first + lanes) (Morton order), the last valid one
/// repeated into lanes past `end` (their results are not used).
template <class M>
struct Targets {
  using V = typename M::V;
  V x, y, z;
  Targets(const double* xs, const double* ys, const double* zs, std::uint32_t first, std::uint32_t end) {
    alignas(64) double bx[lanes], by[lanes], bz[lanes];
    for (std::size_t l = 0; l < lanes; ++l) {
      const std::size_t k = std::min<std::size_t>(first + l, end - 1);
      bx[l] = xs[k], by[l] = ys[k], bz[l] = zs[k];
    }
    x = M::load(bx), y = M::load(by), z = M::load(bz);
  }
};

/// What a cell's pull and potential share at the targets t (TreeGravity::Expansion e): r = x - c,
/// y = 1/s (s^2 = r^2 + eps^2), y2 = y^2, v = 3 S r - (3/2) t, U' = (15/2) U (U_i = O_ijk r_j r_k),
/// P' = r.U' and w = (15/2) (t.r - r.S.r). Inlined by force: a call per cell spills it all.
template <class M>
struct CellTerms {
  using V = typename M::V;
  V rx, ry, rz, y, y2, vx, vy, vz, ux, uy, uz, p, w;
  template <class Expansion>
  [[gnu::always_inline]] CellTerms(const Expansion& e, const Targets<M>& t, V e2)
      : rx(t.x - M::splat(e.com[0])), ry(t.y - M::splat(e.com[1])), rz(t.z - M::splat(e.com[2])) {
    y = rsqrt(fma(rz, rz, fma(ry, ry, fma(rx, rx, e2))));
    y2 = y * y;
    const double* s = e.s3;  // 3 S: xx, xy, xz, yy, yz, zz
    vx = fma(M::splat(s[2]), rz, fma(M::splat(s[1]), ry, fma(M::splat(s[0]), rx, M::splat(e.mt15[0]))));
    vy = fma(M::splat(s[4]), rz, fma(M::splat(s[3]), ry, fma(M::splat(s[1]), rx, M::splat(e.mt15[1]))));
    vz = fma(M::splat(s[5]), rz, fma(M::splat(s[4]), ry, fma(M::splat(s[2]), rx, M::splat(e.mt15[2]))));
    // r.v + r.(-(3/2) t) = 3 r.S.r - 3 t.r
    const V qt = fma(rz, vz, fma(ry, vy, fma(rx, vx, fma(rz, M::splat(e.mt15[2]), fma(ry, M::splat(e.mt15[1]), rx * M::splat(e.mt15[0]))))));
    w = M::splat(-2.5) * qt;
    const V xx = rx * rx, yy = ry * ry, zz = rz * rz, xy = rx * ry, xz = rx * rz, yz = ry * rz;
    const double* o = e.u;  // per component, the coefficients of xx, yy, zz, xy, xz, yz
    ux = fma(M::splat(o[5]), yz, fma(M::splat(o[4]), xz, fma(M::splat(o[3]), xy, fma(M::splat(o[2]), zz, fma(M::splat(o[1]), yy, M::splat(o[0]) * xx)))));
    uy = fma(M::splat(o[11]), yz, fma(M::splat(o[10]), xz, fma(M::splat(o[9]), xy, fma(M::splat(o[8]), zz, fma(M::splat(o[7]), yy, M::splat(o[6]) * xx)))));
    uz = fma(M::splat(o[17]), yz, fma(M::splat(o[16]), xz, fma(M::splat(o[15]), xy, fma(M::splat(o[14]), zz, fma(M::splat(o[13]), yy, M::splat(o[12]) * xx)))));
    p = fma(rz, uz, fma(ry, uy, rx * ux));
  }
};

}  // namespace

ForceErrorStats relative_force_errors(const std::vector<double>& a, const std::vector<double>& reference) {
  std::vector<double> error;
  const std::size_t n = std::min(a.size(), reference.size()) / 3;
  for (std::size_t i = 0; i < n; ++i) {
    double d2 = 0, r2 = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double d = a[3 * i + k] - reference[3 * i + k];
      d2 += d * d;
      r2 += reference[3 * i + k] * reference[3 * i + k];
    }
    if (r2 > 0) error.push_back(std::sqrt(d2 / r2));
  }
  ForceErrorStats stats;
  stats.particles = error.size();
  if (error.empty()) return stats;
  std::sort(error.begin(), error.end());
  stats.median = error[error.size() / 2];
  stats.p99 = error[std::min(error.size() - 1, error.size() * 99 / 100)];
  stats.max = error.back();
  return stats;
}

double opening_angle_for(double force_error, bool portable) {
  return std::clamp(3.0 * portable_math::pow(force_error, 2.0 / 9.0, portable), 0.1, 0.7);
}

TreeGravity::TreeGravity(const std::vector<double>& mass, double softening, double force_error, GravityKernel kernel)
    : kernel_(kernel),
      count_(mass.size()),
      eps2_(softening * softening),
      theta_(opening_angle_for(force_error, uses_portable_math(kernel))),
      theta_quadrupole_(portable_math::pow(theta_, 5.0 / 3.0, uses_portable_math(kernel))),
      mass_(mass),
      key_(mass.size()),
      order_(mass.size()),
      x_(mass.size()),
      y_(mass.size()),
      z_(mass.size()),
      m_(mass.size()),
      acceleration_(3 * mass.size(), 0.0) {}

std::uint32_t TreeGravity::build_node(std::uint32_t begin, std::uint32_t end, int level) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  const bool leaf = end - begin <= leaf_capacity || level > deepest_level;
  Node node{};  // moments: compute_moments()
  node.begin = begin, node.end = end, node.leaf = leaf;
  nodes_.push_back(node);
  block_of_.push_back(leaf ? 0 : static_cast<std::uint32_t>(block_valid_.size()));
  if (!leaf) block_valid_.push_back(0), block_leaf_.push_back(0);
  if (!leaf) {
    for (std::uint32_t b = begin; b < end;) {
      const unsigned o = octant(key_[b], level);
      std::uint32_t e = b + 1;
      while (e < end && octant(key_[e], level) == o) ++e;
      build_node(b, e, level + 1);
      b = e;
    }
  }
  nodes_[index].next = static_cast<std::uint32_t>(nodes_.size());
  return index;
}

namespace {
/// node.com = (mx, my, mz) / mass; a node of massless particles only (no pull) takes its first
/// particle's position (x0, y0, z0) as centre.
template <class TreeNode>
void set_centre_of_mass(TreeNode& node, double mass, double mx, double my, double mz, double x0, double y0,
                        double z0) {
  if (mass > 0) {
    node.com[0] = mx / mass, node.com[1] = my / mass, node.com[2] = mz / mass;
  } else {
    node.com[0] = x0, node.com[1] = y0, node.com[2] = z0;
  }
}
}  // namespace

void TreeGravity::compute_moments(std::size_t index) {
  Node& node = nodes_[index];
  double mass = 0, mx = 0, my = 0, mz = 0;
  for (std::uint32_t k = node.begin; k < node.end; ++k) {
    mass += m_[k];
    mx += m_[k] * x_[k];
    my += m_[k] * y_[k];
    mz += m_[k] * z_[k];
  }
  set_centre_of_mass(node, mass, mx, my, mz, x_[node.begin], y_[node.begin], z_[node.begin]);
  Moments& mo = moments_[index];
  mo = Moments{mass, {0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0}};
  double* s = mo.s;
  double* o = mo.o;
  double bmax2 = 0;
  for (std::uint32_t k = node.begin; k < node.end; ++k) {
    const double d[3] = {x_[k] - node.com[0], y_[k] - node.com[1], z_[k] - node.com[2]};
    const double m = m_[k];
    s[0] += m * d[0] * d[0];
    s[1] += m * d[0] * d[1];
    s[2] += m * d[0] * d[2];
    s[3] += m * d[1] * d[1];
    s[4] += m * d[1] * d[2];
    s[5] += m * d[2] * d[2];
    std::size_t c = 0;  // i <= j <= l: xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz, zzz
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = i; j < 3; ++j)
        for (std::size_t l = j; l < 3; ++l) o[c++] += m * d[i] * d[j] * d[l];
    bmax2 = std::max(bmax2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  node.bmax2 = bmax2;
}

void TreeGravity::combine_moments(std::size_t index) {
  // Children in pre-order: index + 1, then each one's `next`, up to this node's `next`.
  Node& node = nodes_[index];
  double mass = 0, mx = 0, my = 0, mz = 0;
  for (std::uint32_t c = static_cast<std::uint32_t>(index) + 1; c < node.next; c = nodes_[c].next) {
    const double mc = moments_[c].mass;
    mass += mc;
    mx += mc * nodes_[c].com[0];
    my += mc * nodes_[c].com[1];
    mz += mc * nodes_[c].com[2];
  }
  set_centre_of_mass(node, mass, mx, my, mz, x_[node.begin], y_[node.begin], z_[node.begin]);
  // Shifted to this node's centre (the children's first moments about their own centres vanish):
  // S = sum_c S_c + m_c d d^T, O_ijk = sum_c O_c,ijk + (S_c,ij d_k + S_c,ik d_j + S_c,jk d_i)
  // + m_c d_i d_j d_k, d = c_c - c.
  Moments& mo = moments_[index];
  mo = Moments{mass, {0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0}};
  constexpr int sym[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};  // S_ij -> its index in s[6]
  for (std::uint32_t c = static_cast<std::uint32_t>(index) + 1; c < node.next; c = nodes_[c].next) {
    const Moments& mc = moments_[c];
    const double d[3] = {nodes_[c].com[0] - node.com[0], nodes_[c].com[1] - node.com[1], nodes_[c].com[2] - node.com[2]};
    const double m = mc.mass;
    std::size_t q = 0;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = i; j < 3; ++j, ++q) mo.s[q] += mc.s[q] + m * d[i] * d[j];
    q = 0;
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = i; j < 3; ++j)
        for (std::size_t l = j; l < 3; ++l, ++q)
          mo.o[q] += mc.o[q] + (mc.s[sym[i][j]] * d[l] + mc.s[sym[i][l]] * d[j] + mc.s[sym[j][l]] * d[i]) +
                     m * d[i] * d[j] * d[l];
  }
  // b_max exactly, from the particles (the children's bound |d| + b_max,c would open more cells
  // than the calibration assumes).
  double bmax2 = 0;
  for (std::uint32_t k = node.begin; k < node.end; ++k) {
    const double dx = x_[k] - node.com[0], dy = y_[k] - node.com[1], dz = z_[k] - node.com[2];
    bmax2 = std::max(bmax2, dx * dx + dy * dy + dz * dz);
  }
  node.bmax2 = bmax2;
}

void TreeGravity::finish_expansion(std::size_t index) {
  const Node& node = nodes_[index];
  const double* s = moments_[index].s;
  const double* o = moments_[index].o;
  Expansion& e = expansion_[index];
  std::copy(node.com, node.com + 3, e.com);
  e.neg_mass = -moments_[index].mass;
  e.t15 = 1.5 * (s[0] + s[3] + s[5]);
  for (std::size_t k = 0; k < 6; ++k) e.s3[k] = 3.0 * s[k];
  e.mt15[0] = -1.5 * (o[0] + o[3] + o[5]);  // xxx + xyy + xzz
  e.mt15[1] = -1.5 * (o[1] + o[6] + o[8]);  // xxy + yyy + yzz
  e.mt15[2] = -1.5 * (o[2] + o[7] + o[9]);  // xxz + yyz + zzz
  // U_i = O_ijk r_j r_k: the O entries of r_x^2, r_y^2, r_z^2, 2 r_x r_y, 2 r_x r_z, 2 r_y r_z
  constexpr int of_u[3][6] = {{0, 3, 5, 1, 2, 4}, {1, 6, 8, 3, 4, 7}, {2, 7, 9, 4, 5, 8}};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t k = 0; k < 6; ++k) e.u[6 * i + k] = (k < 3 ? 7.5 : 15.0) * o[of_u[i][k]];
  ExpansionF& f = expansion_f_[index];  // each coefficient rounded once from the double one
  f.neg_mass = static_cast<float>(e.neg_mass);
  f.t15 = static_cast<float>(e.t15);
  for (std::size_t k = 0; k < 6; ++k) f.s3[k] = static_cast<float>(e.s3[k]);
  for (std::size_t k = 0; k < 3; ++k) f.mt15[k] = static_cast<float>(e.mt15[k]);
  for (std::size_t k = 0; k < 18; ++k) f.u[k] = static_cast<float>(e.u[k]);
}

void TreeGravity::prepare(const double* position) {
  const std::size_t n = count_;
  nodes_.clear();
  groups_.clear();
  block_of_.clear();
  block_valid_.clear();
  block_leaf_.clear();
  task_roots_.clear();
  top_nodes_.clear();
  if (n == 0) return;
  double lo[3], hi[3];
  for (std::size_t k = 0; k < 3; ++k) lo[k] = hi[k] = position[k];
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], position[3 * i + k]);
      hi[k] = std::max(hi[k], position[3 * i + k]);
    }
  const double side = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double cells = static_cast<double>(1u << key_bits);
  const double scale = side > 0 && std::isfinite(side) ? cells / side : 0.0;
  const auto quantize = [&](double x, std::size_t k) {
    const double q = (x - lo[k]) * scale;  // NaN positions go to cell 0; the forces show them
    return q >= cells - 1 ? static_cast<std::uint64_t>(cells - 1) : q > 0 ? static_cast<std::uint64_t>(q) : 0;
  };
  std::vector<Keyed>& keyed = keyed_;
  keyed.resize(n);
  // On one thread: the per-particle loops are memory-light (~0.5 ms at N ~ 60,000), and every
  // parallel loop ends in a barrier where a thread paused by the OS holds up the others.
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = position + 3 * i;
    keyed[i] = {spread_bits(quantize(p[0], 0)) << 2 | spread_bits(quantize(p[1], 1)) << 1 | spread_bits(quantize(p[2], 2)),
                static_cast<std::uint32_t>(i)};
  }
  // By key, ties by index: a total order, so the same sequence from any correct sort. Between
  // force passes the particles move little and the last pass's order is nearly sorted: an
  // insertion sort from it does in ~0.1 ms what the radix sort below needs ~2 ms for, and gives
  // the same sequence. It gives up after 8 moves per particle on average (a body torn apart).
  sorted_.resize(n);
  bool sorted = false;
  if (have_order_) {
    for (std::size_t k = 0; k < n; ++k) sorted_[k] = keyed[order_[k]];
    const auto before = [](const Keyed& a, const Keyed& b) { return a.key < b.key || (a.key == b.key && a.index < b.index); };
    std::size_t budget = 8 * n;
    sorted = true;
    for (std::size_t k = 1; k < n && sorted; ++k) {
      const Keyed item = sorted_[k];
      std::size_t at = k;
      for (; at > 0 && before(item, sorted_[at - 1]); --at) sorted_[at] = sorted_[at - 1];
      sorted_[at] = item;
      if (k - at > budget) sorted = false;
      budget -= std::min(budget, k - at);
    }
    if (sorted) keyed.swap(sorted_);
  }
  sorted_from_previous_order_ = sorted;
  // Otherwise from the index order (the first pass, or after giving up): a stable
  // least-significant-digit radix sort, 11 bits a pass, keeps the index order of equal keys and is
  // several times faster than a comparison sort at large N; passes whose digit is the same for
  // every particle are skipped.
  constexpr int digit_bits = 11;
  constexpr std::size_t buckets = std::size_t{1} << digit_bits;
  std::vector<std::uint32_t> count(buckets);
  for (int shift = 0; !sorted && shift < 3 * key_bits; shift += digit_bits) {
    std::fill(count.begin(), count.end(), 0u);
    for (const Keyed& k : keyed) ++count[(k.key >> shift) & (buckets - 1)];
    if (*std::max_element(count.begin(), count.end()) == n) continue;
    std::uint32_t start = 0;  // count -> first slot of each digit
    for (std::uint32_t& c : count) {
      const std::uint32_t size = c;
      c = start;
      start += size;
    }
    for (const Keyed& k : keyed) sorted_[count[(k.key >> shift) & (buckets - 1)]++] = k;
    keyed.swap(sorted_);
  }
  have_order_ = true;
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t i = keyed[k].index;
    key_[k] = keyed[k].key;
    order_[k] = i;
    x_[k] = position[3 * i], y_[k] = position[3 * i + 1], z_[k] = position[3 * i + 2];
    m_[k] = mass_[i];
  }
  build_node(0, static_cast<std::uint32_t>(n), 0);
  for (std::size_t b = 0; b < n; b += group_size)
    groups_.push_back(Group{static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(std::min(n, b + group_size)), {}, {}});
  const std::size_t node_total = nodes_.size();
  expansion_.resize(node_total);
  expansion_f_.resize(node_total);
  moments_.resize(node_total);
  // The moment tasks: subtrees of at most 1/64 of the particles (or leaves), found in
  // pre-order; the nodes above them are few (~100) and run in finish_build().
  const std::size_t task_particles = std::max<std::size_t>(leaf_capacity, n / 64);
  for (std::uint32_t i = 0; i < node_total;) {
    if (nodes_[i].leaf || nodes_[i].end - nodes_[i].begin <= task_particles) {
      task_roots_.push_back(i);
      i = nodes_[i].next;
    } else {
      top_nodes_.push_back(i++);
    }
  }
}

void TreeGravity::moment_task(std::size_t task) {
  const std::uint32_t root = task_roots_[task];
  // Reverse pre-order: every node after its children (a node's subtree follows it).
  for (std::uint32_t i = nodes_[root].next; i-- > root;) {
    if (nodes_[i].leaf) compute_moments(i);
    else combine_moments(i);
    finish_expansion(i);
  }
  // The groups that start in this subtree (each group starts in exactly one).
  const std::size_t first = (nodes_[root].begin + group_size - 1) / group_size;
  const std::size_t end = (nodes_[root].end + group_size - 1) / group_size;
  for (std::size_t gi = first; gi < end; ++gi) {
    Group& g = groups_[gi];
    for (std::size_t k = 0; k < 3; ++k) g.lo[k] = std::numeric_limits<double>::infinity(), g.hi[k] = -g.lo[k];
    for (std::uint32_t k = g.begin; k < g.end; ++k) {
      const double p[3] = {x_[k], y_[k], z_[k]};
      for (std::size_t a = 0; a < 3; ++a) g.lo[a] = std::min(g.lo[a], p[a]), g.hi[a] = std::max(g.hi[a], p[a]);
    }
  }
}

void TreeGravity::finish_build() {
  if (count_ == 0) return;
  for (std::size_t k = top_nodes_.size(); k-- > 0;) {
    combine_moments(top_nodes_[k]);
    finish_expansion(top_nodes_[k]);
  }
  child_blocks();
}

void TreeGravity::build(const double* position) {
  prepare(position);
  const std::size_t tasks = moment_task_count();
  // One dynamic loop, no barrier per tree level: a task's nodes only read nodes of the same task.
#pragma omp parallel for schedule(dynamic, 1) if (count_ >= 4096)
  for (std::size_t t = 0; t < tasks; ++t) moment_task(t);
  finish_build();
}

void TreeGravity::child_blocks() {
  const std::size_t slots = lanes * block_valid_.size();
  walk_x_.assign(slots, 0.0), walk_y_.assign(slots, 0.0), walk_z_.assign(slots, 0.0);
  walk_bmax2_.assign(slots, 0.0);
  walk_node_.assign(slots, 0), walk_block_.assign(slots, 0);
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].leaf) continue;
    const std::uint32_t b = block_of_[i];
    unsigned l = 0;  // an octree node has at most 8 children, one per octant
    for (std::uint32_t c = static_cast<std::uint32_t>(i) + 1; c < nodes_[i].next; c = nodes_[c].next, ++l) {
      const std::size_t slot = lanes * b + l;
      walk_x_[slot] = nodes_[c].com[0], walk_y_[slot] = nodes_[c].com[1], walk_z_[slot] = nodes_[c].com[2];
      walk_bmax2_[slot] = nodes_[c].bmax2;
      walk_node_[slot] = c;
      walk_block_[slot] = block_of_[c];
      block_valid_[b] |= static_cast<std::uint8_t>(1u << l);
      if (nodes_[c].leaf) block_leaf_[b] |= static_cast<std::uint8_t>(1u << l);
    }
  }
}

void TreeGravity::interaction_list(const Group& g, InteractionList& list) const {
  list.cell_count = 0;
  list.quadrupole_count = 0;
  list.ranges.clear();
  std::uint32_t* cells = list.cells.get();
  std::uint32_t* quadrupole_cells = list.quadrupole_cells.get();
  std::vector<std::uint32_t>& ranges = list.ranges;
  if (nodes_[0].leaf) {  // the root holds the group's particles: never accepted
    ranges.push_back(nodes_[0].begin), ranges.push_back(nodes_[0].end);
    return;
  }
  const double theta2 = theta_ * theta_, quadrupole2 = theta_quadrupole_ * theta_quadrupole_;
  // Breadth first over child blocks, in a queue: the next block to test is already known while
  // this one's test runs, so the tests overlap (depth first, each pop waited for the last push).
  std::uint32_t* queue = list.queue.get();
  std::size_t head = 0, tail = 0, count = 0, quadrupole_count = 0;
  queue[tail++] = block_of_[0];
  while (head < tail) {
    const std::uint32_t b = queue[head++];
    const std::size_t first = lanes * b;
    // A child is accepted when b_max^2 < theta^2 d^2, d the distance from its centre to the
    // group's box, d^2 = (dx^2 + dy^2) + dz^2 (the same operations in both paths, no FMA: the
    // same decisions). A child holding a particle of the group never passes: that particle lies
    // in the box, so d <= b_max, and theta < 1.
#if defined(__AVX512F__) && defined(__AVX512VL__)
    const __m512d zero = _mm512_setzero_pd();
    __m512d d2 = zero;
    const double* centre[3] = {walk_x_.data() + first, walk_y_.data() + first, walk_z_.data() + first};
    for (std::size_t k = 0; k < 3; ++k) {
      const __m512d c = _mm512_loadu_pd(centre[k]);
      // maskz: GCC 12 warns about the plain max's undefined pass-through operand
      const __m512d d = _mm512_maskz_max_pd(0xFF, _mm512_maskz_max_pd(0xFF, _mm512_sub_pd(_mm512_set1_pd(g.lo[k]), c),
                                                                     _mm512_sub_pd(c, _mm512_set1_pd(g.hi[k]))),
                                            zero);
      d2 = k == 0 ? _mm512_mul_pd(d, d) : _mm512_add_pd(d2, _mm512_mul_pd(d, d));
    }
    const __m512d bmax2 = _mm512_loadu_pd(walk_bmax2_.data() + first);
    const unsigned accepted =
        block_valid_[b] & _mm512_cmp_pd_mask(bmax2, _mm512_mul_pd(_mm512_set1_pd(theta2), d2), _CMP_LT_OQ);
    const unsigned quadrupole =
        accepted & _mm512_cmp_pd_mask(bmax2, _mm512_mul_pd(_mm512_set1_pd(quadrupole2), d2), _CMP_LT_OQ);
    const unsigned octupole = accepted & ~quadrupole;
    const unsigned opened = block_valid_[b] & ~accepted;
    const unsigned inner = opened & ~block_leaf_[b];
    // Compressed in a register and stored whole (a compressing store to memory is slow): the
    // lanes past the count are scratch, overwritten by the next store (8 slots of slack).
    const __m256i children = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(walk_node_.data() + first));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(cells + count),
                        _mm256_maskz_compress_epi32(static_cast<__mmask8>(octupole), children));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(quadrupole_cells + quadrupole_count),
                        _mm256_maskz_compress_epi32(static_cast<__mmask8>(quadrupole), children));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(queue + tail),
                        _mm256_maskz_compress_epi32(static_cast<__mmask8>(inner),
                                                    _mm256_loadu_si256(reinterpret_cast<const __m256i*>(walk_block_.data() + first))));
    count += static_cast<std::size_t>(__builtin_popcount(octupole));
    quadrupole_count += static_cast<std::size_t>(__builtin_popcount(quadrupole));
    tail += static_cast<std::size_t>(__builtin_popcount(inner));
#else
    unsigned accepted = 0, quadrupole = 0;
    for (unsigned l = 0; l < lanes; ++l) {
      if (!((block_valid_[b] >> l) & 1u)) continue;
      const double c[3] = {walk_x_[first + l], walk_y_[first + l], walk_z_[first + l]};
      double d2 = 0;
      for (std::size_t k = 0; k < 3; ++k) {
        const double d = std::max(std::max(g.lo[k] - c[k], c[k] - g.hi[k]), 0.0);
        d2 = k == 0 ? d * d : d2 + d * d;
      }
      if (walk_bmax2_[first + l] < theta2 * d2) accepted |= 1u << l;
      if (walk_bmax2_[first + l] < quadrupole2 * d2) quadrupole |= 1u << l;
    }
    quadrupole &= accepted;
    const unsigned octupole = accepted & ~quadrupole;
    const unsigned opened = block_valid_[b] & ~accepted;
    const unsigned inner = opened & ~block_leaf_[b];
    for (unsigned l = 0; l < lanes; ++l) {
      if ((octupole >> l) & 1u) cells[count++] = walk_node_[first + l];
      if ((quadrupole >> l) & 1u) quadrupole_cells[quadrupole_count++] = walk_node_[first + l];
      if ((inner >> l) & 1u) queue[tail++] = walk_block_[first + l];
    }
#endif
    for (unsigned leaves = opened & block_leaf_[b]; leaves != 0; leaves &= leaves - 1) {
      const Node& leaf = nodes_[walk_node_[first + static_cast<unsigned>(__builtin_ctz(leaves))]];
      if (!ranges.empty() && ranges.back() == leaf.begin)
        ranges.back() = leaf.end;  // contiguous leaves make one longer range
      else
        ranges.push_back(leaf.begin), ranges.push_back(leaf.end);
    }
  }
  list.cell_count = count;
  list.quadrupole_count = quadrupole_count;
}

namespace {

/// Cells summed in single precision between two widenings to double: bounds the float
/// accumulators' rounding to ~64 terms (a few 1e-7 relative) whatever the list's length.
constexpr std::size_t cells_per_block = 64;

/// Adds the pull of the cells (TreeGravity::Node for the centre, TreeGravity::ExpansionF, in
/// list order) at the group's 2 * lanes targets to a0 (targets 0..7) and a1 (8..15), in single
/// precision: t holds the targets relative to the group's first particle o, each cell's centre
/// is taken relative to o in double and rounded once, so r = x - c keeps ~1e-7 relative
/// accuracy. The float sums of each block of cells_per_block cells are widened and added in
/// double. To octupole order:
///   a = y^3 (-M + y^2 ((3/2) tr S + y^2 (w - (7/3) P' y^2))) r + y^5 (v + y^2 U'),
/// to quadrupole order (Octupole false; O = 0, so t = U' = P' = 0): v = 3 S r, w = -(5/2) r.v,
///   a = y^3 (-M + y^2 ((3/2) tr S + y^2 w)) r + y^5 v.
template <class M, bool Octupole, class Node, class ExpansionF>
[[gnu::always_inline]] inline void sum_cells_f(const std::uint32_t* cells, std::size_t count, const Node* nodes,
                                               const ExpansionF* expansion, const double* o, typename M::F tx,
                                               typename M::F ty, typename M::F tz, typename M::F e2,
                                               typename M::V* a0, typename M::V* a1) {
  using F = typename M::F;
  const F minus_seven_thirds = M::splat_f(-7.0f / 3.0f), minus_five_halves = M::splat_f(-2.5f);
  const F zero = M::splat_f(0.0f);
  for (std::size_t block = 0; block < count; block += cells_per_block) {
    F ax = zero, ay = zero, az = zero;
    const std::size_t block_end = std::min(count, block + cells_per_block);
    for (std::size_t n = block; n < block_end; ++n) {
      const std::uint32_t c = cells[n];
      const double* com = nodes[c].com;
      const ExpansionF& e = expansion[c];
      const F rx = tx - M::splat_f(static_cast<float>(com[0] - o[0])), ry = ty - M::splat_f(static_cast<float>(com[1] - o[1])),
              rz = tz - M::splat_f(static_cast<float>(com[2] - o[2]));
      const F y = rsqrt(fma(rz, rz, fma(ry, ry, fma(rx, rx, e2)))), y2 = y * y;
      const float* s = e.s3;  // 3 S: xx, xy, xz, yy, yz, zz
      if constexpr (!Octupole) {
        const F vx = fma(M::splat_f(s[2]), rz, fma(M::splat_f(s[1]), ry, M::splat_f(s[0]) * rx));
        const F vy = fma(M::splat_f(s[4]), rz, fma(M::splat_f(s[3]), ry, M::splat_f(s[1]) * rx));
        const F vz = fma(M::splat_f(s[5]), rz, fma(M::splat_f(s[4]), ry, M::splat_f(s[2]) * rx));
        const F w = minus_five_halves * fma(rz, vz, fma(ry, vy, rx * vx));
        const F y3 = y * y2, y5 = y3 * y2;
        const F radial = y3 * fma(y2, fma(y2, w, M::splat_f(e.t15)), M::splat_f(e.neg_mass));
        ax = fma(y5, vx, fma(radial, rx, ax));
        ay = fma(y5, vy, fma(radial, ry, ay));
        az = fma(y5, vz, fma(radial, rz, az));
        continue;
      }
      const F vx = fma(M::splat_f(s[2]), rz, fma(M::splat_f(s[1]), ry, fma(M::splat_f(s[0]), rx, M::splat_f(e.mt15[0]))));
      const F vy = fma(M::splat_f(s[4]), rz, fma(M::splat_f(s[3]), ry, fma(M::splat_f(s[1]), rx, M::splat_f(e.mt15[1]))));
      const F vz = fma(M::splat_f(s[5]), rz, fma(M::splat_f(s[4]), ry, fma(M::splat_f(s[2]), rx, M::splat_f(e.mt15[2]))));
      // r.v + r.(-(3/2) t) = 3 r.S.r - 3 t.r
      const F qt = fma(rz, vz, fma(ry, vy, fma(rx, vx, fma(rz, M::splat_f(e.mt15[2]), fma(ry, M::splat_f(e.mt15[1]), rx * M::splat_f(e.mt15[0]))))));
      const F w = minus_five_halves * qt;
      const F xx = rx * rx, yy = ry * ry, zz = rz * rz, xy = rx * ry, xz = rx * rz, yz = ry * rz;
      const float* u = e.u;  // per component, the coefficients of xx, yy, zz, xy, xz, yz
      const F ux = fma(M::splat_f(u[5]), yz, fma(M::splat_f(u[4]), xz, fma(M::splat_f(u[3]), xy, fma(M::splat_f(u[2]), zz, fma(M::splat_f(u[1]), yy, M::splat_f(u[0]) * xx)))));
      const F uy = fma(M::splat_f(u[11]), yz, fma(M::splat_f(u[10]), xz, fma(M::splat_f(u[9]), xy, fma(M::splat_f(u[8]), zz, fma(M::splat_f(u[7]), yy, M::splat_f(u[6]) * xx)))));
      const F uz = fma(M::splat_f(u[17]), yz, fma(M::splat_f(u[16]), xz, fma(M::splat_f(u[15]), xy, fma(M::splat_f(u[14]), zz, fma(M::splat_f(u[13]), yy, M::splat_f(u[12]) * xx)))));
      const F p = fma(rz, uz, fma(ry, uy, rx * ux));
      const F y3 = y * y2, y5 = y3 * y2;
      const F radial = y3 * fma(y2, fma(y2, fma(minus_seven_thirds * p, y2, w), M::splat_f(e.t15)), M::splat_f(e.neg_mass));
      ax = fma(y5, fma(y2, ux, vx), fma(radial, rx, ax));
      ay = fma(y5, fma(y2, uy, vy), fma(radial, ry, ay));
      az = fma(y5, fma(y2, uz, vz), fma(radial, rz, az));
    }
    a0[0] = a0[0] + M::widen(ax, 0), a0[1] = a0[1] + M::widen(ay, 0), a0[2] = a0[2] + M::widen(az, 0);
    a1[0] = a1[0] + M::widen(ax, 1), a1[1] = a1[1] + M::widen(ay, 1), a1[2] = a1[2] + M::widen(az, 1);
  }
}

}  // namespace

void TreeGravity::accumulate_chunk(std::size_t chunk) {
#if defined(__AVX512F__)
  if (kernel_ == GravityKernel::fast) return accumulate_chunk_with<FastMath>(chunk);
#endif
  accumulate_chunk_with<PlainMath>(chunk);
}

template <class M>
void TreeGravity::accumulate_chunk_with(std::size_t chunk) {
  using V = typename M::V;
  using F = typename M::F;
  InteractionList list(nodes_.size());
  const std::vector<std::uint32_t>& ranges = list.ranges;
  const F e2f = M::splat_f(static_cast<float>(eps2_));
  const auto store_accelerations = [&](std::uint32_t first, std::uint32_t end, const V* a) {
    alignas(64) double b[3][lanes];
    for (std::size_t k = 0; k < 3; ++k) M::store(b[k], a[k]);
    for (std::size_t l = 0; l < lanes && first + l < end; ++l)
      for (std::size_t k = 0; k < 3; ++k) acceleration_[3 * static_cast<std::size_t>(order_[first + l]) + k] = b[k][l];
  };
  const std::size_t last = std::min(groups_.size(), (chunk + 1) * groups_per_chunk);
  for (std::size_t gi = chunk * groups_per_chunk; gi < last; ++gi) {
    const Group& g = groups_[gi];
    interaction_list(g, list);
    // All 16 targets of the group in one float vector, about the group's first particle c (the
    // last valid particle repeated into lanes past its end; their results are not used): the far
    // field (cells, sum_cells_f) and then the near field (particles), both in single precision.
    static_assert(group_size == 2 * lanes);
    const std::uint32_t second = g.begin + lanes;
    const double c[3] = {x_[g.begin], y_[g.begin], z_[g.begin]};
    const double cx = c[0], cy = c[1], cz = c[2];
    alignas(64) float ox[2 * lanes], oy[2 * lanes], oz[2 * lanes];
    for (std::size_t l = 0; l < 2 * lanes; ++l) {
      const std::size_t k = std::min<std::size_t>(g.begin + l, g.end - 1);
      ox[l] = static_cast<float>(x_[k] - cx), oy[l] = static_cast<float>(y_[k] - cy), oz[l] = static_cast<float>(z_[k] - cz);
    }
    const F tx = M::load_f(ox), ty = M::load_f(oy), tz = M::load_f(oz);
    V a0[3], a1[3];
    for (std::size_t k = 0; k < 3; ++k) a0[k] = M::splat(0.0), a1[k] = a0[k];
    sum_cells_f<M, false>(list.quadrupole_cells.get(), list.quadrupole_count, nodes_.data(), expansion_f_.data(), c, tx,
                       ty, tz, e2f, a0, a1);
    sum_cells_f<M, true>(list.cells.get(), list.cell_count, nodes_.data(), expansion_f_.data(), c, tx, ty, tz, e2f, a0, a1);
    F ax = M::splat_f(0.0f), ay = ax, az = ax;
    for (std::size_t r = 0; r < ranges.size(); r += 2) {
      for (std::uint32_t j = ranges[r]; j < ranges[r + 1]; ++j) {
        const F dx = M::splat_f(static_cast<float>(x_[j] - cx)) - tx, dy = M::splat_f(static_cast<float>(y_[j] - cy)) - ty,
                dz = M::splat_f(static_cast<float>(z_[j] - cz)) - tz;
        const F y = rsqrt(fma(dz, dz, fma(dy, dy, fma(dx, dx, e2f))));
        const F f = keep_lanes(M::splat_f(static_cast<float>(m_[j])) * (y * y * y), all_but_self_group(g.begin, j));
        ax = fma(f, dx, ax), ay = fma(f, dy, ay), az = fma(f, dz, az);
      }
    }
    a0[0] = a0[0] + M::widen(ax, 0), a0[1] = a0[1] + M::widen(ay, 0), a0[2] = a0[2] + M::widen(az, 0);
    a1[0] = a1[0] + M::widen(ax, 1), a1[1] = a1[1] + M::widen(ay, 1), a1[2] = a1[2] + M::widen(az, 1);
    store_accelerations(g.begin, g.end, a0);
    store_accelerations(second, g.end, a1);
  }
}

double TreeGravity::covered_mass(std::size_t group) const {
  InteractionList list(nodes_.size());
  interaction_list(groups_.at(group), list);
  double mass = 0;
  for (std::size_t n = 0; n < list.cell_count; ++n) mass += moments_[list.cells[n]].mass;
  for (std::size_t n = 0; n < list.quadrupole_count; ++n) mass += moments_[list.quadrupole_cells[n]].mass;
  for (std::size_t r = 0; r < list.ranges.size(); r += 2)
    for (std::uint32_t j = list.ranges[r]; j < list.ranges[r + 1]; ++j) mass += m_[j];
  return mass;
}

void TreeGravity::accelerations(const double* position, double* acceleration, bool parallel) {
  prepare(position);
  const std::size_t tasks = moment_task_count();
  // Three barriers: after the moment tasks, after the top of the tree, at the end. Each chunk
  // writes its own particles' accelerations.
#pragma omp parallel if (parallel)
  {
#pragma omp for schedule(dynamic, 1)
    for (std::size_t t = 0; t < tasks; ++t) moment_task(t);
#pragma omp single
    finish_build();
    const std::size_t chunks = chunk_count();
#pragma omp for schedule(dynamic, 1)
    for (std::size_t c = 0; c < chunks; ++c) {
      accumulate_chunk(c);
      for (std::size_t k = chunk_begin(c); k < chunk_end(c); ++k) {
        const std::size_t i = order_[k];
        this->acceleration(i, acceleration + 3 * i);
      }
    }
  }
}

void TreeGravity::group_potential(const Group& g, InteractionList& list) {
#if defined(__AVX512F__)
  if (kernel_ == GravityKernel::fast) return group_potential_with<FastMath>(g, list);
#endif
  group_potential_with<PlainMath>(g, list);
}

template <class M>
void TreeGravity::group_potential_with(const Group& g, InteractionList& list) {
  using V = typename M::V;
  interaction_list(g, list);
  const std::vector<std::uint32_t>& ranges = list.ranges;
  const V e2 = M::splat(eps2_), minus_third = M::splat(-1.0 / 3.0), fifth = M::splat(0.2);
  for (std::uint32_t first = g.begin; first < g.end; first += lanes) {
    const Targets<M> t(x_.data(), y_.data(), z_.data(), first, g.end);
    V phi = M::splat(0.0);
    for (std::size_t n = 0; n < list.quadrupole_count; ++n) {
      const Expansion& e = expansion_[list.quadrupole_cells[n]];
      // To quadrupole order (as the forces): phi = y (-M + y^2 ((1/2) tr S + y^2 w/5)),
      // w = -(5/2) r.(3 S r)
      const V rx = t.x - M::splat(e.com[0]), ry = t.y - M::splat(e.com[1]), rz = t.z - M::splat(e.com[2]);
      const V y = rsqrt(fma(rz, rz, fma(ry, ry, fma(rx, rx, e2)))), y2 = y * y;
      const double* s = e.s3;
      const V vx = fma(M::splat(s[2]), rz, fma(M::splat(s[1]), ry, M::splat(s[0]) * rx));
      const V vy = fma(M::splat(s[4]), rz, fma(M::splat(s[3]), ry, M::splat(s[1]) * rx));
      const V vz = fma(M::splat(s[5]), rz, fma(M::splat(s[4]), ry, M::splat(s[2]) * rx));
      const V w = M::splat(-2.5) * fma(rz, vz, fma(ry, vy, rx * vx));
      phi = fma(y, fma(y2, fma(y2, fifth * w, M::splat(e.t15 / 3.0)), M::splat(e.neg_mass)), phi);
    }
    for (std::size_t n = 0; n < list.cell_count; ++n) {
      const Expansion& e = expansion_[list.cells[n]];
      const CellTerms<M> k(e, t, e2);
      // phi = y (-M + y^2 ((1/2) tr S + y^2 (w/5 - (1/3) P' y^2)))
      phi = fma(k.y, fma(k.y2, fma(k.y2, fma(minus_third * k.p, k.y2, fifth * k.w), M::splat(e.t15 / 3.0)), M::splat(e.neg_mass)), phi);
    }
    for (std::size_t r = 0; r < ranges.size(); r += 2)
      for (std::uint32_t j = ranges[r]; j < ranges[r + 1]; ++j) {
        const V dx = M::splat(x_[j]) - t.x, dy = M::splat(y_[j]) - t.y, dz = M::splat(z_[j]) - t.z;
        const V y = rsqrt(fma(dz, dz, fma(dy, dy, fma(dx, dx, e2))));
        phi = phi - keep_lanes(M::splat(m_[j]) * y, all_but_self(first, j));
      }
    alignas(64) double b[lanes];
    M::store(b, phi);
    for (std::size_t l = 0; l < lanes && first + l < g.end; ++l) potential_[first + l] = b[l];
  }
}

double TreeGravity::potential_energy(const double* position) {
  build(position);
  potential_.assign(count_, 0.0);
  const std::size_t groups = groups_.size();
#pragma omp parallel if (count_ >= 512)
  {
    InteractionList list(nodes_.size());
#pragma omp for schedule(dynamic, 16)
    for (std::size_t g = 0; g < groups; ++g) group_potential(groups_[g], list);
  }
  std::vector<double> by_index(count_);
  for (std::size_t k = 0; k < count_; ++k) by_index[order_[k]] = potential_[k];
  double energy = 0;
  for (std::size_t i = 0; i < count_; ++i) energy += 0.5 * mass_[i] * by_index[i];
  return energy;
}

}  // namespace tidalcrust
