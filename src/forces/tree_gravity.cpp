#include "forces/tree_gravity.hpp"

#include <algorithm>
#include <cmath>
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

// One vector of `lanes` doubles: AVX-512 intrinsics when available (explicit FMAs: the project
// compiles with -ffp-contract=off), else plain loops. Both give deterministic results; their
// last bits differ, like DirectGravity's two paths.
#if defined(__AVX512F__)
struct V {
  __m512d v;
};
inline V splat(double a) { return {_mm512_set1_pd(a)}; }
inline V load(const double* p) { return {_mm512_loadu_pd(p)}; }
inline void store(double* p, V a) { _mm512_storeu_pd(p, a.v); }
inline V operator+(V a, V b) { return {_mm512_add_pd(a.v, b.v)}; }
inline V operator-(V a, V b) { return {_mm512_sub_pd(a.v, b.v)}; }
inline V operator*(V a, V b) { return {_mm512_mul_pd(a.v, b.v)}; }
/// a * b + c
inline V fma(V a, V b, V c) { return {_mm512_fmadd_pd(a.v, b.v, c.v)}; }
/// 1/sqrt(s): the 14-bit hardware estimate and two Newton steps (~1 ulp), as DirectGravity.
inline V rsqrt(V s) {
  const __m512d three_halves = _mm512_set1_pd(1.5);
  const __m512d half_s = _mm512_mul_pd(_mm512_set1_pd(0.5), s.v);
  __m512d y = _mm512_maskz_rsqrt14_pd(0xFF, s.v);
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(half_s, _mm512_mul_pd(y, y), three_halves));
  y = _mm512_mul_pd(y, _mm512_fnmadd_pd(half_s, _mm512_mul_pd(y, y), three_halves));
  return {y};
}
/// a with the lanes whose bit in `keep` is 0 set to zero.
inline V keep_lanes(V a, unsigned keep) { return {_mm512_maskz_mov_pd(static_cast<__mmask8>(keep), a.v)}; }
#else
struct V {
  double v[lanes];
};
inline V splat(double a) {
  V r;
  for (std::size_t l = 0; l < lanes; ++l) r.v[l] = a;
  return r;
}
inline V load(const double* p) {
  V r;
  for (std::size_t l = 0; l < lanes; ++l) r.v[l] = p[l];
  return r;
}
inline void store(double* p, V a) {
  for (std::size_t l = 0; l < lanes; ++l) p[l] = a.v[l];
}
#define TIDALCRUST_LANEWISE(op)                                  \
  inline V operator op(V a, V b) {                               \
    for (std::size_t l = 0; l < lanes; ++l) a.v[l] = a.v[l] op b.v[l]; \
    return a;                                                    \
  }
TIDALCRUST_LANEWISE(+)
TIDALCRUST_LANEWISE(-)
TIDALCRUST_LANEWISE(*)
#undef TIDALCRUST_LANEWISE
inline V fma(V a, V b, V c) { return a * b + c; }
inline V rsqrt(V s) {
  for (std::size_t l = 0; l < lanes; ++l) s.v[l] = 1.0 / std::sqrt(s.v[l]);
  return s;
}
inline V keep_lanes(V a, unsigned keep) {
  for (std::size_t l = 0; l < lanes; ++l)
    if (!((keep >> l) & 1u)) a.v[l] = 0.0;
  return a;
}
#endif

/// Lanes of the vector of particles [first, first + lanes) other than particle j (self-pair).
inline unsigned all_but_self(std::uint32_t first, std::uint32_t j) {
  return j >= first && j < first + lanes ? 0xFFu & ~(1u << (j - first)) : 0xFFu;
}

/// Positions of the group's particles [first, first + lanes) (Morton order), the last valid one
/// repeated into lanes past `end` (their results are not used).
struct Targets {
  V x, y, z;
  Targets(const double* xs, const double* ys, const double* zs, std::uint32_t first, std::uint32_t end) {
    alignas(64) double bx[lanes], by[lanes], bz[lanes];
    for (std::size_t l = 0; l < lanes; ++l) {
      const std::size_t k = std::min<std::size_t>(first + l, end - 1);
      bx[l] = xs[k], by[l] = ys[k], bz[l] = zs[k];
    }
    x = load(bx), y = load(by), z = load(bz);
  }
};

/// The octupole contractions of a cell at r = x - com: U_i = O_ijk r_j r_k and P = r.U.
struct Octupole {
  V ux, uy, uz, p;
  template <class Cell>
  Octupole(const Cell& cell, V rx, V ry, V rz) {
    const double* o = cell.third;  // xxx, xxy, xxz, xyy, xyz, xzz, yyy, yyz, yzz, zzz
    const V xx = rx * rx, yy = ry * ry, zz = rz * rz, two = splat(2.0);
    const V xy = two * rx * ry, xz = two * rx * rz, yz = two * ry * rz;
    ux = fma(splat(o[4]), yz, fma(splat(o[2]), xz, fma(splat(o[1]), xy, fma(splat(o[5]), zz, fma(splat(o[3]), yy, splat(o[0]) * xx)))));
    uy = fma(splat(o[7]), yz, fma(splat(o[4]), xz, fma(splat(o[3]), xy, fma(splat(o[8]), zz, fma(splat(o[6]), yy, splat(o[1]) * xx)))));
    uz = fma(splat(o[8]), yz, fma(splat(o[5]), xz, fma(splat(o[4]), xy, fma(splat(o[9]), zz, fma(splat(o[7]), yy, splat(o[2]) * xx)))));
    p = fma(rz, uz, fma(ry, uy, rx * ux));
  }
};

/// What a cell's pull and potential share at the targets t: r = x - com, y = 1/s (s^2 = r^2 +
/// eps^2) and its powers, S r, q = r.S.r, the octupole contractions and t.r (t_k = O_iik).
struct CellTerms {
  V rx, ry, rz, y, y2, y3, y5, srx, sry, srz, q;
  Octupole oct;
  V tr;
  template <class Cell>
  CellTerms(const Cell& cell, const Targets& t, V e2)
      : rx(t.x - splat(cell.com[0])),
        ry(t.y - splat(cell.com[1])),
        rz(t.z - splat(cell.com[2])),
        y(rsqrt(fma(rz, rz, fma(ry, ry, fma(rx, rx, e2))))),
        y2(y * y),
        y3(y2 * y),
        y5(y3 * y2),
        srx(fma(splat(cell.second[2]), rz, fma(splat(cell.second[1]), ry, splat(cell.second[0]) * rx))),
        sry(fma(splat(cell.second[4]), rz, fma(splat(cell.second[3]), ry, splat(cell.second[1]) * rx))),
        srz(fma(splat(cell.second[5]), rz, fma(splat(cell.second[4]), ry, splat(cell.second[2]) * rx))),
        q(fma(rz, srz, fma(ry, sry, rx * srx))),
        oct(cell, rx, ry, rz),
        tr(fma(splat(cell.third_trace[2]), rz, fma(splat(cell.third_trace[1]), ry, splat(cell.third_trace[0]) * rx))) {}
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

double opening_angle_for(double force_error) {
  return std::clamp(2.55 * std::pow(force_error, 2.0 / 9.0), 0.1, 0.7);
}

TreeGravity::TreeGravity(const std::vector<double>& mass, double softening, double force_error)
    : count_(mass.size()),
      eps2_(softening * softening),
      theta_(opening_angle_for(force_error)),
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

void TreeGravity::compute_moments(std::size_t index) {
  Node& node = nodes_[index];
  double mass = 0, mx = 0, my = 0, mz = 0;
  for (std::uint32_t k = node.begin; k < node.end; ++k) {
    mass += m_[k];
    mx += m_[k] * x_[k];
    my += m_[k] * y_[k];
    mz += m_[k] * z_[k];
  }
  node.mass = mass;
  if (mass > 0) {
    node.com[0] = mx / mass, node.com[1] = my / mass, node.com[2] = mz / mass;
  } else {  // massless particles only: no pull, any centre
    node.com[0] = x_[node.begin], node.com[1] = y_[node.begin], node.com[2] = z_[node.begin];
  }
  double s[6] = {0, 0, 0, 0, 0, 0}, o[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, bmax2 = 0;
  for (std::uint32_t k = node.begin; k < node.end; ++k) {
    const double d[3] = {x_[k] - node.com[0], y_[k] - node.com[1], z_[k] - node.com[2]};
    const double m = m_[k];
    s[0] += m * d[0] * d[0];
    s[1] += m * d[0] * d[1];
    s[2] += m * d[0] * d[2];
    s[3] += m * d[1] * d[1];
    s[4] += m * d[1] * d[2];
    s[5] += m * d[2] * d[2];
    std::size_t c = 0;  // i <= j <= l, in the order of Node::third
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = i; j < 3; ++j)
        for (std::size_t l = j; l < 3; ++l) o[c++] += m * d[i] * d[j] * d[l];
    bmax2 = std::max(bmax2, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  }
  std::copy(s, s + 6, node.second);
  node.trace = s[0] + s[3] + s[5];
  std::copy(o, o + 10, node.third);
  node.third_trace[0] = o[0] + o[3] + o[5];  // xxx + xyy + xzz
  node.third_trace[1] = o[1] + o[6] + o[8];  // xxy + yyy + yzz
  node.third_trace[2] = o[2] + o[7] + o[9];  // xxz + yyz + zzz
  node.bmax2 = bmax2;
}

void TreeGravity::build(const double* position) {
  const std::size_t n = count_;
  nodes_.clear();
  groups_.clear();
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
  struct Keyed {
    std::uint64_t key;
    std::uint32_t index;
  };
  std::vector<Keyed> keyed(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* p = position + 3 * i;
    keyed[i] = {spread_bits(quantize(p[0], 0)) << 2 | spread_bits(quantize(p[1], 1)) << 1 | spread_bits(quantize(p[2], 2)),
                static_cast<std::uint32_t>(i)};
  }
  // A total order (ties by index): the same sorted sequence from any sort algorithm.
  std::sort(keyed.begin(), keyed.end(),
            [](const Keyed& a, const Keyed& b) { return a.key < b.key || (a.key == b.key && a.index < b.index); });
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
  // Each node's moments from its own particles (O(N depth)): independent, any thread.
#pragma omp parallel for schedule(dynamic, 32) if (n >= 4096)
  for (std::size_t i = 0; i < node_total; ++i) compute_moments(i);
  for (Group& g : groups_) {
    for (std::size_t k = 0; k < 3; ++k) g.lo[k] = std::numeric_limits<double>::infinity(), g.hi[k] = -g.lo[k];
    for (std::uint32_t k = g.begin; k < g.end; ++k) {
      const double p[3] = {x_[k], y_[k], z_[k]};
      for (std::size_t a = 0; a < 3; ++a) g.lo[a] = std::min(g.lo[a], p[a]), g.hi[a] = std::max(g.hi[a], p[a]);
    }
  }
}

void TreeGravity::interaction_list(const Group& g, std::vector<std::uint32_t>& cells,
                                   std::vector<std::uint32_t>& ranges) const {
  cells.clear();
  ranges.clear();
  const double theta2 = theta_ * theta_;
  const std::size_t total = nodes_.size();
  for (std::size_t i = 0; i < total;) {
    const Node& node = nodes_[i];
    double d2 = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      const double d = std::max({g.lo[k] - node.com[k], node.com[k] - g.hi[k], 0.0});
      d2 += d * d;
    }
    // A node holding a particle of the group never passes: that particle lies in the box, so
    // d <= b_max, and theta < 1.
    if (node.bmax2 < theta2 * d2) {
      cells.push_back(static_cast<std::uint32_t>(i));
      i = node.next;
    } else if (node.leaf) {
      if (!ranges.empty() && ranges.back() == node.begin)
        ranges.back() = node.end;  // contiguous leaves make one longer range
      else
        ranges.push_back(node.begin), ranges.push_back(node.end);
      i = node.next;
    } else {
      ++i;
    }
  }
}

void TreeGravity::accumulate_chunk(std::size_t chunk) {
  std::vector<std::uint32_t> cells, ranges;
  const V e2 = splat(eps2_), three = splat(3.0), three_halves = splat(1.5), fifteen_halves = splat(7.5),
          thirty_five_halves = splat(17.5);
  const std::size_t last = std::min(groups_.size(), (chunk + 1) * groups_per_chunk);
  for (std::size_t gi = chunk * groups_per_chunk; gi < last; ++gi) {
    const Group& g = groups_[gi];
    interaction_list(g, cells, ranges);
    for (std::uint32_t first = g.begin; first < g.end; first += lanes) {
      const Targets t(x_.data(), y_.data(), z_.data(), first, g.end);
      V ax = splat(0.0), ay = ax, az = ax;
      for (const std::uint32_t c : cells) {
        const Node& cell = nodes_[c];
        const CellTerms k(cell, t, e2);
        const V &rx = k.rx, &ry = k.ry, &rz = k.rz, &y3 = k.y3, &y5 = k.y5, &q = k.q, &tr = k.tr;
        const V y7 = y5 * k.y2, y9 = y7 * k.y2;
        const V &srx = k.srx, &sry = k.sry, &srz = k.srz;
        const Octupole& oct = k.oct;
        // monopole and quadrupole: -M/s^3 + (3/2) tr S/s^5 - (15/2) q/s^7 along r, 3/s^5 along S r;
        // octupole: (15/2) (t.r)/s^7 - (35/2) P/s^9 along r, (15/2)/s^7 along U, -(3/2)/s^5 along t
        const V radial = fma(three_halves * splat(cell.trace), y5, splat(0.0) - splat(cell.mass) * y3) -
                         fifteen_halves * q * y7 + fifteen_halves * tr * y7 - thirty_five_halves * oct.p * y9;
        const V along = three * y5, along_u = fifteen_halves * y7, along_t = three_halves * y5;
        ax = fma(along_u, oct.ux, fma(along, srx, fma(radial, rx, ax))) - along_t * splat(cell.third_trace[0]);
        ay = fma(along_u, oct.uy, fma(along, sry, fma(radial, ry, ay))) - along_t * splat(cell.third_trace[1]);
        az = fma(along_u, oct.uz, fma(along, srz, fma(radial, rz, az))) - along_t * splat(cell.third_trace[2]);
      }
      for (std::size_t r = 0; r < ranges.size(); r += 2) {
        for (std::uint32_t j = ranges[r]; j < ranges[r + 1]; ++j) {
          const V dx = splat(x_[j]) - t.x, dy = splat(y_[j]) - t.y, dz = splat(z_[j]) - t.z;
          const V y = rsqrt(fma(dz, dz, fma(dy, dy, fma(dx, dx, e2))));
          const V f = keep_lanes(splat(m_[j]) * (y * y * y), all_but_self(first, j));
          ax = fma(f, dx, ax);
          ay = fma(f, dy, ay);
          az = fma(f, dz, az);
        }
      }
      alignas(64) double bx[lanes], by[lanes], bz[lanes];
      store(bx, ax), store(by, ay), store(bz, az);
      for (std::size_t l = 0; l < lanes && first + l < g.end; ++l) {
        double* a = acceleration_.data() + 3 * static_cast<std::size_t>(order_[first + l]);
        a[0] = bx[l], a[1] = by[l], a[2] = bz[l];
      }
    }
  }
}

void TreeGravity::accelerations(const double* position, double* acceleration, bool parallel) {
  build(position);
  const std::size_t chunks = chunk_count();
#pragma omp parallel if (parallel)
  {
#pragma omp for schedule(dynamic, 1)
    for (std::size_t c = 0; c < chunks; ++c) accumulate_chunk(c);
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < count_; ++i) this->acceleration(i, acceleration + 3 * i);
  }
}

void TreeGravity::group_potential(const Group& g, std::vector<std::uint32_t>& cells, std::vector<std::uint32_t>& ranges) {
  interaction_list(g, cells, ranges);
  const V e2 = splat(eps2_), half = splat(0.5), three = splat(3.0), sixth = splat(1.0 / 6.0), nine = splat(9.0),
          fifteen = splat(15.0);
  for (std::uint32_t first = g.begin; first < g.end; first += lanes) {
    const Targets t(x_.data(), y_.data(), z_.data(), first, g.end);
    V phi = splat(0.0);
    for (const std::uint32_t c : cells) {
      const Node& cell = nodes_[c];
      const CellTerms k(cell, t, e2);
      const V &y = k.y, &y2 = k.y2, &y3 = k.y3, &y5 = k.y5, &q = k.q, &tr = k.tr;
      const Octupole& oct = k.oct;
      // -M/s - (1/2) (3 q/s^5 - tr S/s^3) + (1/6) (9 t.r/s^5 - 15 P/s^7)
      phi = phi - splat(cell.mass) * y - half * (three * q * y5 - splat(cell.trace) * y3) +
            sixth * (nine * tr * y5 - fifteen * oct.p * y5 * y2);
    }
    for (std::size_t r = 0; r < ranges.size(); r += 2)
      for (std::uint32_t j = ranges[r]; j < ranges[r + 1]; ++j) {
        const V dx = splat(x_[j]) - t.x, dy = splat(y_[j]) - t.y, dz = splat(z_[j]) - t.z;
        const V y = rsqrt(fma(dz, dz, fma(dy, dy, fma(dx, dx, e2))));
        phi = phi - keep_lanes(splat(m_[j]) * y, all_but_self(first, j));
      }
    alignas(64) double b[lanes];
    store(b, phi);
    for (std::size_t l = 0; l < lanes && first + l < g.end; ++l) potential_[first + l] = b[l];
  }
}

double TreeGravity::potential_energy(const double* position) {
  build(position);
  potential_.assign(count_, 0.0);
  const std::size_t groups = groups_.size();
#pragma omp parallel if (count_ >= 512)
  {
    std::vector<std::uint32_t> cells, ranges;
#pragma omp for schedule(dynamic, 16)
    for (std::size_t g = 0; g < groups; ++g) group_potential(groups_[g], cells, ranges);
  }
  std::vector<double> by_index(count_);
  for (std::size_t k = 0; k < count_; ++k) by_index[order_[k]] = potential_[k];
  double energy = 0;
  for (std::size_t i = 0; i < count_; ++i) energy += 0.5 * mass_[i] * by_index[i];
  return energy;
}

}  // namespace tidalcrust
