#include "physics/shell_failure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <string>
#include <utility>
#include <vector>

#include "base/errors.hpp"
#include "base/vec3.hpp"
#include "bodies/neighbor_grid.hpp"
#include "forces/spring_force.hpp"
#include "model/center_of_mass.hpp"
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

/// What a candidate would do to the cracks (CrackMap::role).
enum class CrackRole {
  extends,   ///< a failed spring within the crack neighbourhood, the candidate ahead of it
  starts,    ///< no failed spring within the shadow distance: a new crack
  shadowed,  ///< extends no crack but lies in a crack's stress shadow
};

/// A grid over the particles' bounding box with cells of `cell_size` (at most 64 a side), for the
/// crack rules' neighbour queries between spring midpoints.
NeighborGrid grid_over_particles(const State& state, double cell_size) {
  Vec3 lo = vec3_at(state.position, 0), hi = lo;
  for (std::size_t i = 1; i < state.position.size() / 3; ++i) {
    const Vec3 p = vec3_at(state.position, i);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return NeighborGrid(lo, hi, std::max(cell_size, (hi - lo).maxCoeff() / 64));
}

/// Where the failed shell springs are, for the shadow and griffith rules: their midpoints (in a
/// grid) and axes. A failed spring's crack runs across it, so a candidate extends that crack when
/// its midpoint lies within the crack neighbourhood (the exclusion distance) and at least 45
/// degrees off the failed spring's axis (ahead of the crack, not on its flanks, which the opening
/// unloads). A candidate that extends no crack but has a failed spring within the shadow distance
/// would start a new crack in that crack's stress shadow. The crack a candidate extends is looked
/// for within `search_radius`: the shadow rule's is its shadow distance (as measured in
/// docs/results, though a neighbourhood wider than the shadow then sees less), the griffith
/// rule's the larger of the two.
class CrackMap {
 public:
  CrackMap(const Body& body, const State& state, double shadow_distance, double neighbourhood, double search_radius)
      : shadow_distance_(shadow_distance),
        neighbourhood_(neighbourhood),
        search_radius_(search_radius),
        grid_(grid_over_particles(state, shadow_distance)) {
    for (std::size_t n = 0; n < body.spring_count(); ++n)
      if (body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell) && state.springs.failed[n])
        add(body, state, n);
  }
  /// With `candidate_axis` (the nonlocal rule: the candidate's unit axis), "ahead" is judged
  /// against it instead of the failed spring's, and for the crack as a whole: a candidate extends
  /// when the mean offset to the failed springs within the neighbourhood lies at least 45 degrees
  /// off its own axis (the crack lies across it, behind its tip, where its segment continues the
  /// crack), and is in the crack's shadow otherwise. Judged spring by spring, a candidate on a
  /// crack's flank, pulled across it, finds failed springs further along the crack more than 45
  /// degrees off its axis whenever the neighbourhood is wider than its distance from the crack, and
  /// opened a parallel crack there, as many lattice rows beside it as the neighbourhood holds; a
  /// crack drawn on the lattice zig-zags over springs of all three directions, so neither a failed
  /// spring's own axis nor the nearest one's offset is the crack's normal. `crack_point`, when
  /// given, receives the midpoint of the failed spring a candidate extends (with `candidate_axis`:
  /// the nearest within the neighbourhood, the tip).
  CrackRole role(const Vec3& mid, const Vec3* candidate_axis = nullptr, Vec3* crack_point = nullptr) const {
    if (candidate_axis) return role_across(mid, *candidate_axis, crack_point);
    bool in_shadow = false;
    for (const std::int32_t id : grid_.closer_than(mid, search_radius_)) {
      const Vec3 offset = mid - grid_.point(id);
      const double distance = offset.norm();
      // cos 45 deg = 1/sqrt(2): |offset . axis| <= |offset| / sqrt(2), squared to avoid the root.
      const double along = offset.dot(candidate_axis ? *candidate_axis : axis_[static_cast<std::size_t>(id)]);
      if (distance < neighbourhood_ && 2 * along * along <= distance * distance) {
        if (crack_point) *crack_point = grid_.point(id);
        return CrackRole::extends;
      }
      in_shadow = in_shadow || distance < shadow_distance_;
    }
    return in_shadow ? CrackRole::shadowed : CrackRole::starts;
  }
  void add(const Body& body, const State& state, std::size_t n) {
    const auto i = static_cast<std::size_t>(body.springs[n][0]);
    const auto j = static_cast<std::size_t>(body.springs[n][1]);
    grid_.insert(spring_midpoint(body, state, n));
    axis_.push_back((vec3_at(state.position, j) - vec3_at(state.position, i)).normalized());
  }
  /// Whether a failed spring's midpoint lies closer than the crack neighbourhood to `mid`.
  bool in_neighbourhood(const Vec3& mid) const { return grid_.any_closer_than(mid, neighbourhood_); }

 private:
  CrackRole role_across(const Vec3& mid, const Vec3& axis, Vec3* crack_point) const {
    bool in_shadow = false;
    Vec3 offset_sum = Vec3::Zero();  // summed in the grid's order: the same bits for any thread count
    std::int32_t nearest = -1;
    double nearest_distance = 0;
    for (const std::int32_t id : grid_.closer_than(mid, search_radius_)) {
      const Vec3 offset = mid - grid_.point(id);
      const double distance = offset.norm();
      in_shadow = in_shadow || distance < shadow_distance_;
      if (!(distance < neighbourhood_)) continue;
      offset_sum += offset;
      if (nearest < 0 || distance < nearest_distance || (distance == nearest_distance && id < nearest)) {
        nearest = id;
        nearest_distance = distance;
      }
    }
    if (nearest < 0) return in_shadow ? CrackRole::shadowed : CrackRole::starts;
    // cos 45 deg = 1/sqrt(2): |m . axis| <= |m| / sqrt(2) for the mean offset m, squared (the
    // count cancels; a sum of zero, a candidate midway between two cracks' ends in line, extends).
    const double along = offset_sum.dot(axis);
    if (!(2 * along * along <= offset_sum.squaredNorm())) return CrackRole::shadowed;
    if (crack_point) *crack_point = grid_.point(nearest);
    return CrackRole::extends;
  }

  double shadow_distance_;
  double neighbourhood_;
  double search_radius_;
  NeighborGrid grid_;        // midpoints; points outside its box are found too, only more slowly
  std::vector<Vec3> axis_;   // unit axis of each failed spring, by grid id
};

/// The great-circle segment of a flaw (the griffith rule) or of an averaging segment (the
/// critical_distance rule) at spring n: the arc of the circle about `center` through n's midpoint
/// m, perpendicular to n's axis, whose points r lie within length / 2 of m as rho |sin theta|
/// (rho = |m - center|, theta the angle from m; no transcendental function, so the same bits on
/// every CPU). Spring n itself crosses it. ahead_of(p) keeps only the part from p's abscissa on
/// towards the side away from p (a crack's tip advancing away from its crack, with no gap behind).
class GreatCircleSegment {
 public:
  GreatCircleSegment(const Body& body, const State& state, std::size_t n, const Vec3& center, double length)
      : GreatCircleSegment(center, spring_midpoint(body, state, n),
                           vec3_at(state.position, static_cast<std::size_t>(body.springs[n][1])) -
                               vec3_at(state.position, static_cast<std::size_t>(body.springs[n][0])),
                           length) {}
  /// The arc through `mid` perpendicular to `axis` (any length; its tangential part is used).
  GreatCircleSegment(const Vec3& center, const Vec3& mid, const Vec3& axis, double length)
      : center_(center), length_(length) {
    const Vec3 m = mid - center;
    rho_ = m.norm();
    up_ = m / rho_;
    normal_ = axis - axis.dot(up_) * up_;  // the circle's plane normal: the axis, tangential part
    normal_.normalize();
    along_ = normal_.cross(up_);
  }
  /// Whether spring k's ends lie on opposite sides of the circle's plane with the crossing point
  /// on the segment.
  bool crossed_by(const Body& body, const State& state, std::size_t k) const {
    const Vec3 p = vec3_at(state.position, static_cast<std::size_t>(body.springs[k][0])) - center_;
    const Vec3 q = vec3_at(state.position, static_cast<std::size_t>(body.springs[k][1])) - center_;
    const double sp = p.dot(normal_), sq = q.dot(normal_);
    if (!(sp * sq < 0)) return false;
    const Vec3 r = p + (q - p) * (sp / (sp - sq));
    if (!(r.dot(up_) > 0)) return false;
    const double sideways = rho_ * r.dot(along_);  // rho sin(theta) |r|
    if (side_ != 0 && !(side_ * sideways >= start_ * r.norm())) return false;
    return 4 * sideways * sideways <= length_ * length_ * r.squaredNorm();
  }
  void ahead_of(const Vec3& p) {
    const Vec3 r = p - center_;
    const double sideways = rho_ * r.dot(along_) / r.norm();  // m itself has none
    side_ = sideways > 0 ? -1 : 1;
    start_ = side_ * sideways;  // <= 0: from p's side of m onward
  }

 private:
  Vec3 center_;
  double length_;
  int side_ = 0;  // 0: both halves; +1 or -1: from start_ on towards where rho sin(theta) has that sign
  double start_ = 0;
  double rho_ = 0;
  Vec3 up_, normal_, along_;
};

/// The unfailed shell springs, in index order, across the flaw a new crack opens at spring n (the
/// griffith rule): every spring is tested.
std::vector<std::size_t> springs_across_flaw(const Body& body, const State& state, std::size_t n, const Vec3& center,
                                             double flaw_length) {
  const GreatCircleSegment flaw(body, state, n, center, flaw_length);
  std::vector<std::size_t> across;
  for (std::size_t k = 0; k < body.spring_count(); ++k)
    if (is_unfailed_shell(body, state, k) && flaw.crossed_by(body, state, k)) across.push_back(k);
  return across;
}

/// The shell springs' midpoints in a grid, for the critical_distance rule, which looks for the
/// springs across a segment at every check: the springs tested are those whose midpoints lie
/// within segment_length + 2 (longest shell spring) of the candidate's, which holds every spring
/// across the segment while the crust stays within segment_length / 2 of the candidate's radius.
class ShellSpringGrid {
 public:
  ShellSpringGrid(const Body& body, const State& state, double segment_length)
      : grid_(grid_over_particles(state, segment_length / 2)) {
    for (std::size_t n = 0; n < body.spring_count(); ++n)
      if (body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::shell)) {
        grid_.insert(spring_midpoint(body, state, n));
        spring_.push_back(n);
        const auto i = static_cast<std::size_t>(body.springs[n][0]);
        const auto j = static_cast<std::size_t>(body.springs[n][1]);
        longest_ = std::max(longest_, (vec3_at(state.position, i) - vec3_at(state.position, j)).norm());
      }
    reach_ = segment_length + 2 * longest_;
  }
  /// The unfailed shell springs across `segment` (centred on the midpoint `mid`), in index order.
  std::vector<std::size_t> across(const Body& body, const State& state, const GreatCircleSegment& segment,
                                  const Vec3& mid) const {
    std::vector<std::size_t> found;
    for (const std::int32_t id : grid_.closer_than(mid, reach_)) {  // ids in increasing order: index order
      const std::size_t k = spring_[static_cast<std::size_t>(id)];
      if (!state.springs.failed[k] && segment.crossed_by(body, state, k)) found.push_back(k);
    }
    return found;
  }
  /// The unfailed shell springs whose midpoints lie closer than `radius` to `mid`, in index order.
  std::vector<std::size_t> within(const State& state, const Vec3& mid, double radius) const {
    std::vector<std::size_t> found;
    for (const std::int32_t id : grid_.closer_than(mid, radius)) {
      const std::size_t k = spring_[static_cast<std::size_t>(id)];
      if (!state.springs.failed[k]) found.push_back(k);
    }
    return found;
  }

 private:
  NeighborGrid grid_;
  std::vector<std::size_t> spring_;  // spring index of each grid id
  double longest_ = 0;
  double reach_ = 0;
};

/// The nonlocal rules' strain at spring n (docs/failure-rule.md, "A strain averaged over a length"):
/// in the tangent plane at n's midpoint (normal: from `center` through it), with e1 along n's axis
/// and e2 = normal x e1, the strain tensor (E11, E12, E22) whose strain along each spring k of
/// `springs`, E11 c^2 + 2 E12 c s + E22 s^2 (c, s: the components of k's unit axis along e1, e2,
/// renormalised in the plane), fits k's strain / f by least squares (sums in the order given).
/// Components dimensionless; nothing when fewer than 6 springs or their directions do not
/// determine the tensor (the normal matrix's determinant below 1e-3 of (trace / 3)^3; 0.87 for the
/// three directions of a triangular lattice).
struct FittedStrain {
  double e11 = 0, e12 = 0, e22 = 0;
  Vec3 e1, e2;  ///< the frame: unit tangent vectors, e1 along n's axis
  /// The largest principal strain, (E11 + E22) / 2 + ((E11 - E22)^2 / 4 + E12^2)^(1/2).
  double largest_principal() const { return 0.5 * (e11 + e22) + principal_radius(); }
  /// The unit tangent direction of the largest principal strain; e1 where the tensor is isotropic.
  /// Of the two forms of the eigenvector the one away from 0 (no transcendental function: the
  /// same bits on every CPU).
  Vec3 principal_direction() const {
    const double half = 0.5 * (e11 - e22), radius = principal_radius();
    if (!(radius > 0)) return e1;
    const Vec3 v = half >= 0 ? ((half + radius) * e1 + e12 * e2) : (e12 * e1 + (radius - half) * e2);
    return v.normalized();
  }

 private:
  double principal_radius() const {
    const double half = 0.5 * (e11 - e22);
    return std::sqrt(half * half + e12 * e12);
  }
};

std::optional<FittedStrain> fitted_strain(const Body& body, const State& state, std::size_t n, const Vec3& center,
                                          const std::vector<std::size_t>& springs) {
  if (springs.size() < 6) return std::nullopt;
  auto ends = [&](std::size_t k) {
    return std::pair{vec3_at(state.position, static_cast<std::size_t>(body.springs[k][0])),
                     vec3_at(state.position, static_cast<std::size_t>(body.springs[k][1]))};
  };
  const auto [a, b] = ends(n);
  const Vec3 normal = (0.5 * (a + b) - center).normalized();
  FittedStrain fit;
  fit.e1 = ((b - a) - (b - a).dot(normal) * normal).normalized();
  fit.e2 = normal.cross(fit.e1);
  double m[3][3] = {}, y[3] = {};
  for (const std::size_t k : springs) {
    const auto [p, q] = ends(k);
    const double c = (q - p).dot(fit.e1), s = (q - p).dot(fit.e2), in_plane = c * c + s * s;
    if (!(in_plane > 0)) continue;
    const double row[3] = {c * c / in_plane, 2 * c * s / in_plane, s * s / in_plane};
    const double strain = spring_strain(body, state, k) / body.failure_strain_factor(k);
    for (int r = 0; r < 3; ++r) {
      y[r] += row[r] * strain;
      for (int col = 0; col < 3; ++col) m[r][col] += row[r] * row[col];
    }
  }
  auto det = [](const double (&x)[3][3]) {
    return x[0][0] * (x[1][1] * x[2][2] - x[1][2] * x[2][1]) - x[0][1] * (x[1][0] * x[2][2] - x[1][2] * x[2][0]) +
           x[0][2] * (x[1][0] * x[2][1] - x[1][1] * x[2][0]);
  };
  const double whole = det(m), scale = (m[0][0] + m[1][1] + m[2][2]) / 3;
  if (!(whole > 1e-3 * scale * scale * scale)) return std::nullopt;
  // Cramer's rule: component c is det(m with column c replaced by the right-hand side) / det(m).
  double component[3];
  for (int c = 0; c < 3; ++c) {
    double replaced[3][3];
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 3; ++col) replaced[r][col] = col == c ? y[r] : m[r][col];
    component[c] = det(replaced) / whole;
  }
  fit.e11 = component[0];
  fit.e12 = component[1];
  fit.e22 = component[2];
  return fit;
}

/// The crack rules' parameters beyond the local rule's: 0 shadow distance for the local rule;
/// flaw_length > 0 only for the griffith rule, segment_length > 0 only for the critical_distance and
/// nonlocal rules; nonlocal_strain only for the nonlocal rules, principal_opening only for
/// nonlocal_principal.
struct CrackGrowth {
  double shadow_distance = 0;
  double flaw_length = 0;
  double growth_strain_factor = 1;
  double segment_length = 0;
  bool nonlocal_strain = false;
  bool principal_opening = false;
};

/// The local rule's check: candidates beyond eps_S by decreasing strain (index on ties); one
/// fails unless a failure of the last relaxation_steps steps (or of this check) lies within
/// exclusion_distance of it (midpoints, current positions). With a shadow distance (> 0, the
/// shadow and griffith rules) a candidate that extends no crack (CrackMap) also waits while any
/// failed shell spring lies within the shadow distance. With a flaw length (the griffith rule) a
/// candidate that extends a crack fails only beyond growth_strain_factor eps_S, and one that starts
/// a crack fails with every spring across its flaw (springs_across_flaw). With a segment length (the
/// critical_distance rule) a candidate that starts or extends a crack fails, with every unfailed
/// shell spring across the segment centred on it, only if their mean of strain / f reaches eps_S;
/// with nonlocal_strain (the nonlocal rule) only if the fitted_strain over the unfailed shell
/// springs within half a segment and outside the crack neighbourhood, along the candidate's axis,
/// reaches eps_S (the segment's mean where the fit is not determined); with principal_opening
/// (nonlocal_principal) its largest principal strain must, and the segment lies across that
/// principal direction instead of across the candidate's axis, which also judges its role.
std::size_t fail_local(const LocalFailureRule& rule, const CrackGrowth& growth, const FailureThreshold& threshold,
                       const Body& body, State& state, std::vector<FailureEvent>& log) {
  // A spring of strength factor f fails beyond f eps_S; candidates go by strain / f, the most
  // over-strained first (for f = 1, as for every spring of a uniform crust, exactly by strain).
  struct Candidate {
    double overstrain;  ///< strain / f
    std::size_t n;
    double strain;
  };
  std::vector<Candidate> candidates;
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (!is_unfailed_shell(body, state, n)) continue;
    const double strain = spring_strain(body, state, n);
    const double f = body.failure_strain_factor(n);
    if (strain > threshold.failure_strain * f) candidates.push_back({strain / f, n, strain});
  }
  if (candidates.empty()) return 0;
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.overstrain > b.overstrain || (a.overstrain == b.overstrain && a.n < b.n);
  });
  // Midpoints of the failures still relaxing (the log is in step order: scan from its end).
  std::vector<Vec3> relaxing;
  for (auto e = log.rbegin(); e != log.rend() && e->step > state.step - rule.relaxation_steps; ++e)
    relaxing.push_back(spring_midpoint(body, state, static_cast<std::size_t>(e->spring)));
  std::optional<CrackMap> cracks;
  if (growth.shadow_distance > 0)
    cracks.emplace(body, state, growth.shadow_distance, rule.exclusion_distance,
                   growth.flaw_length > 0 ? std::max(growth.shadow_distance, rule.exclusion_distance)
                                          : growth.shadow_distance);
  std::optional<Vec3> center;  // the flaws' great circles are about the body's centre of mass
  std::optional<ShellSpringGrid> shell_grid;  // the segment rules', made at their first segment
  const double r2 = rule.exclusion_distance * rule.exclusion_distance;
  const double growth_strain = growth.growth_strain_factor * threshold.failure_strain;
  std::size_t failed = 0;
  auto fail = [&](std::size_t n, double strain) {
    log.push_back(fail_spring(body, state, n, strain, threshold.failed_stiffness_factor));
    relaxing.push_back(spring_midpoint(body, state, n));
    if (cracks) cracks->add(body, state, n);
    ++failed;
  };
  for (const auto& [overstrain, n, strain] : candidates) {
    if (state.springs.failed[n]) continue;  // across an earlier flaw of this check
    const Vec3 mid = spring_midpoint(body, state, n);
    const bool excluded =
        std::any_of(relaxing.begin(), relaxing.end(), [&](const Vec3& p) { return (p - mid).squaredNorm() < r2; });
    if (excluded) continue;
    // The nonlocal rules' strain tensor over half a segment around the candidate, without the crack
    // neighbourhood.
    auto fit_around = [&]() {
      if (!center) center = body_center_of_mass(body, state);
      if (!shell_grid) shell_grid.emplace(body, state, growth.segment_length);
      std::vector<std::size_t> fitted;
      for (const std::size_t k : shell_grid->within(state, mid, growth.segment_length / 2))
        if (!cracks || !cracks->in_neighbourhood(spring_midpoint(body, state, k))) fitted.push_back(k);
      return fitted_strain(body, state, n, *center, fitted);
    };
    std::optional<Vec3> axis;  // the nonlocal rules': the direction the candidate's segment opens across
    std::optional<FittedStrain> fit;
    if (growth.nonlocal_strain) {
      axis = (vec3_at(state.position, static_cast<std::size_t>(body.springs[n][1])) -
              vec3_at(state.position, static_cast<std::size_t>(body.springs[n][0])))
                 .normalized();
      if (growth.principal_opening) {
        // Beyond the crack neighbourhood the role does not depend on the axis: a shadowed
        // candidate needs no fit.
        if (cracks && !cracks->in_neighbourhood(mid) && cracks->role(mid, &*axis) == CrackRole::shadowed) continue;
        fit = fit_around();
        if (fit) axis = fit->principal_direction();
      }
    }
    Vec3 crack_point = Vec3::Zero();
    const CrackRole role = cracks ? cracks->role(mid, axis ? &*axis : nullptr, &crack_point) : CrackRole::starts;
    if (role == CrackRole::shadowed) continue;
    if (growth.flaw_length > 0 && role == CrackRole::extends && !(strain > growth_strain * body.failure_strain_factor(n)))
      continue;
    if (growth.segment_length > 0) {
      if (!center) center = body_center_of_mass(body, state);
      if (!shell_grid) shell_grid.emplace(body, state, growth.segment_length);
      GreatCircleSegment segment = growth.principal_opening
                                       ? GreatCircleSegment(*center, mid, *axis, growth.segment_length)
                                       : GreatCircleSegment(body, state, n, *center, growth.segment_length);
      // The nonlocal rule's crack advances by the half segment ahead of its tip, away from the
      // crack: the half behind would run beside the crack, a lattice row off it where the tip
      // steps sideways, and draw a parallel crack of L at every such step.
      if (growth.nonlocal_strain && role == CrackRole::extends) segment.ahead_of(crack_point);
      std::optional<double> nonlocal;
      if (growth.nonlocal_strain && !growth.principal_opening) fit = fit_around();
      if (fit) nonlocal = growth.principal_opening ? fit->largest_principal() : fit->e11;
      if (nonlocal && !(*nonlocal >= threshold.failure_strain)) continue;  // before the segment is looked for
      const std::vector<std::size_t> across = shell_grid->across(body, state, segment, mid);
      if (!nonlocal) {
        double sum = 0;  // in index order: the same bits for any thread count
        for (const std::size_t k : across) sum += spring_strain(body, state, k) / body.failure_strain_factor(k);
        if (!(sum >= threshold.failure_strain * static_cast<double>(across.size()))) continue;
      }
      fail(n, strain);  // the log names the candidate first, then the segment's other springs in index order
      for (const std::size_t k : across)
        if (k != n) fail(k, spring_strain(body, state, k));
      continue;
    }
    if (growth.flaw_length > 0 && role == CrackRole::starts) {
      if (!center) center = body_center_of_mass(body, state);
      const std::vector<std::size_t> flaw = springs_across_flaw(body, state, n, *center, growth.flaw_length);
      fail(n, strain);  // the log names the spring that opened the flaw first, then the rest in index order
      for (const std::size_t k : flaw)
        if (k != n) fail(k, spring_strain(body, state, k));
      continue;
    }
    fail(n, strain);
  }
  return failed;
}

}  // namespace

double crack_neighbourhood_radius(const Config& config, double L_S) {
  return config.encounter.exclusion_distance.value_or(config.encounter.exclusion_radius * L_S);
}

FailureRule make_failure_rule(const Config& config, std::optional<double> relaxation_crossings, const Body& body,
                              const State& state, double dt) {
  switch (config.encounter.failure_rule) {
    case FailureRuleKind::paper:
      break;
    case FailureRuleKind::local:
    case FailureRuleKind::shadow:
    case FailureRuleKind::griffith:
    case FailureRuleKind::critical_distance:
    case FailureRuleKind::nonlocal:
    case FailureRuleKind::nonlocal_principal: {
      // A body without a crust has nothing to fail: the (default) local rule needs no shell there.
      if (body.count_species(Species::shell) == 0) break;
      const DerivedQuantities q = derive_quantities(body, state, config.interior.radius);
      if (!(q.L_S > 0) || !(q.V_SP > 0))
        throw InputError(fmt::format("encounter.failure_rule = \"{}\" needs a shell (no shell springs in this body)",
                                     choice_name(config.encounter.failure_rule)));
      // The critical_distance and nonlocal rules' cracks grow by half a segment at a time: the crust
      // relaxes over that length, so the crack tip runs at V_SP / relaxation_crossings at every resolution.
      const bool by_segments = config.encounter.failure_rule == FailureRuleKind::critical_distance ||
                               config.encounter.failure_rule == FailureRuleKind::nonlocal ||
                               config.encounter.failure_rule == FailureRuleKind::nonlocal_principal;
      const double crossing_time = (by_segments ? config.encounter.flaw_length / 2 : q.L_S) / q.V_SP;
      LocalFailureRule rule;
      rule.relaxation_steps = std::max<std::int64_t>(
          1, std::llround(relaxation_crossings.value_or(config.encounter.relaxation_crossings) * crossing_time / dt));
      rule.exclusion_distance = crack_neighbourhood_radius(config, q.L_S);
      rule.configured_fail_interval = config.encounter.fail_interval;
      if (config.encounter.failure_rule == FailureRuleKind::shadow)
        return ShadowFailureRule{rule, config.encounter.shadow_distance};
      if (config.encounter.failure_rule == FailureRuleKind::griffith)
        // The tip strain of a crack of length a_0 under the far-field strain eps_S: LEFM's
        // sigma_yy = K / sqrt(2 pi r), K = sigma sqrt(pi a_0 / 2), at the first spring ahead of the
        // tip (r ~ L_S / 2) gives sqrt(a_0 / (2 L_S)) (docs/failure-rule.md).
        return GriffithFailureRule{{rule, config.encounter.shadow_distance},
                                   config.encounter.flaw_length,
                                   std::max(1.0, std::sqrt(config.encounter.flaw_length / (2 * q.L_S)))};
      const NonlocalFailureRule nonlocal{{rule, config.encounter.shadow_distance}, config.encounter.flaw_length};
      if (config.encounter.failure_rule == FailureRuleKind::nonlocal) return nonlocal;
      if (config.encounter.failure_rule == FailureRuleKind::nonlocal_principal) return PrincipalNonlocalFailureRule{nonlocal};
      if (by_segments) return CriticalDistanceFailureRule{{rule, config.encounter.shadow_distance}, config.encounter.flaw_length};
      return rule;
    }
  }
  return PaperFailureRule{config.encounter.fail_interval};
}

std::string unresolved_rule_lengths(const Config& config, const Body& body, const State& state) {
  const FailureRuleKind kind = config.encounter.failure_rule;
  const bool nonlocal = kind == FailureRuleKind::nonlocal || kind == FailureRuleKind::nonlocal_principal;
  if (kind != FailureRuleKind::shadow && kind != FailureRuleKind::griffith && kind != FailureRuleKind::critical_distance &&
      !nonlocal)
    return "";
  if (body.count_species(Species::shell) == 0) return "";
  const double L_S = derive_quantities(body, state, config.interior.radius).L_S;
  std::vector<std::string> short_ones;
  auto check = [&](const char* name, double length) {
    if (length < 3 * L_S) short_ones.push_back(fmt::format("encounter.{} = {:g} R is {:.1f} L_S", name, length, length / L_S));
  };
  check("shadow_distance", config.encounter.shadow_distance);
  if (kind != FailureRuleKind::shadow) check("flaw_length", config.encounter.flaw_length);
  std::vector<std::string> parts;
  if (!short_ones.empty())
    parts.push_back(fmt::format("{} (L_S = {:.3g} R): the {} rule's lengths are drawn by the lattice from 3 L_S on",
                                fmt::join(short_ones, ", "), L_S, choice_name(kind)));
  // The nonlocal rule at a crack's tip fits the springs within L = flaw_length / 2 and beyond the
  // crack neighbourhood r_ex: where L reaches less than L_S beyond r_ex, few springs or none.
  const double reach = crack_neighbourhood_radius(config, L_S) + L_S;
  if (nonlocal && config.encounter.flaw_length / 2 < reach)
    parts.push_back(fmt::format("encounter.flaw_length / 2 = {:g} R is less than the crack neighbourhood plus one "
                                "spacing, r_ex + L_S = {:.3g} R (r_ex: {}): at a crack's tip the "
                                "nonlocal rule's fit holds few springs, and where it is not determined the rule takes "
                                "the segment's mean",
                                config.encounter.flaw_length / 2, reach,
                                config.encounter.exclusion_distance ? "encounter.exclusion_distance"
                                                                    : "encounter.exclusion_radius L_S"));
  if (parts.empty()) return "";
  return fmt::format("warning: {} (docs/failure-rule.md)", fmt::join(parts, "; "));
}

std::size_t apply_failure_rule(const FailureRule& rule, const FailureThreshold& threshold, const Body& body,
                               State& state, std::int64_t start_step, std::vector<FailureEvent>& log) {
  if (const auto* local = std::get_if<LocalFailureRule>(&rule)) return fail_local(*local, {}, threshold, body, state, log);
  if (const auto* shadow = std::get_if<ShadowFailureRule>(&rule))
    return fail_local(shadow->local, {shadow->shadow_distance}, threshold, body, state, log);
  if (const auto* griffith = std::get_if<GriffithFailureRule>(&rule))
    return fail_local(griffith->shadow.local,
                      {griffith->shadow.shadow_distance, griffith->flaw_length, griffith->growth_strain_factor},
                      threshold, body, state, log);
  if (const auto* critical = std::get_if<CriticalDistanceFailureRule>(&rule))
    return fail_local(critical->shadow.local, {critical->shadow.shadow_distance, 0.0, 1.0, critical->segment_length},
                      threshold, body, state, log);
  if (const auto* nonlocal = std::get_if<NonlocalFailureRule>(&rule))
    return fail_local(nonlocal->shadow.local, {nonlocal->shadow.shadow_distance, 0.0, 1.0, nonlocal->segment_length, true},
                      threshold, body, state, log);
  if (const auto* principal = std::get_if<PrincipalNonlocalFailureRule>(&rule)) {
    const NonlocalFailureRule& nonlocal = principal->nonlocal;
    return fail_local(nonlocal.shadow.local,
                      {nonlocal.shadow.shadow_distance, 0.0, 1.0, nonlocal.segment_length, true, true}, threshold, body,
                      state, log);
  }
  if ((state.step - start_step) % std::get<PaperFailureRule>(rule).fail_interval != 0) return 0;
  auto event = fail_most_strained_shell_spring(body, state, threshold.failure_strain, threshold.failed_stiffness_factor);
  if (!event) return 0;
  log.push_back(*event);
  return 1;
}

std::optional<FailureEvent> fail_most_strained_shell_spring(const Body& body, State& state, double failure_strain,
                                                            double failed_stiffness_factor) {
  // The most over-strained beyond its own f eps_S (strain / f; exactly the strain where f = 1).
  std::optional<std::size_t> worst;
  double worst_overstrain = 0, worst_strain = 0;
  for (std::size_t n = 0; n < body.spring_count(); ++n) {
    if (!is_unfailed_shell(body, state, n)) continue;
    const double strain = spring_strain(body, state, n);
    const double f = body.failure_strain_factor(n);
    if (!(strain > failure_strain * f)) continue;
    if (!worst || strain / f > worst_overstrain) {  // strict: ties keep the lowest index
      worst_overstrain = strain / f;
      worst_strain = strain;
      worst = n;
    }
  }
  if (!worst) return std::nullopt;
  return fail_spring(body, state, *worst, worst_strain, failed_stiffness_factor);
}

}  // namespace tidalcrust
