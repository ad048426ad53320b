#include "forces/liquid_pressure.hpp"

#include <cmath>

#include "base/invariant.hpp"

namespace tidalcrust {

LiquidPressure::LiquidPressure(const Body& body) : body_(body) {
  const std::size_t n = body.particle_count();
  TIDALCRUST_ASSERT(body.liquid.present() && body.liquid.node_volume.size() == n,
                    "a liquid layer needs one node volume per particle");
  for (std::size_t s = 0; s < body.spring_count(); ++s)
    if (body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::liquid))
      liquid_springs_.push_back(static_cast<std::int32_t>(s));
  for (std::size_t p = 0; p < n; ++p)
    if (body.species[p] == static_cast<std::uint8_t>(Species::liquid)) liquid_.push_back(static_cast<std::int32_t>(p));
  std::vector<std::int32_t> count(n + 1, 0);
  for (const std::int32_t s : liquid_springs_)
    for (const std::int32_t p : body.springs[static_cast<std::size_t>(s)]) ++count[static_cast<std::size_t>(p) + 1];
  offset_.assign(n + 1, 0);
  for (std::size_t p = 0; p < n; ++p) offset_[p + 1] = offset_[p] + count[p + 1];
  incident_.assign(static_cast<std::size_t>(offset_[n]), 0);
  std::vector<std::int32_t> next(offset_.begin(), offset_.end() - 1);
  for (std::size_t k = 0; k < liquid_springs_.size(); ++k) {
    const auto& ends = body.springs[static_cast<std::size_t>(liquid_springs_[k])];
    incident_[static_cast<std::size_t>(next[static_cast<std::size_t>(ends[0])]++)] = static_cast<std::int32_t>(2 * k);
    incident_[static_cast<std::size_t>(next[static_cast<std::size_t>(ends[1])]++)] = static_cast<std::int32_t>(2 * k + 1);
  }
  for (const std::int32_t a : liquid_)
    TIDALCRUST_ASSERT(offset_[static_cast<std::size_t>(a) + 1] > offset_[static_cast<std::size_t>(a)],
                      "every liquid particle has a liquid spring");
  force_.assign(3 * n, 0.0);
  factor_.assign(n, 0.0);
  strain_.assign(liquid_springs_.size(), 0.0);
  length_.assign(liquid_springs_.size(), 0.0);
  coefficient_.assign(liquid_springs_.size(), 0.0);
}

void LiquidPressure::spring_strains(const double* position, const SpringState& springs, bool parallel) const {
  const std::size_t count = liquid_springs_.size();
#pragma omp parallel for schedule(static) if (parallel)
  for (std::size_t k = 0; k < count; ++k) {
    const auto s = static_cast<std::size_t>(liquid_springs_[k]);
    const double* xi = position + 3 * static_cast<std::size_t>(body_.springs[s][0]);
    const double* xj = position + 3 * static_cast<std::size_t>(body_.springs[s][1]);
    const double d0 = xi[0] - xj[0], d1 = xi[1] - xj[1], d2 = xi[2] - xj[2];
    length_[k] = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
    strain_[k] = length_[k] / springs.rest_length[s] - 1;
  }
}

double LiquidPressure::theta_of(std::size_t a) const {
  double sum = 0;
  for (std::int32_t e = offset_[a]; e < offset_[a + 1]; ++e) sum += strain_[static_cast<std::size_t>(incident_[static_cast<std::size_t>(e)] >> 1)];
  return 3.0 * sum / static_cast<double>(offset_[a + 1] - offset_[a]);
}

std::vector<double> LiquidPressure::volumetric_strain(const double* position, const SpringState& springs) const {
  spring_strains(position, springs, false);
  std::vector<double> theta(body_.particle_count(), 0.0);
  for (const std::int32_t a : liquid_) theta[static_cast<std::size_t>(a)] = theta_of(static_cast<std::size_t>(a));
  return theta;
}

std::vector<double> LiquidPressure::pressure(const double* position, const SpringState& springs) const {
  std::vector<double> p = volumetric_strain(position, springs);
  for (double& v : p) v = v == 0 ? 0.0 : -body_.liquid.bulk_modulus * v;
  return p;
}

void LiquidPressure::compute(const double* position, const SpringState& springs, bool parallel) {
  spring_strains(position, springs, parallel);
  const double bulk = body_.liquid.bulk_modulus;
  const std::size_t liquid_count = liquid_.size();
#pragma omp parallel if (parallel)
  {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < liquid_count; ++i) {
      const auto a = static_cast<std::size_t>(liquid_[i]);
      const double n = static_cast<double>(offset_[a + 1] - offset_[a]);
      factor_[a] = bulk * body_.liquid.node_volume[a] * theta_of(a) * 3.0 / n;
    }
    // dE/dL_s = (factor_i + factor_j) / L0_s (factor 0 at a solid end); the force on the first
    // end is -dE/dL_s d/L_s.
#pragma omp for schedule(static)
    for (std::size_t k = 0; k < liquid_springs_.size(); ++k) {
      const auto s = static_cast<std::size_t>(liquid_springs_[k]);
      const auto i = static_cast<std::size_t>(body_.springs[s][0]), j = static_cast<std::size_t>(body_.springs[s][1]);
      coefficient_[k] = -(factor_[i] + factor_[j]) / (springs.rest_length[s] * length_[k]);
    }
#pragma omp for schedule(dynamic, 256)
    for (std::size_t p = 0; p < body_.particle_count(); ++p) {
      double f[3] = {0, 0, 0};
      for (std::int32_t e = offset_[p]; e < offset_[p + 1]; ++e) {
        const auto entry = static_cast<std::size_t>(incident_[static_cast<std::size_t>(e)]);
        const std::size_t k = entry >> 1;
        const auto s = static_cast<std::size_t>(liquid_springs_[k]);
        const double* xi = position + 3 * static_cast<std::size_t>(body_.springs[s][0]);
        const double* xj = position + 3 * static_cast<std::size_t>(body_.springs[s][1]);
        // +c d on the first end, -c d on the second (d = x_first - x_second).
        const double sign = (entry & 1) ? -1.0 : 1.0;
        for (int c = 0; c < 3; ++c) f[c] += sign * coefficient_[k] * (xi[c] - xj[c]);
      }
      for (int c = 0; c < 3; ++c) force_[3 * p + c] = f[c];
    }
  }
}

double LiquidPressure::energy(const double* position, const SpringState& springs) const {
  spring_strains(position, springs, false);
  double e = 0;
  for (const std::int32_t ai : liquid_) {
    const auto a = static_cast<std::size_t>(ai);
    const double theta = theta_of(a);
    e += 0.5 * body_.liquid.bulk_modulus * body_.liquid.node_volume[a] * theta * theta;
  }
  return e;
}

}  // namespace tidalcrust
