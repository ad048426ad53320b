#pragma once
// The crust failure rule of a stage, with its schedule in steps: one alternative per
// FailureRuleKind (model/choices.hpp), each with its own parameters. physics/shell_failure.hpp
// makes it from the configuration (where physical intervals become steps, once) and applies it;
// the encounter record stores it (model/stage_records.hpp). docs/failure-rule.md.
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <variant>

#include "model/choices.hpp"

namespace tidalcrust {

/// "paper" (section 2.6): one check every fail_interval steps; each check fails the single most
/// strained shell spring beyond eps_S.
struct PaperFailureRule {
  std::int64_t fail_interval = 1;  ///< t_fail, steps between checks (>= 1)
  bool operator==(const PaperFailureRule&) const = default;
};

/// "local" (docs/failure-rule.md): a check every step; every shell spring beyond eps_S may fail,
/// most strained first, but not within exclusion_distance of a failure of the last
/// relaxation_steps steps.
struct LocalFailureRule {
  std::int64_t relaxation_steps = 1;  ///< relaxation interval of a crack neighbourhood, steps (>= 1)
  double exclusion_distance = 0;      ///< crack neighbourhood radius r_ex L_S between spring midpoints, R
  /// The workflow's [encounter] fail_interval, which this rule does not read: the record stores
  /// it in /checkpoint/record@fail_interval for every rule, as it did before the rule had kinds.
  std::int64_t configured_fail_interval = 1;
  bool operator==(const LocalFailureRule&) const = default;
};

/// "shadow" (docs/failure-rule.md, "A physical crack spacing"): the local rule, and a spring with
/// no failed shell spring within the local rule's exclusion_distance (it would start a new crack)
/// fails only if no failed shell spring lies within shadow_distance of it (midpoints, current
/// positions): a crack unloads the crust beside it, so cracks start at least that far apart at
/// every resolution, and grow from their tips.
struct ShadowFailureRule {
  LocalFailureRule local;       ///< relaxation interval and neighbourhood, as the local rule
  double shadow_distance = 0;   ///< stress-shadow radius, R (a physical length, not in L_S)
  bool operator==(const ShadowFailureRule&) const = default;
};

/// "griffith" (docs/failure-rule.md, "A fixed fracture toughness"): the shadow rule, where a new
/// crack opens as a flaw: every unfailed shell spring crossing the great-circle segment of length
/// flaw_length centred on the candidate's midpoint, perpendicular to its axis, fails at once; and a
/// spring that extends a crack fails only beyond growth_strain_factor * eps_S, the tip strain at
/// which a crack of flaw_length under the far-field strain eps_S is critical (a toughness
/// K_c = E eps_S sqrt(pi flaw_length / 2) at every resolution).
struct GriffithFailureRule {
  ShadowFailureRule shadow;           ///< relaxation interval, neighbourhood and stress shadow
  double flaw_length = 0;             ///< a_0, length of a new crack's flaw, R
  double growth_strain_factor = 1;    ///< eps_tip / eps_S = max(1, sqrt(a_0 / (2 L_S))) (dimensionless)
  bool operator==(const GriffithFailureRule&) const = default;
};

/// "critical_distance" (docs/failure-rule.md, "A strength over a length: the critical-distance
/// rule"): the shadow rule, where a candidate that starts or extends a crack fails together with
/// every unfailed shell spring across the great-circle segment of length segment_length centred on
/// its midpoint, perpendicular to its axis, and only if their mean strain (each over its own
/// strength factor) reaches eps_S: the line method of the theory of critical distances (Taylor
/// 2007), strength and length both physical, so no decision reads a single spring's lattice-scale
/// strain. Its relaxation interval is set by the segment, not by L_S.
struct CriticalDistanceFailureRule {
  ShadowFailureRule shadow;     ///< relaxation interval (of a segment), neighbourhood and stress shadow
  double segment_length = 0;    ///< 2 L, the averaging segment a crack opens or grows by, R
  bool operator==(const CriticalDistanceFailureRule&) const = default;
};

/// "nonlocal" (docs/failure-rule.md, "A strain averaged over a length: the nonlocal rule"): the
/// critical_distance rule (same segments, shadow and relaxation interval), where a candidate is
/// judged by its nonlocal strain: the strain along its axis of the tangent-plane strain tensor
/// fitted by least squares to the unfailed shell springs whose midpoints lie within half a segment
/// of its own and outside the crack neighbourhood (no failed shell spring's midpoint within
/// shadow.local.exclusion_distance), as nonlocal damage models average strain over a material
/// length (Pijaudier-Cabot & Bazant 1987). Where that fit is not determined it is judged as by
/// critical_distance.
struct NonlocalFailureRule {
  ShadowFailureRule shadow;     ///< relaxation interval (of a segment), neighbourhood (left out of the fit), shadow
  double segment_length = 0;    ///< 2 L: the segment a crack opens or grows by; the fit's radius is L, R
  bool operator==(const NonlocalFailureRule&) const = default;
};

/// "nonlocal_principal" (docs/failure-rule.md, "Opening across the principal strain"): the nonlocal
/// rule (same fit, neighbourhood, shadow, segments and relaxation interval), where the fitted
/// tensor's largest principal strain, not its component along the candidate's axis, must reach
/// eps_S, and the segment opens across that principal direction instead of across the candidate's
/// axis: a tension crack runs perpendicular to the largest principal stress (Erdogan & Sih 1963),
/// so its path follows the crust's stress trajectories, not the lattice's three directions. Where
/// the fit is not determined, or is isotropic, the candidate's axis stands in.
struct PrincipalNonlocalFailureRule {
  NonlocalFailureRule nonlocal;  ///< fit, neighbourhood, shadow, segment and relaxation interval
  bool operator==(const PrincipalNonlocalFailureRule&) const = default;
};

/// The rule; its alternatives in FailureRuleKind order (a new kind: its struct here, its row in
/// the choice table, and its code in physics/shell_failure.cpp).
using FailureRule =
    std::variant<PaperFailureRule, LocalFailureRule, ShadowFailureRule, GriffithFailureRule, CriticalDistanceFailureRule,
                 NonlocalFailureRule, PrincipalNonlocalFailureRule>;
static_assert(std::variant_size_v<FailureRule> == ChoiceTable<FailureRuleKind>::rows.size());
static_assert(std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(FailureRuleKind::local), FailureRule>,
                             LocalFailureRule>);
static_assert(std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(FailureRuleKind::shadow), FailureRule>,
                             ShadowFailureRule>);
static_assert(std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(FailureRuleKind::griffith), FailureRule>,
                             GriffithFailureRule>);
static_assert(
    std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(FailureRuleKind::critical_distance), FailureRule>,
                   CriticalDistanceFailureRule>);
static_assert(std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(FailureRuleKind::nonlocal), FailureRule>,
                             NonlocalFailureRule>);
static_assert(
    std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(FailureRuleKind::nonlocal_principal), FailureRule>,
                   PrincipalNonlocalFailureRule>);

/// Which kind `rule` is.
inline FailureRuleKind kind_of(const FailureRule& rule) { return static_cast<FailureRuleKind>(rule.index()); }

/// The rule as the encounter record stores it (/checkpoint/record: fail_interval, failure_rule,
/// relaxation_steps, exclusion_distance, shadow_distance, flaw_length, growth_strain_factor;
/// docs/checkpoint-layout.md): the
/// parameters of every kind, 0 for those of another kind (fail_interval: the configured one).
struct StoredFailureRule {
  std::int64_t fail_interval = 1;
  FailureRuleKind kind = FailureRuleKind::paper;
  std::int64_t relaxation_steps = 0;
  double exclusion_distance = 0;
  double shadow_distance = 0;
  double flaw_length = 0;
  double growth_strain_factor = 0;
};

inline StoredFailureRule stored_failure_rule(const FailureRule& rule) {
  if (const auto* local = std::get_if<LocalFailureRule>(&rule))
    return {local->configured_fail_interval, FailureRuleKind::local, local->relaxation_steps,
            local->exclusion_distance, 0.0, 0.0, 0.0};
  auto shadow_fields = [](const ShadowFailureRule& shadow, FailureRuleKind kind) {
    return StoredFailureRule{shadow.local.configured_fail_interval, kind, shadow.local.relaxation_steps,
                             shadow.local.exclusion_distance, shadow.shadow_distance, 0.0, 0.0};
  };
  if (const auto* shadow = std::get_if<ShadowFailureRule>(&rule)) return shadow_fields(*shadow, FailureRuleKind::shadow);
  if (const auto* griffith = std::get_if<GriffithFailureRule>(&rule)) {
    StoredFailureRule stored = shadow_fields(griffith->shadow, FailureRuleKind::griffith);
    stored.flaw_length = griffith->flaw_length;
    stored.growth_strain_factor = griffith->growth_strain_factor;
    return stored;
  }
  auto segment_fields = [&](const auto& segments) {  // the critical_distance and both nonlocal rules
    StoredFailureRule stored = shadow_fields(segments.shadow, kind_of(rule));
    stored.flaw_length = segments.segment_length;
    return stored;
  };
  if (const auto* critical = std::get_if<CriticalDistanceFailureRule>(&rule)) return segment_fields(*critical);
  if (const auto* nonlocal = std::get_if<NonlocalFailureRule>(&rule)) return segment_fields(*nonlocal);
  if (const auto* principal = std::get_if<PrincipalNonlocalFailureRule>(&rule)) return segment_fields(principal->nonlocal);
  return {std::get<PaperFailureRule>(rule).fail_interval, FailureRuleKind::paper, 0, 0.0, 0.0, 0.0, 0.0};
}

inline FailureRule failure_rule_of(const StoredFailureRule& stored) {
  const LocalFailureRule local{stored.relaxation_steps, stored.exclusion_distance, stored.fail_interval};
  switch (stored.kind) {
    case FailureRuleKind::local:
      return local;
    case FailureRuleKind::shadow:
      return ShadowFailureRule{local, stored.shadow_distance};
    case FailureRuleKind::griffith:
      return GriffithFailureRule{{local, stored.shadow_distance}, stored.flaw_length, stored.growth_strain_factor};
    case FailureRuleKind::critical_distance:
      return CriticalDistanceFailureRule{{local, stored.shadow_distance}, stored.flaw_length};
    case FailureRuleKind::nonlocal:
      return NonlocalFailureRule{{local, stored.shadow_distance}, stored.flaw_length};
    case FailureRuleKind::nonlocal_principal:
      return PrincipalNonlocalFailureRule{{{local, stored.shadow_distance}, stored.flaw_length}};
    case FailureRuleKind::paper:
      break;
  }
  return PaperFailureRule{stored.fail_interval};
}

/// Lists the stored fields of a rule as visit(name, value, unit, meaning), in stored order; for a
/// non-const rule the visited values are then read back into it (the checkpoint reader).
template <typename Rule, typename Visit>
  requires std::same_as<std::remove_const_t<Rule>, FailureRule>
void visit_failure_rule(Rule& rule, Visit&& visit) {
  StoredFailureRule stored = stored_failure_rule(rule);
  visit("fail_interval", stored.fail_interval, "steps", "t_fail (paper rule)");
  visit("failure_rule", stored.kind, "", "failure rule (model/choices.hpp)");
  visit("relaxation_steps", stored.relaxation_steps, "steps", "local rule: relaxation interval of a crack neighbourhood");
  visit("exclusion_distance", stored.exclusion_distance, "R", "local rule: crack neighbourhood radius");
  visit("shadow_distance", stored.shadow_distance, "R", "shadow rule: no new crack this close to a crack");
  visit("flaw_length", stored.flaw_length, "R",
        "griffith rule: length of a new crack's flaw; critical_distance and nonlocal rules: the averaging segment");
  visit("growth_strain_factor", stored.growth_strain_factor, "1", "griffith rule: crack-tip failure strain / eps_S");
  if constexpr (!std::is_const_v<Rule>) rule = failure_rule_of(stored);
}

}  // namespace tidalcrust
