#include "forces/liquid_pressure.hpp"

#include "base/invariant.hpp"
#include "forces/maxwell_liquid.hpp"

namespace tidalcrust {

double tetrahedron_volume(const double* x0, const double* x1, const double* x2, const double* x3) {
  const double a[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
  const double b[3] = {x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
  const double c[3] = {x3[0] - x0[0], x3[1] - x0[1], x3[2] - x0[2]};
  return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6.0;
}

LiquidPressure::LiquidPressure(const Body& body) : body_(body) {
  const std::size_t n = body.particle_count(), nt = body.liquid.tetrahedra.size();
  TIDALCRUST_ASSERT(body.liquid.present(), "a liquid layer");
  std::vector<std::int32_t> count(n + 1, 0);
  for (std::size_t t = 0; t < nt; ++t)
    for (const std::int32_t p : body.liquid.tetrahedra[t]) {
      TIDALCRUST_ASSERT(p >= 0 && static_cast<std::size_t>(p) < n, "a tetrahedron's corner is a particle");
      ++count[static_cast<std::size_t>(p) + 1];
    }
  for (std::size_t p = 0; p < n; ++p)
    if (count[p + 1] > 0) node_.push_back(static_cast<std::int32_t>(p));
  offset_.assign(n + 1, 0);
  for (std::size_t p = 0; p < n; ++p) offset_[p + 1] = offset_[p] + count[p + 1];
  corner_.assign(static_cast<std::size_t>(offset_[n]), 0);
  std::vector<std::int32_t> next(offset_.begin(), offset_.end() - 1);
  for (std::size_t t = 0; t < nt; ++t)
    for (int v = 0; v < 4; ++v)
      corner_[static_cast<std::size_t>(next[static_cast<std::size_t>(body.liquid.tetrahedra[t][v])]++)] =
          static_cast<std::int32_t>(4 * t + static_cast<std::size_t>(v));
  tet_volume_.assign(nt, 0.0);
  pressure_.assign(n, 0.0);
  corner_force_.assign(12 * nt, 0.0);
  force_.assign(3 * n, 0.0);
}

void LiquidPressure::tetrahedron_volumes(const double* position, bool parallel) const {
  const auto& tets = body_.liquid.tetrahedra;
  const std::size_t nt = tets.size();
#pragma omp parallel for schedule(static) if (parallel)
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& c = tets[t];
    tet_volume_[t] = tetrahedron_volume(position + 3 * c[0], position + 3 * c[1], position + 3 * c[2], position + 3 * c[3]);
  }
}

double LiquidPressure::volume_of(std::size_t a) const {
  double v = 0;
  for (std::int32_t e = offset_[a]; e < offset_[a + 1]; ++e) {
    const std::size_t t = static_cast<std::size_t>(corner_[static_cast<std::size_t>(e)]) >> 2;
    v += tet_volume_[t];
  }
  return 0.25 * v;
}

std::vector<double> LiquidPressure::volumes(const double* position) const {
  tetrahedron_volumes(position, false);
  std::vector<double> v(body_.particle_count(), 0.0);
  for (const std::int32_t a : node_) v[static_cast<std::size_t>(a)] = volume_of(static_cast<std::size_t>(a));
  return v;
}

std::vector<double> LiquidPressure::pressure(const double* position, const std::vector<double>& rest_volume) const {
  std::vector<double> p = volumes(position);
  for (const std::int32_t ai : node_) {
    const auto a = static_cast<std::size_t>(ai);
    p[a] = -body_.liquid.bulk_modulus * (p[a] - rest_volume[a]) / rest_volume[a];
  }
  return p;
}

void LiquidPressure::compute(const double* position, const std::vector<double>& rest_volume,
                             const std::vector<double>& support, bool parallel) {
  TIDALCRUST_ASSERT(rest_volume.size() == body_.particle_count(), "one rest volume per particle");
  TIDALCRUST_ASSERT(support.empty() || support.size() == 3 * body_.particle_count(), "one support force per particle");
  const double* fixed = support.empty() ? nullptr : support.data();
  tetrahedron_volumes(position, parallel);
  const auto& tets = body_.liquid.tetrahedra;
  const std::size_t nt = tets.size(), n = body_.particle_count(), nl = node_.size();
  const double bulk = body_.liquid.bulk_modulus;
#pragma omp parallel if (parallel)
  {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < nl; ++i) {
      const auto a = static_cast<std::size_t>(node_[i]);
      pressure_[a] = -bulk * (volume_of(a) - rest_volume[a]) / rest_volume[a];
    }
    // dE/dx_v = sum over corners a of -P_a dV_a/dx_v, dV_a/dx_v = dV_t/dx_v / 4: the force on
    // corner v is p_t dV_t/dx_v with p_t the mean of the four corners' pressures.
#pragma omp for schedule(static)
    for (std::size_t t = 0; t < nt; ++t) {
      const auto& c = tets[t];
      double p = 0;
      for (const std::int32_t v : c) p += pressure_[static_cast<std::size_t>(v)];
      p *= 0.25;
      const double* x0 = position + 3 * c[0];
      const double* x1 = position + 3 * c[1];
      const double* x2 = position + 3 * c[2];
      const double* x3 = position + 3 * c[3];
      const double a[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
      const double b[3] = {x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
      const double d[3] = {x3[0] - x0[0], x3[1] - x0[1], x3[2] - x0[2]};
      // dV/dx1 = (b x d)/6, dV/dx2 = (d x a)/6, dV/dx3 = (a x b)/6, dV/dx0 = -(sum of the three).
      const double g1[3] = {b[1] * d[2] - b[2] * d[1], b[2] * d[0] - b[0] * d[2], b[0] * d[1] - b[1] * d[0]};
      const double g2[3] = {d[1] * a[2] - d[2] * a[1], d[2] * a[0] - d[0] * a[2], d[0] * a[1] - d[1] * a[0]};
      const double g3[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
      double* f = corner_force_.data() + 12 * t;
      for (int k = 0; k < 3; ++k) {
        f[3 + k] = p * g1[k] / 6.0;
        f[6 + k] = p * g2[k] / 6.0;
        f[9 + k] = p * g3[k] / 6.0;
        f[k] = -(f[3 + k] + f[6 + k] + f[9 + k]);
      }
    }
#pragma omp for schedule(dynamic, 256)
    for (std::size_t q = 0; q < n; ++q) {
      double f[3] = {0, 0, 0};
      for (std::int32_t e = offset_[q]; e < offset_[q + 1]; ++e) {
        const double* fc = corner_force_.data() + 3 * static_cast<std::size_t>(corner_[static_cast<std::size_t>(e)]);
        for (int k = 0; k < 3; ++k) f[k] += fc[k];
      }
      if (fixed)
        for (int k = 0; k < 3; ++k) f[k] += fixed[3 * q + k];
      for (int k = 0; k < 3; ++k) force_[3 * q + k] = f[k];
    }
  }
}

double LiquidPressure::energy(const double* position, const std::vector<double>& rest_volume,
                              const std::vector<double>& support) const {
  tetrahedron_volumes(position, false);
  double e = 0;
  for (const std::int32_t ai : node_) {
    const auto a = static_cast<std::size_t>(ai);
    const double dv = volume_of(a) - rest_volume[a];
    e += 0.5 * body_.liquid.bulk_modulus * dv * dv / rest_volume[a];
  }
  return e + liquid_support_energy(support, position);
}

}  // namespace tidalcrust
