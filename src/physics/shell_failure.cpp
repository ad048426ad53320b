#include "physics/shell_failure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include <fmt/format.h>

#include <utility>

#include "base/errors.hpp"
#include "base/vec3.hpp"
#include "bodies/neighbor_grid.hpp"
#include "forces/spring_force.hpp"
#include "model/derived_quantities.hpp"

namespace tidalcrust {
namespace {

bool is_unfailed_shell(const Body& body, const State& state, std::size_t n) {
  return body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell) && !state.springs.failed[n];
}

}  // namespace

double spring_strain(const Body& body, const State& state, std::size_t n) {
  const auto i = static_cast<std::size_t>(body.springs[n][0]);
  const auto j = static_cast<std::size_t>(body.springs[n][1]);
  const double length = (vec3_at(state.position, i) - vec3_at(state.position, j)).norm();
  const double rest = state.springs.rest_length[n];
  return (length - rest) / rest;
}

double max_abs_shell_strain(const Body& body, const State& state) {
  double largest = 0;
  for (std::size_t n = 0; n < body.spring_count(); ++n)
    if (is_unfailed_shell(body, state, n)) largest = std::max(largest, std::abs(spring_strain(body, state, n)));
  return largest;
}

double max_shell_tension(const Body& body, const State& state) {
  double largest = 0;
  for (std::size_t n = 0; n < body.spring_count(); ++n)
    if (is_unfailed_shell(body, state, n)) largest = std::max(largest, spring_strain(body, state, n));
  return largest;
}

namespace {

Vec3 spring_midpoint(const Body& body, const State& state, std::size_t n) {
  const auto i = static_cast<std::size_t>(body.springs[n][0]);
  const auto j = static_cast<std::size_t>(body.springs[n][1]);
  return 0.5 * (vec3_at(state.position, i) + vec3_at(state.position, j));
}

/// Spring n fails now: stiffness *= F_Sk, failed = 1; the event to log.
FailureEvent fail_spring(const Body& body, State& state, std::size_t n, double strain, double failed_stiffness_factor) {
  const auto i = static_cast<std::size_t>(body.springs[n][0]);
  const auto j = static_cast<std::size_t>(body.springs[n][1]);
  // The energy budget's failure term: the spring's elastic energy at this strain before and
  // after its stiffness drops (the same evaluator as the force law; shell springs are linear).
  const double length = (vec3_at(state.position, i) - vec3_at(state.position, j)).norm();
  auto elastic_energy = [&] {
    return SpringEvaluator(state.springs.rest_length[n], state.springs.stiffness[n], 0.0).force_and_energy(length, 0).energy;
  };
  const double energy_before = elastic_energy();
  state.springs.stiffness[n] *= failed_stiffness_factor;
  state.springs.failed[n] = 1;
  const Vec3 mid = spring_midpoint(body, state, n);
  FailureEvent event;
  event.time = state.time;
  event.step = state.step;
  event.spring = static_cast<std::int32_t>(n);
  event.strain = strain;
  event.position = {mid.x(), mid.y(), mid.z()};
  event.released_energy = energy_before - elastic_energy();
  return event;
}

/// Where the failed shell springs are, for the shadow rule: their midpoints (in a grid) and axes.
/// A failed spring's crack runs across it, so a candidate extends that crack when its midpoint lies
/// within the crack neighbourhood (the exclusion distance) and at least 45 degrees off the failed
/// spring's axis (ahead of the crack, not on its flanks, which the opening unloads). A candidate
/// that extends no crack but has a failed spring within the shadow distance would start a new crack
/// in that crack's stress shadow.
class CrackMap {
 public:
  CrackMap(const Body& body, const State& state, double shadow_distance)
      : shadow_distance_(shadow_distance), grid_(grid_over(state, shadow_distance)) {
    for (std::size_t n = 0; n < body.spring_count(); ++n)
      if (body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell) && state.springs.failed[n])
        add(body, state, n);
  }
  /// True if a candidate at `mid` extends no crack (see above) and has a failed spring within the
  /// shadow distance.
  bool shadowed(const Vec3& mid, double neighbourhood) const {
    const std::vector<std::int32_t> near = grid_.closer_than(mid, shadow_distance_);
    for (const std::int32_t id : near) {
      const Vec3 offset = mid - grid_.point(id);
      const double distance = offset.norm();
      // cos 45 deg = 1/sqrt(2): |offset . axis| <= |offset| / sqrt(2), squared to avoid the root.
      const double along = offset.dot(axis_[static_cast<std::size_t>(id)]);
      if (distance < neighbourhood && 2 * along * along <= distance * distance) return false;
    }
    return !near.empty();
  }
  void add(const Body& body, const State& state, std::size_t n) {
    const auto i = static_cast<std::size_t>(body.springs[n][0]);
    const auto j = static_cast<std::size_t>(body.springs[n][1]);
    grid_.insert(spring_midpoint(body, state, n));
    axis_.push_back((vec3_at(state.position, j) - vec3_at(state.position, i)).normalized());
  }

 private:
  /// A grid over the particles' bounding box, cells of the shadow distance (at most 64 a side).
  static NeighborGrid grid_over(const State& state, double shadow_distance) {
    Vec3 lo = vec3_at(state.position, 0), hi = lo;
    for (std::size_t i = 1; i < state.position.size() / 3; ++i) {
      const Vec3 p = vec3_at(state.position, i);
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    return NeighborGrid(lo, hi, std::max(shadow_distance, (hi - lo).maxCoeff() / 64));
  }

  double shadow_distance_;
  NeighborGrid grid_;        // midpoints; points outside its box are found too, only more slowly
  std::vector<Vec3> axis_;   // unit axis of each failed spring, by grid id
};

/// The local rule's check: candidates beyond eps_S by decreasing strain (index on ties); one
/// fails unless a failure of the last relaxation_steps steps (or of this check) lies within
/// exclusion_distance of it (midpoints, current positions). With a shadow distance (> 0, the
/// shadow rule) a candidate that extends no crack (CrackMap) also waits while any failed shell
/// spring lies within the shadow distance.
std::size_t fail_local(const LocalFailureRule& rule, double shadow_distance, const FailureThreshold& threshold,
                       const Body& body, State& state, std::vector<FailureEvent>& log) {
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (!is_unfailed_shell(body, state, n)) continue;
    const double strain = spring_strain(body, state, n);
    if (strain > threshold.failure_strain) candidates.emplace_back(strain, n);
  }
  if (candidates.empty()) return 0;
  std::sort(candidates.begin(), candidates.end(),
            [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  // Midpoints of the failures still relaxing (the log is in step order: scan from its end).
  std::vector<Vec3> relaxing;
  for (auto e = log.rbegin(); e != log.rend() && e->step > state.step - rule.relaxation_steps; ++e)
    relaxing.push_back(spring_midpoint(body, state, static_cast<std::size_t>(e->spring)));
  std::optional<CrackMap> cracks;
  if (shadow_distance > 0) cracks.emplace(body, state, shadow_distance);
  const double r2 = rule.exclusion_distance * rule.exclusion_distance;
  std::size_t failed = 0;
  for (const auto& [strain, n] : candidates) {
    const Vec3 mid = spring_midpoint(body, state, n);
    const bool excluded =
        std::any_of(relaxing.begin(), relaxing.end(), [&](const Vec3& p) { return (p - mid).squaredNorm() < r2; });
    if (excluded || (cracks && cracks->shadowed(mid, rule.exclusion_distance))) continue;
    log.push_back(fail_spring(body, state, n, strain, threshold.failed_stiffness_factor));
    relaxing.push_back(mid);
    if (cracks) cracks->add(body, state, n);
    ++failed;
  }
  return failed;
}

}  // namespace

FailureRule make_failure_rule(const Config& config, std::optional<double> relaxation_crossings, const Body& body,
                              const State& state, double dt) {
  switch (config.encounter.failure_rule) {
    case FailureRuleKind::paper:
      break;
    case FailureRuleKind::local:
    case FailureRuleKind::shadow: {
      // A body without a crust has nothing to fail: the (default) local rule needs no shell there.
      if (body.count_species(Species::shell) == 0) break;
      const DerivedQuantities q = derive_quantities(body, state, config.interior.radius);
      if (!(q.L_S > 0) || !(q.V_SP > 0))
        throw InputError(fmt::format("encounter.failure_rule = \"{}\" needs a shell (no shell springs in this body)",
                                     choice_name(config.encounter.failure_rule)));
      const double crossing_time = q.L_S / q.V_SP;
      LocalFailureRule rule;
      rule.relaxation_steps = std::max<std::int64_t>(
          1, std::llround(relaxation_crossings.value_or(config.encounter.relaxation_crossings) * crossing_time / dt));
      rule.exclusion_distance = config.encounter.exclusion_radius * q.L_S;
      rule.configured_fail_interval = config.encounter.fail_interval;
      if (config.encounter.failure_rule == FailureRuleKind::shadow)
        return ShadowFailureRule{rule, config.encounter.shadow_distance};
      return rule;
    }
  }
  return PaperFailureRule{config.encounter.fail_interval};
}

std::size_t apply_failure_rule(const FailureRule& rule, const FailureThreshold& threshold, const Body& body,
                               State& state, std::int64_t start_step, std::vector<FailureEvent>& log) {
  if (const auto* local = std::get_if<LocalFailureRule>(&rule)) return fail_local(*local, 0.0, threshold, body, state, log);
  if (const auto* shadow = std::get_if<ShadowFailureRule>(&rule))
    return fail_local(shadow->local, shadow->shadow_distance, threshold, body, state, log);
  if ((state.step - start_step) % std::get<PaperFailureRule>(rule).fail_interval != 0) return 0;
  auto event = fail_most_strained_shell_spring(body, state, threshold.failure_strain, threshold.failed_stiffness_factor);
  if (!event) return 0;
  log.push_back(*event);
  return 1;
}

std::optional<FailureEvent> fail_most_strained_shell_spring(const Body& body, State& state, double failure_strain,
                                                            double failed_stiffness_factor) {
  std::optional<std::size_t> worst;
  double worst_strain = failure_strain;
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (!is_unfailed_shell(body, state, n)) continue;
    const double strain = spring_strain(body, state, n);
    if (strain > worst_strain) {  // strict: ties keep the lowest index
      worst_strain = strain;
      worst = n;
    }
  }
  if (!worst) return std::nullopt;
  return fail_spring(body, state, *worst, worst_strain, failed_stiffness_factor);
}

}  // namespace tidalcrust
