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

/// The rule; its alternatives in FailureRuleKind order (a new kind: its struct here, its row in
/// the choice table, and its code in physics/shell_failure.cpp).
using FailureRule = std::variant<PaperFailureRule, LocalFailureRule, ShadowFailureRule>;
static_assert(std::variant_size_v<FailureRule> == ChoiceTable<FailureRuleKind>::rows.size());
static_assert(std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(FailureRuleKind::local), FailureRule>,
                             LocalFailureRule>);
static_assert(std::is_same_v<std::variant_alternative_t<static_cast<std::size_t>(FailureRuleKind::shadow), FailureRule>,
                             ShadowFailureRule>);

/// Which kind `rule` is.
inline FailureRuleKind kind_of(const FailureRule& rule) { return static_cast<FailureRuleKind>(rule.index()); }

/// The rule as the encounter record stores it (/checkpoint/record: fail_interval, failure_rule,
/// relaxation_steps, exclusion_distance, shadow_distance; docs/checkpoint-layout.md): the
/// parameters of every kind, 0 for those of another kind (fail_interval: the configured one).
struct StoredFailureRule {
  std::int64_t fail_interval = 1;
  FailureRuleKind kind = FailureRuleKind::paper;
  std::int64_t relaxation_steps = 0;
  double exclusion_distance = 0;
  double shadow_distance = 0;
};

inline StoredFailureRule stored_failure_rule(const FailureRule& rule) {
  if (const auto* local = std::get_if<LocalFailureRule>(&rule))
    return {local->configured_fail_interval, FailureRuleKind::local, local->relaxation_steps,
            local->exclusion_distance, 0.0};
  if (const auto* shadow = std::get_if<ShadowFailureRule>(&rule))
    return {shadow->local.configured_fail_interval, FailureRuleKind::shadow, shadow->local.relaxation_steps,
            shadow->local.exclusion_distance, shadow->shadow_distance};
  return {std::get<PaperFailureRule>(rule).fail_interval, FailureRuleKind::paper, 0, 0.0, 0.0};
}

inline FailureRule failure_rule_of(const StoredFailureRule& stored) {
  const LocalFailureRule local{stored.relaxation_steps, stored.exclusion_distance, stored.fail_interval};
  switch (stored.kind) {
    case FailureRuleKind::local:
      return local;
    case FailureRuleKind::shadow:
      return ShadowFailureRule{local, stored.shadow_distance};
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
  if constexpr (!std::is_const_v<Rule>) rule = failure_rule_of(stored);
}

}  // namespace tidalcrust
