#pragma once
// The closed choices of the configuration, each an enum class with ONE name table: its values'
// TOML spellings and a one-line meaning each. Parsing (parse_choice), the "is not one of: ..."
// error, printing (choice_name: to_toml, inspect, messages, the checkpoint record, fingerprints)
// and the key's comment in the resolved configuration (choice_doc) all read the table.
// A new value is a new enumerator and its row in the table (rows in enumerator order; checked at
// compile time), plus the code that acts on it.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

#include "base/errors.hpp"

namespace tidalcrust {

/// One value of a closed choice: the enumerator, its spelling and what it means (one line).
template <class E>
struct ChoiceRow {
  E value;
  std::string_view name;
  std::string_view meaning;
};

/// The name table of a choice E: `static constexpr std::array rows` of ChoiceRow<E>, one per
/// enumerator, in enumerator order. Specialised below for each choice.
template <class E>
struct ChoiceTable;

template <class E>
concept Choice = std::is_enum_v<E> && requires { ChoiceTable<E>::rows; };

// ---- the choices ------------------------------------------------------------------------------

/// [relax] crust_support: how the relaxed crust is supported (docs/crust-support.md).
enum class CrustSupport {
  paper,     ///< section 2.8: the crust carries the cross springs' tangential push
  balanced,  ///< cross-spring rest lengths chosen so that they alone carry each shell node's weight
  lithostatic,  ///< balanced, but the crust keeps the compression its weight gives on a welded interior
  floating,  ///< the crust floats on an ocean ([ocean]): its rest lengths creep to the current lengths, no cross springs
};
template <>
struct ChoiceTable<CrustSupport> {
  static constexpr std::array rows{
      ChoiceRow<CrustSupport>{CrustSupport::paper, "paper", "crust carries the cross springs' sideways push"},
      ChoiceRow<CrustSupport>{CrustSupport::balanced, "balanced", "no crust pre-stress"},
      ChoiceRow<CrustSupport>{CrustSupport::lithostatic, "lithostatic",
                              "crust compressed by its own weight; welded crust only"},
      ChoiceRow<CrustSupport>{CrustSupport::floating, "floating", "crust floats on an ocean; [ocean] only"},
  };
};

/// [cross] coupling: how the shell is tied to the interior (docs/crust-support.md, "The welded
/// coupling"; bodies/welded_coupling.hpp).
enum class CrossCoupling {
  paper,   ///< section 2.7: every shell-interior pair closer than d_C, stiffness k_C (eq. 25)
  welded,  ///< the shell joined into the interior network: the layer under the crust has the interior's moduli
};
template <>
struct ChoiceTable<CrossCoupling> {
  static constexpr std::array rows{
      ChoiceRow<CrossCoupling>{CrossCoupling::paper, "paper", "d_C rule and k_C"},
      ChoiceRow<CrossCoupling>{CrossCoupling::welded, "welded", "shell joined into the interior network"},
  };
};

/// [stretch] hydrostatic_support: how the interior carries its hydrostatic pressure
/// (docs/material.md).
enum class HydrostaticSupport {
  strengthen,  ///< section 2.3: one common compression, springs stiffened inside by P(r)/P_uniform
  compress,    ///< each interior spring compressed by P(r)/(2E) at its built stiffness
};
template <>
struct ChoiceTable<HydrostaticSupport> {
  static constexpr std::array rows{
      ChoiceRow<HydrostaticSupport>{HydrostaticSupport::strengthen, "strengthen", "paper: stiffer core springs"},
      ChoiceRow<HydrostaticSupport>{HydrostaticSupport::compress, "compress",
                                    "pre-strain at the material's stiffness; default for [material]"},
  };
};

/// [encounter] failure_rule: which over-strained shell springs fail when (docs/failure-rule.md;
/// the rule with its parameters in steps: FailureRule, model/failure_rule.hpp).
enum class FailureRuleKind {
  paper,  ///< section 2.6: the single most strained spring fails, one check every t_fail steps
  local,  ///< every over-strained spring may fail, at most one per crack neighbourhood per relaxation interval
  shadow, ///< local, and a new crack does not start within shadow_distance of an existing one
  griffith, ///< shadow, a new crack opens as a flaw of flaw_length and grows at the Griffith tip strain
  critical_distance, ///< shadow, a crack opens or grows by a segment of flaw_length whose mean strain reaches eps_S
  nonlocal, ///< critical_distance, judged by the strain tensor fitted to the springs within half a segment
  nonlocal_principal, ///< nonlocal, judged by that tensor's largest principal strain and opening across its direction
};
template <>
struct ChoiceTable<FailureRuleKind> {
  static constexpr std::array rows{
      ChoiceRow<FailureRuleKind>{FailureRuleKind::paper, "paper", "one spring per fail_interval"},
      ChoiceRow<FailureRuleKind>{FailureRuleKind::local, "local", "one per neighbourhood per relaxation interval"},
      ChoiceRow<FailureRuleKind>{FailureRuleKind::shadow, "shadow", "local, no new crack in a crack's stress shadow"},
      ChoiceRow<FailureRuleKind>{FailureRuleKind::griffith, "griffith",
                                 "shadow, cracks open as flaws of flaw_length and grow at a fixed toughness"},
      ChoiceRow<FailureRuleKind>{FailureRuleKind::critical_distance, "critical_distance",
                                 "shadow, cracks open and grow by segments of flaw_length whose mean strain is eps_S"},
      ChoiceRow<FailureRuleKind>{FailureRuleKind::nonlocal, "nonlocal",
                                 "critical_distance, judged by the crust's strain averaged over half a segment around it"},
      ChoiceRow<FailureRuleKind>{FailureRuleKind::nonlocal_principal, "nonlocal_principal",
                                 "nonlocal, opening across the averaged strain's largest principal direction"},
  };
};

/// [gravity] method: how ForceField computes self-gravity (docs/architecture.md, "Self-gravity
/// methods").
enum class GravityMethod {
  direct,  ///< every pair once, O(N^2) (forces/gravity.hpp): the reference
  tree,    ///< octree with softened multipoles, O(N log N) (forces/tree_gravity.hpp): for large N
};
template <>
struct ChoiceTable<GravityMethod> {
  static constexpr std::array rows{
      ChoiceRow<GravityMethod>{GravityMethod::direct, "direct", "every pair, the reference"},
      ChoiceRow<GravityMethod>{GravityMethod::tree, "tree", "octree, quadrupoles"},
  };
};

/// [gravity] kernel: which code DirectGravity evaluates the pairs with (docs/determinism.md).
/// Both sum the same pairs in the same blocks, lanes and order; they differ in how one pair's
/// inverse cube and the partial sums are rounded.
enum class GravityKernel {
  /// With AVX-512: vrsqrt14pd and two Newton steps, explicit fused multiply-adds (fastest);
  /// its bits differ from a build without AVX-512. Without AVX-512: the portable code.
  fast,
  /// Integer and IEEE +, -, * only (the inverse square root from an integer guess and Newton
  /// steps, portable_math::inverse_sqrt), no fused multiply-adds: the same bits in every x86-64
  /// build, with or without AVX-512 (tests/forces/test_gravity_kernels.cpp).
  portable,
};
template <>
struct ChoiceTable<GravityKernel> {
  static constexpr std::array rows{
      ChoiceRow<GravityKernel>{GravityKernel::fast, "fast", "AVX-512 estimates where available"},
      ChoiceRow<GravityKernel>{GravityKernel::portable, "portable", "the same bits on every x86-64 CPU"},
  };
};

/// Whether `kernel` takes its transcendental functions (and the state's path takes its own) from
/// base/portable_math.hpp: portable does, and so does fast in a build without AVX-512, where fast
/// is the portable code (gravity_kernel_label "fast/generic": the same bits as portable).
inline bool uses_portable_math(GravityKernel kernel) {
#if defined(__AVX512F__)
  return kernel == GravityKernel::portable;
#else
  (void)kernel;
  return true;
#endif
}

/// [ensemble] vary: what differs between the members of an ensemble (docs/ensembles.md).
enum class EnsembleVariation {
  pericenter,  ///< the trajectory: q (1 + delta u_k), one relaxed body
  body_seed,   ///< the body: member k on the body of seed workflow.seed + k, each its own body chain
  both,        ///< member k on the body of seed workflow.seed + k at q (1 + delta u_k)
};
template <>
struct ChoiceTable<EnsembleVariation> {
  static constexpr std::array rows{
      ChoiceRow<EnsembleVariation>{EnsembleVariation::pericenter, "pericenter", "pericenters spread by delta, one body"},
      ChoiceRow<EnsembleVariation>{EnsembleVariation::body_seed, "body_seed", "a body of its own seed per member"},
      ChoiceRow<EnsembleVariation>{EnsembleVariation::both, "both", "its own body and its own pericenter"},
  };
};

// ---- reading the tables -----------------------------------------------------------------------

/// True when row i of E's table holds enumerator i (so that a value indexes its row).
template <Choice E>
consteval bool rows_in_enumerator_order() {
  const auto& rows = ChoiceTable<E>::rows;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (static_cast<std::size_t>(rows[i].value) != i) return false;
  return true;
}

/// The spelling of `value` ("paper", "tree", ...).
template <Choice E>
constexpr std::string_view choice_name(E value) {
  static_assert(rows_in_enumerator_order<E>(), "a choice table's rows must follow its enumerators");
  return ChoiceTable<E>::rows[static_cast<std::size_t>(value)].name;
}

/// The one-line meaning of `value`.
template <Choice E>
constexpr std::string_view choice_meaning(E value) {
  static_assert(rows_in_enumerator_order<E>(), "a choice table's rows must follow its enumerators");
  return ChoiceTable<E>::rows[static_cast<std::size_t>(value)].meaning;
}

/// The value spelt `name`, or nothing.
template <Choice E>
constexpr std::optional<E> find_choice(std::string_view name) {
  for (const auto& row : ChoiceTable<E>::rows)
    if (row.name == name) return row.value;
  return std::nullopt;
}

/// "paper, balanced": every spelling, in table order.
template <Choice E>
std::string choice_names() {
  std::string out;
  for (const auto& row : ChoiceTable<E>::rows) (out += out.empty() ? "" : ", ") += row.name;
  return out;
}

/// The value spelt `name`; InputError "<what> = "<name>" is not one of: a, b" otherwise (`what`
/// names the file or option and the key, e.g. "run.toml: relax.crust_support").
template <Choice E>
E parse_choice(std::string_view name, std::string_view what) {
  if (auto value = find_choice<E>(name)) return *value;
  throw InputError(std::string(what) + " = \"" + std::string(name) + "\" is not one of: " + choice_names<E>());
}

/// The key's comment in the resolved configuration: "\"a\" (meaning a) or \"b\" (meaning b)"
/// (three or more: "\"a\" (...), \"b\" (...) or \"c\" (...)").
template <Choice E>
const std::string& choice_doc() {
  static const std::string doc = [] {
    const auto& rows = ChoiceTable<E>::rows;
    std::string out;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (i > 0) out += i + 1 == rows.size() ? " or " : ", ";
      ((((out += '"') += rows[i].name) += "\" (") += rows[i].meaning) += ')';
    }
    return out;
  }();
  return doc;
}

}  // namespace tidalcrust
