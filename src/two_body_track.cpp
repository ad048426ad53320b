#include "two_body_track.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tidalcrust {

namespace {
struct Phase {
  Vec3 r, v;
};

Phase derivative(const Phase& p, double mu) {
  const double d = p.r.norm();
  return {p.v, -mu / (d * d * d) * p.r};
}

Phase rk4_step(const Phase& p, double h, double mu) {
  auto advance = [](const Phase& base, const Phase& slope, double step) {
    return Phase{base.r + step * slope.r, base.v + step * slope.v};
  };
  const Phase k1 = derivative(p, mu);
  const Phase k2 = derivative(advance(p, k1, 0.5 * h), mu);
  const Phase k3 = derivative(advance(p, k2, 0.5 * h), mu);
  const Phase k4 = derivative(advance(p, k3, h), mu);
  return {p.r + h / 6 * (k1.r + 2 * k2.r + 2 * k3.r + k4.r), p.v + h / 6 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v)};
}

constexpr double max_step = 1e-3;
}  // namespace

std::vector<Vec3> two_body_track(double perturber_mass, double pericenter, double pericenter_speed,
                                 double pericenter_time, const std::vector<double>& times) {
  const double mu = 1.0 + perturber_mass;
  const Phase at_pericenter{Vec3(0, pericenter, 0), Vec3(-pericenter_speed, 0, 0)};
  std::vector<Vec3> track(times.size());
  std::vector<std::size_t> order(times.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(times[a] - pericenter_time) < std::abs(times[b] - pericenter_time);
  });
  // Two marches outward from pericenter, one per direction of time, each visiting its
  // requested times in order of distance from pericenter.
  for (const double direction : {1.0, -1.0}) {
    Phase phase = at_pericenter;
    double elapsed = 0;  // |t - t_peri| reached so far
    for (const std::size_t i : order) {
      const double offset = times[i] - pericenter_time;
      if ((direction > 0) != (offset >= 0)) continue;
      const double target = std::abs(offset);
      const double span = target - elapsed;
      const auto steps = static_cast<long>(std::ceil(span / max_step));
      for (long k = 0; k < steps; ++k) phase = rk4_step(phase, direction * span / static_cast<double>(steps), mu);
      elapsed = target;
      track[i] = phase.r;
    }
  }
  return track;
}

}  // namespace tidalcrust
