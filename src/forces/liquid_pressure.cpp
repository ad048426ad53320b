#include "forces/liquid_pressure.hpp"

#include <algorithm>
#include <limits>

#include "base/invariant.hpp"

namespace tidalcrust {

namespace {
constexpr std::int64_t cell_bits = 21;  // cells per axis < 2^21: keys fit in 63 bits
constexpr std::int64_t cell_limit = (std::int64_t{1} << cell_bits) - 1;
}  // namespace

LiquidPressure::LiquidPressure(const Body& body)
    : body_(body),
      kernel_{body.liquid.support_radius},
      contact_{body.liquid.contact_stiffness} {
  TIDALCRUST_ASSERT(body.liquid.present() && body.liquid.density_weight.size() == body.particle_count() &&
                        body.liquid.contact_radius.size() == body.particle_count(),
                    "a liquid layer needs one density weight and one contact radius per particle");
  for (std::size_t i = 0; i < body.particle_count(); ++i)
    if (body.liquid.density_weight[i] > 0 || body.liquid.contact_radius[i] > 0) {
      TIDALCRUST_ASSERT(body.liquid.contact_radius[i] < body.liquid.support_radius,
                        "a contact radius lies within the liquid kernel's reach (the neighbour search)");
      reachable_.push_back(static_cast<std::int32_t>(i));
    }
  force_.assign(3 * body.particle_count(), 0.0);
  damping_force_.assign(3 * body.particle_count(), 0.0);
  density_.assign(body.particle_count(), 0.0);
}

std::int64_t LiquidPressure::cell_of(const double* x) const {
  std::int64_t key = 0;
  for (int k = 2; k >= 0; --k) {
    const double c = std::floor((x[k] - origin_[k]) / kernel_.support);
    const std::int64_t i = c < 0 ? 0 : c > static_cast<double>(cell_limit) ? cell_limit : static_cast<std::int64_t>(c);
    key = (key << cell_bits) | i;
  }
  return key;
}

void LiquidPressure::build_cells(const double* position) const {
  for (int k = 0; k < 3; ++k) origin_[k] = std::numeric_limits<double>::infinity();
  for (const std::int32_t p : reachable_)
    for (int k = 0; k < 3; ++k) origin_[k] = std::min(origin_[k], position[3 * p + k]);
  // One empty cell below the lowest particle, so that every neighbour key is >= 0.
  for (int k = 0; k < 3; ++k) origin_[k] -= kernel_.support;
  std::vector<std::pair<std::int64_t, std::int32_t>> keyed;
  keyed.reserve(reachable_.size());
  for (const std::int32_t p : reachable_) keyed.emplace_back(cell_of(position + 3 * p), p);
  std::sort(keyed.begin(), keyed.end());
  cell_key_.resize(keyed.size());
  cell_order_.resize(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    cell_key_[i] = keyed[i].first;
    cell_order_[i] = keyed[i].second;
  }
}

void LiquidPressure::neighbours(std::size_t a, const double* position, std::vector<std::int32_t>& out) const {
  out.clear();
  const double* xa = position + 3 * a;
  const std::int64_t key = cell_of(xa);
  const std::int64_t mask = cell_limit;
  const std::int64_t ix = key & mask, iy = (key >> cell_bits) & mask, iz = key >> (2 * cell_bits);
  const double h2 = kernel_.support * kernel_.support;
  for (std::int64_t dz = -1; dz <= 1; ++dz)
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const std::int64_t x = ix + dx, y = iy + dy, z = iz + dz;
        if (x < 0 || y < 0 || z < 0 || x > cell_limit || y > cell_limit || z > cell_limit) continue;
        const std::int64_t k = (((z << cell_bits) | y) << cell_bits) | x;
        const auto [lo, hi] = std::equal_range(cell_key_.begin(), cell_key_.end(), k);
        for (auto it = lo; it != hi; ++it) {
          const std::int32_t b = cell_order_[static_cast<std::size_t>(it - cell_key_.begin())];
          if (static_cast<std::size_t>(b) == a) continue;
          const double* xb = position + 3 * b;
          const double d0 = xa[0] - xb[0], d1 = xa[1] - xb[1], d2 = xa[2] - xb[2];
          if (d0 * d0 + d1 * d1 + d2 * d2 < h2) out.push_back(b);
        }
      }
}

std::vector<double> LiquidPressure::densities(const double* position, bool parallel) const {
  build_cells(position);
  const auto& w = body_.liquid.density_weight;
  const std::uint8_t liquid = static_cast<std::uint8_t>(Species::liquid);
  std::vector<double> n(body_.particle_count(), 0.0);
  const std::size_t count = reachable_.size();
#pragma omp parallel if (parallel)
  {
    std::vector<std::int32_t> near;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t a = static_cast<std::size_t>(reachable_[i]);
      if (body_.species[a] != liquid) continue;
      neighbours(a, position, near);
      double sum = w[a] * kernel_.value(0);
      for (const std::int32_t b : near) {
        const double* xa = position + 3 * a;
        const double* xb = position + 3 * b;
        const double d0 = xa[0] - xb[0], d1 = xa[1] - xb[1], d2 = xa[2] - xb[2];
        sum += w[static_cast<std::size_t>(b)] * kernel_.value(std::sqrt(d0 * d0 + d1 * d1 + d2 * d2));
      }
      n[a] = sum;
    }
  }
  return n;
}

void LiquidPressure::compute(const double* position, const double* velocity,
                             const std::vector<double>& reference_density, double damping, bool parallel) {
  TIDALCRUST_ASSERT(reference_density.size() == body_.particle_count(), "one reference density per particle");
  density_ = densities(position, parallel);  // also sorts the cells for this pass
  const auto& w = body_.liquid.density_weight;
  const auto& mass = body_.mass;
  const std::uint8_t liquid = static_cast<std::uint8_t>(Species::liquid);
  const double bulk = body_.liquid.bulk_modulus;
  // slope[a] = de_a/dn_a for a liquid particle, 0 otherwise (kept in density_'s place).
  std::vector<double> slope(body_.particle_count(), 0.0);
  for (const std::int32_t p : reachable_)
    if (body_.species[static_cast<std::size_t>(p)] == liquid)
      slope[static_cast<std::size_t>(p)] =
          LiquidEquationOfState{reference_density[static_cast<std::size_t>(p)], bulk}.energy_slope(density_[static_cast<std::size_t>(p)]);
  const double inv_w0 = 1.0 / kernel_.value(0);
  const std::size_t count = reachable_.size();
#pragma omp parallel if (parallel)
  {
    std::vector<std::int32_t> near;
#pragma omp for schedule(dynamic, 64)
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t a = static_cast<std::size_t>(reachable_[i]);
      neighbours(a, position, near);
      double f[3] = {0, 0, 0}, fd[3] = {0, 0, 0};
      const double* xa = position + 3 * a;
      const double* va = velocity + 3 * a;
      for (const std::int32_t bi : near) {
        const std::size_t b = static_cast<std::size_t>(bi);
        // A pair of two solid particles has no liquid energy: nothing acts between them.
        if (body_.species[a] != liquid && body_.species[b] != liquid) continue;
        const double* xb = position + 3 * b;
        const double d[3] = {xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]};
        const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        // -d/dx_a of e_a(n_a) + e_b(n_b) through this pair: -(e'_a w_b + e'_b w_a) W'(r) d/r.
        double c = -(slope[a] * w[b] + slope[b] * w[a]) * kernel_.derivative(r) / r;
        if (body_.species[a] != liquid) c += contact_.coefficient(r, body_.liquid.contact_radius[a]);
        else if (body_.species[b] != liquid) c += contact_.coefficient(r, body_.liquid.contact_radius[b]);
        const double* vb = velocity + 3 * b;
        const double d_dot_dv = d[0] * (va[0] - vb[0]) + d[1] * (va[1] - vb[1]) + d[2] * (va[2] - vb[2]);
        const double mu = mass[a] * mass[b] / (mass[a] + mass[b]);
        const double cd = -damping * mu * (kernel_.value(r) * inv_w0) * d_dot_dv / (r * r);
        for (int k = 0; k < 3; ++k) {
          f[k] += c * d[k];
          fd[k] += cd * d[k];
        }
      }
      for (int k = 0; k < 3; ++k) {
        force_[3 * a + k] = f[k] + fd[k];
        damping_force_[3 * a + k] = fd[k];
      }
    }
  }
}

double LiquidPressure::energy(const double* position, const std::vector<double>& reference_density) const {
  const std::vector<double> n = densities(position, false);
  const std::uint8_t liquid = static_cast<std::uint8_t>(Species::liquid);
  double e = 0;
  std::vector<std::int32_t> near;
  for (std::size_t a = 0; a < body_.particle_count(); ++a) {
    if (body_.species[a] != liquid) continue;
    e += LiquidEquationOfState{reference_density[a], body_.liquid.bulk_modulus}.energy(n[a]);
    neighbours(a, position, near);  // the cells of densities() above
    for (const std::int32_t b : near) {
      if (body_.species[static_cast<std::size_t>(b)] == liquid) continue;
      const double* xa = position + 3 * a;
      const double* xb = position + 3 * b;
      const double d0 = xa[0] - xb[0], d1 = xa[1] - xb[1], d2 = xa[2] - xb[2];
      e += contact_.energy(std::sqrt(d0 * d0 + d1 * d1 + d2 * d2), body_.liquid.contact_radius[static_cast<std::size_t>(b)]);
    }
  }
  return e;
}

double LiquidPressure::damping_power(const double* position, const double* velocity, double damping) const {
  build_cells(position);
  const std::uint8_t liquid = static_cast<std::uint8_t>(Species::liquid);
  const double inv_w0 = 1.0 / kernel_.value(0);
  std::vector<std::int32_t> near;
  double power = 0;
  for (const std::int32_t ai : reachable_) {
    const std::size_t a = static_cast<std::size_t>(ai);
    neighbours(a, position, near);
    for (const std::int32_t bi : near) {
      const std::size_t b = static_cast<std::size_t>(bi);
      if (b < a || (body_.species[a] != liquid && body_.species[b] != liquid)) continue;  // each pair once
      const double d[3] = {position[3 * a] - position[3 * b], position[3 * a + 1] - position[3 * b + 1],
                           position[3 * a + 2] - position[3 * b + 2]};
      const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
      const double d_dot_dv = d[0] * (velocity[3 * a] - velocity[3 * b]) +
                              d[1] * (velocity[3 * a + 1] - velocity[3 * b + 1]) +
                              d[2] * (velocity[3 * a + 2] - velocity[3 * b + 2]);
      const double mu = body_.mass[a] * body_.mass[b] / (body_.mass[a] + body_.mass[b]);
      power += damping * mu * kernel_.value(std::sqrt(r2)) * inv_w0 * d_dot_dv * d_dot_dv / r2;
    }
  }
  return power;
}

double LiquidPressure::damping_work(const double* start, const double* end) const {
  double removed = 0;
  for (std::size_t i = 0; i < damping_force_.size(); ++i) removed -= damping_force_[i] * (end[i] - start[i]);
  return removed;
}

}  // namespace tidalcrust
