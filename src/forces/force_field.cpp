#include "forces/force_field.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "base/invariant.hpp"
#include "forces/hinge_force_x8.hpp"
#include "forces/perturber_gravity.hpp"

namespace tidalcrust {
namespace {

Vec3 point(const double* position, std::int32_t i) {
  const double* p = position + 3 * static_cast<std::size_t>(i);
  return {p[0], p[1], p[2]};
}

/// CSR incidence from a list of (particle, entry) pairs visited in entry order.
void build_incidence(std::size_t particles, const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs,
                     std::vector<std::int32_t>& offset, std::vector<std::int32_t>& entry) {
  offset.assign(particles + 1, 0);
  for (const auto& [p, e] : pairs) ++offset[static_cast<std::size_t>(p) + 1];
  for (std::size_t p = 0; p < particles; ++p) offset[p + 1] += offset[p];
  entry.resize(pairs.size());
  std::vector<std::int32_t> fill(offset.begin(), offset.end() - 1);
  for (const auto& [p, e] : pairs) entry[static_cast<std::size_t>(fill[static_cast<std::size_t>(p)]++)] = e;
}

void check_index(std::int32_t index, std::size_t particles, const char* what, std::size_t element) {
  // The checkpoint reader and the builders check indices: a bad one here is a bug.
  TIDALCRUST_ASSERT(index >= 0 && static_cast<std::size_t>(index) < particles,
                    fmt::format("{} {} refers to particle {}, but the body has {} particles", what, element, index,
                                particles));
}

}  // namespace

ForceOptions force_options(const Config& config, double damping) {
  ForceOptions options;
  options.damping = damping;
  options.cross_nonlinear = config.cross.nonlinear;
  options.cross_strain_scale = config.cross.strain_scale;
  options.cross_min_force_factor = config.cross.min_force_factor;
  options.gravity_kernel = config.gravity.kernel;
  options.gravity_method = config.gravity.method;
  options.force_error = config.gravity.force_error;
  return options;
}

ForceField::ForceField(const Body& body, ForceOptions options)
    : body_(body),
      options_(options),
      cross_{options.cross_strain_scale, options.cross_min_force_factor} {
  if (options.gravity_method == GravityMethod::tree)
    tree_.emplace(body.mass, body.softening, options.force_error, options.gravity_kernel);
  else
    gravity_.emplace(body.mass, body.softening, options.gravity_kernel);
  if (body.liquid.present()) liquid_.emplace(body);
  const std::size_t n = body.particle_count(), ns = body.spring_count(), nh = body.hinge_count();
  TIDALCRUST_ASSERT(body.spring_kind.size() == ns,
                    fmt::format("body has {} springs but {} spring kinds", ns, body.spring_kind.size()));
  reduced_mass_.resize(ns);
  nonlinear_.resize(ns);
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  pairs.reserve(2 * ns);
  for (std::size_t s = 0; s < ns; ++s) {
    const auto [i, j] = body.springs[s];
    check_index(i, n, "spring", s);
    check_index(j, n, "spring", s);
    reduced_mass_[s] = reduced_mass(body.mass[static_cast<std::size_t>(i)], body.mass[static_cast<std::size_t>(j)]);
    nonlinear_[s] = options.cross_nonlinear && body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::cross);
    pairs.emplace_back(i, static_cast<std::int32_t>(2 * s));
    pairs.emplace_back(j, static_cast<std::int32_t>(2 * s + 1));
  }
  build_incidence(n, pairs, spring_offset_, spring_entry_);
  pairs.clear();
  for (std::size_t h = 0; h < nh; ++h)
    for (std::size_t v = 0; v < 4; ++v) {
      check_index(body.hinges[h][v], n, "hinge", h);
      pairs.emplace_back(body.hinges[h][v], static_cast<std::int32_t>(4 * h + v));
    }
  build_incidence(n, pairs, hinge_offset_, hinge_entry_);
  spring_force_.assign(3 * ns, 0.0);
  hinge_force_.assign(12 * nh, 0.0);
  spring_damping_.assign(ns, 0.0);
  hinge_work_rate_.assign(nh, 0.0);
}

template <typename Visit>
void ForceField::for_each_spring(std::size_t begin, std::size_t end, const double* position, const double* velocity,
                                 const SpringState& springs, Visit&& visit) const {
  const auto* ends = body_.springs.data();
  const double* rest = springs.rest_length.data();
  const double* stiffness = springs.stiffness.data();
  const double damping = options_.damping;  // gamma, the same for every spring
  const double* mu = reduced_mass_.data();
  const std::uint8_t* nonlinear = nonlinear_.data();
  for (std::size_t s = begin; s < end; ++s) {
    const std::size_t i = 3 * static_cast<std::size_t>(ends[s][0]), j = 3 * static_cast<std::size_t>(ends[s][1]);
    const double d[3] = {position[i] - position[j], position[i + 1] - position[j + 1],
                         position[i + 2] - position[j + 2]};
    const double dv[3] = {velocity[i] - velocity[j], velocity[i + 1] - velocity[j + 1],
                          velocity[i + 2] - velocity[j + 2]};
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const SpringEvaluator spring(rest[s], stiffness[s], damping * mu[s], nonlinear[s] ? &cross_ : nullptr);
    visit(s, d, spring.force_and_energy(length, d[0] * dv[0] + d[1] * dv[1] + d[2] * dv[2]));
  }
}

template <typename Visit>
void ForceField::for_each_hinge(std::size_t begin, std::size_t end, const double* position, Visit&& visit) const {
  const auto* corners = body_.hinges.data();
  const double* stiffness = body_.hinge_stiffness.data();  // k_e of each hinge
  const HalfRestAngle* rest = half_rest_.data();
  for (std::size_t h = begin; h < end; ++h) {
    const auto& c = corners[h];
    visit(h, HingeEvaluator(rest[h], stiffness[h])
                 .force_and_energy(point(position, c[0]), point(position, c[1]), point(position, c[2]),
                                   point(position, c[3])));
  }
}

void ForceField::spring_range(std::size_t begin, std::size_t end, const double* position, const double* velocity,
                              const SpringState& springs) {
  double* force = spring_force_.data();
  double* damping = spring_damping_.data();
  for_each_spring(begin, end, position, velocity, springs,
                  [force, damping](std::size_t s, const double* d, const SpringForceEnergy& spring) {
                    for (std::size_t k = 0; k < 3; ++k) force[3 * s + k] = -spring.coefficient * d[k];
                    damping[s] = spring.damping_coefficient;
                  });
}

std::int64_t ForceField::hinge_range(std::size_t begin, std::size_t end, const double* position) {
  double* force = hinge_force_.data();
  double* work_rate = hinge_work_rate_.data();
  std::int64_t collapsed = -1;
#if defined(__AVX512F__)
  static_assert(sizeof(HalfRestAngle) == 2 * sizeof(double) && sizeof(body_.hinges[0]) == 4 * sizeof(std::int32_t));
  // Eight at a time, the same bits as the evaluator (hinge_force_x8.hpp); the rest one by one.
  for (; begin + 8 <= end; begin += 8) {
    const unsigned lanes = hinge_forces_x8(begin, body_.hinges[0].data(), position, half_rest_.data(),
                                           body_.hinge_stiffness.data(), force, work_rate);
    if (lanes != 0 && collapsed < 0) collapsed = static_cast<std::int64_t>(begin) + __builtin_ctz(lanes);
  }
#endif
  for_each_hinge(begin, end, position, [force, work_rate, &collapsed](std::size_t h, const HingeForces& f) {
    if (f.collapsed && collapsed < 0) collapsed = static_cast<std::int64_t>(h);
    work_rate[h] = f.energy_per_prefactor;
    for (std::size_t v = 0; v < 4; ++v)
      for (std::size_t k = 0; k < 3; ++k) force[12 * h + 3 * v + k] = f.on[v][k];
  });
  return collapsed;
}

void ForceField::gather(std::size_t p, bool with_gravity, double* acceleration) const {
  double f[3] = {0, 0, 0};
  for (std::int32_t e = spring_offset_[p]; e < spring_offset_[p + 1]; ++e) {
    const std::int32_t slot = spring_entry_[static_cast<std::size_t>(e)];
    const double* fs = spring_force_.data() + 3 * static_cast<std::size_t>(slot >> 1);
    // +F on the first particle, -F on the second; f + (-1 * F) is bitwise f - F, and no branch.
    const double sign = (slot & 1) ? -1.0 : 1.0;
    for (int k = 0; k < 3; ++k) f[k] += sign * fs[k];
  }
  for (std::int32_t e = hinge_offset_[p]; e < hinge_offset_[p + 1]; ++e) {
    const double* fh = hinge_force_.data() + 3 * static_cast<std::size_t>(hinge_entry_[static_cast<std::size_t>(e)]);
    for (int k = 0; k < 3; ++k) f[k] += fh[k];
  }
  if (liquid_)
    for (int k = 0; k < 3; ++k) f[k] += liquid_->forces()[3 * p + k];
  const double inv_mass = 1.0 / body_.mass[p];
  double g[3] = {0, 0, 0};
  if (with_gravity) {
    if (tree_) tree_->acceleration(p, g);
    else gravity_->sum_blocks(p, g);
  }
  for (int k = 0; k < 3; ++k) acceleration[3 * p + k] = f[k] * inv_mass + g[k];
}

void ForceField::compute_spring_forces(const double* position, const double* velocity, const SpringState& springs) {
  const std::size_t ns = body_.spring_count();
  const std::size_t chunks = (ns + spring_chunk - 1) / spring_chunk;
#pragma omp parallel for schedule(static) if (ns >= options_.min_parallel_items)
  for (std::size_t c = 0; c < chunks; ++c)
    spring_range(c * spring_chunk, std::min(ns, (c + 1) * spring_chunk), position, velocity, springs);
}

void ForceField::refresh_half_rest_angles(const HingeState& hinges) {
  const std::size_t nh = body_.hinge_count();
  if (cached_rest_angle_.size() != nh) {
    cached_rest_angle_.assign(nh, std::nan(""));  // NaN never compares equal: all recomputed
    half_rest_.resize(nh);
  }
  for (std::size_t h = 0; h < nh; ++h) {
    // Bitwise comparison: the table is a pure function of the rest angle's bits.
    if (std::memcmp(&cached_rest_angle_[h], &hinges.rest_angle[h], sizeof(double)) != 0) {
      cached_rest_angle_[h] = hinges.rest_angle[h];
      half_rest_[h] = HalfRestAngle::of(hinges.rest_angle[h], uses_portable_math(options_.gravity_kernel));
    }
  }
}

std::int64_t ForceField::compute_hinge_forces(const double* position, const HingeState& hinges) {
  refresh_half_rest_angles(hinges);
  const std::size_t nh = body_.hinge_count();
  const std::size_t chunks = (nh + hinge_chunk - 1) / hinge_chunk;
  std::int64_t collapsed = std::numeric_limits<std::int64_t>::max();
#pragma omp parallel for schedule(static) reduction(min : collapsed) if (4 * nh >= options_.min_parallel_items)
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::int64_t h = hinge_range(c * hinge_chunk, std::min(nh, (c + 1) * hinge_chunk), position);
    if (h >= 0) collapsed = std::min(collapsed, h);
  }
  return collapsed == std::numeric_limits<std::int64_t>::max() ? -1 : collapsed;
}

void ForceField::check_sizes(const SpringState& springs, const HingeState& hinges) const {
  const std::size_t ns = body_.spring_count(), nh = body_.hinge_count();
  // The checkpoint reader checks every dataset's shape: a mismatch here is a bug.
  TIDALCRUST_ASSERT(springs.rest_length.size() == ns && springs.stiffness.size() == ns &&
                        hinges.rest_angle.size() == nh && body_.hinge_stiffness.size() == nh,
                    fmt::format("state does not match the body: {} springs and {} hinges in the body, "
                                 "{} rest lengths, {} stiffnesses, {} rest angles in the state, "
                                 "{} hinge stiffnesses in the body",
                                 ns, nh, springs.rest_length.size(), springs.stiffness.size(),
                                 hinges.rest_angle.size(), body_.hinge_stiffness.size()));
}

ForceAlarms ForceField::compute(const double* position, const double* velocity, const SpringState& springs,
                                const HingeState& hinges, const Perturber& perturber,
                                const std::vector<double>& liquid_rest_volume,
                                const std::vector<double>& liquid_support, Accelerations& out) {
  check_sizes(springs, hinges);
  const std::size_t n = body_.particle_count(), ns = body_.spring_count(), nh = body_.hinge_count();
  out.body.resize(3 * n);
  // The liquid's passes (volumes, pressures, corner forces, gather) come first.
  if (liquid_)
    liquid_->compute(position, liquid_rest_volume, liquid_support, n * n / 128 + ns + 4 * nh >= options_.min_parallel_items);
  refresh_half_rest_angles(hinges);
  const bool self_gravity = options_.self_gravity;
  TreeGravity* tree = self_gravity && tree_ ? &*tree_ : nullptr;
  if (tree) tree->prepare(position);  // Morton order and nodes, a pure function of the positions
  else if (self_gravity) gravity_->load_positions(position);

  // One parallel region per pass, with as few barriers as possible (a thread that the OS pauses,
  // other jobs on the cores, holds up the others at each one): first every piece of work that
  // needs no other from one dynamic queue (the tree's moment tasks or the direct sum's blocks,
  // then spring and hinge chunks); with the tree, one thread then finishes its top nodes, and
  // each chunk of groups is walked and its particles gathered at once; with the direct sum the
  // per-particle gather follows. Every result is written per particle or per element, summed
  // in a fixed order: the same bits for any thread count and schedule.
  const std::size_t first_items =
      tree ? tree->moment_task_count() : self_gravity ? static_cast<std::size_t>(DirectGravity::block_count) : 0;
  const std::size_t spring_items = (ns + spring_chunk - 1) / spring_chunk;
  const std::size_t hinge_items = (nh + hinge_chunk - 1) / hinge_chunk;
  const std::size_t items = first_items + spring_items + hinge_items;
  const bool parallel = n * n / 128 + ns + 4 * nh >= options_.min_parallel_items;
  std::int64_t collapsed = std::numeric_limits<std::int64_t>::max();
  double* acc = out.body.data();
#pragma omp parallel if (parallel)
  {
#pragma omp for schedule(dynamic, 1) reduction(min : collapsed)
    for (std::size_t item = 0; item < items; ++item) {
      if (item < first_items) {
        if (tree) tree->moment_task(item);
        else gravity_->accumulate_block(static_cast<int>(item));
      } else if (item < first_items + spring_items) {
        const std::size_t c = item - first_items;
        spring_range(c * spring_chunk, std::min(ns, (c + 1) * spring_chunk), position, velocity, springs);
      } else {
        const std::size_t c = item - first_items - spring_items;
        const std::int64_t h = hinge_range(c * hinge_chunk, std::min(nh, (c + 1) * hinge_chunk), position);
        if (h >= 0) collapsed = std::min(collapsed, h);
      }
    }
    if (tree) {
#pragma omp single
      tree->finish_build();
      const std::size_t chunks = tree->chunk_count();
#pragma omp for schedule(dynamic, 1)
      for (std::size_t c = 0; c < chunks; ++c) {
        tree->accumulate_chunk(c);
        for (std::size_t k = tree->chunk_begin(c); k < tree->chunk_end(c); ++k) gather(tree->original_index(k), true, acc);
      }
    } else {
#pragma omp for schedule(dynamic, 256)
      for (std::size_t p = 0; p < n; ++p) gather(p, self_gravity, acc);
    }
  }
  ForceAlarms alarms;
  alarms.collapsed_hinge = collapsed == std::numeric_limits<std::int64_t>::max() ? -1 : collapsed;

  out.perturber = {0, 0, 0};
  if (perturber.present)
    out.perturber = add_perturber_gravity(body_.mass, body_.softening, position, perturber, acc);

  for (std::size_t p = 0; p < n; ++p)
    if (!std::isfinite(acc[3 * p] + acc[3 * p + 1] + acc[3 * p + 2])) {
      alarms.nonfinite_particle = static_cast<std::int64_t>(p);
      break;
    }
  if (!std::isfinite(out.perturber[0] + out.perturber[1] + out.perturber[2]) && alarms.nonfinite_particle < 0)
    alarms.nonfinite_particle = 0;  // the perturber only blows up together with some particle
  return alarms;
}

Energies ForceField::energies(const double* position, const double* velocity, const SpringState& springs,
                              const HingeState& hinges, const Perturber& perturber,
                              const std::vector<double>& liquid_rest_volume,
                              const std::vector<double>& liquid_support) {
  check_sizes(springs, hinges);
  refresh_half_rest_angles(hinges);
  Energies e;
  if (liquid_) e.liquid = liquid_->energy(position, liquid_rest_volume, liquid_support);
  for_each_spring(0, body_.spring_count(), position, velocity, springs,
                  [&e](std::size_t, const double*, const SpringForceEnergy& spring) {
                    e.spring += spring.energy;
                    e.damping_power += spring.dissipated_power;
                  });
  for_each_hinge(0, body_.hinge_count(), position, [&e](std::size_t, const HingeForces& f) { e.hinge += f.energy; });
  if (options_.self_gravity)
    e.self_gravity = tree_ ? tree_->potential_energy(position)
                           : self_gravity_energy(body_.mass, body_.softening, position);
  e.perturber = perturber_energy(body_.mass, body_.softening, position, perturber);
  return e;
}

StepWork ForceField::work_of_step(const double* start, const double* half, const double* end) const {
  StepWork work;
  const std::size_t ns = body_.spring_count();
  if (options_.damping != 0) {
    for (std::size_t s = 0; s < ns; ++s) {
      const std::size_t i = 3 * static_cast<std::size_t>(body_.springs[s][0]);
      const std::size_t j = 3 * static_cast<std::size_t>(body_.springs[s][1]);
      double d_dot_change = 0;  // d_half . ((x_i - x_j)_end - (x_i - x_j)_start)
      for (std::size_t k = 0; k < 3; ++k)
        d_dot_change += (half[i + k] - half[j + k]) * ((end[i + k] - start[i + k]) - (end[j + k] - start[j + k]));
      work.damping_removed += spring_damping_[s] * d_dot_change;
    }
  }
  for (std::size_t h = 0; h < body_.hinge_count(); ++h) {
    if (hinge_work_rate_[h] == 0) continue;  // at rest angle (or k_e = 0): no work
    const auto& c = body_.hinges[h];
    const double change = hinge_prefactor(point(end, c[0]), point(end, c[1]), point(end, c[2]), point(end, c[3])) -
                          hinge_prefactor(point(start, c[0]), point(start, c[1]), point(start, c[2]), point(start, c[3]));
    work.hinge_added += hinge_work_rate_[h] * change;
  }
  return work;
}

std::string ForceField::describe(const ForceAlarms& alarms, const double* position) const {
  std::string what;
  if (alarms.collapsed_hinge >= 0) {
    const auto h = static_cast<std::size_t>(alarms.collapsed_hinge);
    const auto& c = body_.hinges[h];
    const Vec3 x1 = point(position, c[0]), x2 = point(position, c[1]), x3 = point(position, c[2]),
               x4 = point(position, c[3]);
    const double l2 = (x4 - x3).squaredNorm();
    const double a1 = (x1 - x3).cross(x1 - x4).norm(), a2 = (x2 - x4).cross(x2 - x3).norm();
    what = fmt::format("hinge {} (wings {}, {}, edge {}-{}): a shell triangle collapsed (|N|/L^2 = {:.3g} and "
                       "{:.3g}, limit {:.0e})",
                       h, c[0], c[1], c[2], c[3], a1 / l2, a2 / l2, collapsed_face_fraction);
  } else if (alarms.nonfinite_particle >= 0) {
    const auto p = static_cast<std::size_t>(alarms.nonfinite_particle);
    std::string source = "gravity or the perturber";
    for (std::int32_t e = spring_offset_[p]; e < spring_offset_[p + 1]; ++e) {
      const std::size_t s = static_cast<std::size_t>(spring_entry_[e] >> 1);
      if (!std::isfinite(spring_force_[3 * s] + spring_force_[3 * s + 1] + spring_force_[3 * s + 2])) {
        source = fmt::format("spring {} ({}-{})", s, body_.springs[s][0], body_.springs[s][1]);
        break;
      }
    }
    what = fmt::format("particle {} ({}) has a non-finite acceleration, first from {}", p,
                       species_name(body_.species[p]), source);
  } else {
    what = "no force alarm";
  }
  return what;
}

}  // namespace tidalcrust
