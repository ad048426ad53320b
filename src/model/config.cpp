#include "model/config.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <cmath>
#include <concepts>
#include <fstream>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <sstream>
#include <toml++/toml.h>
#include <type_traits>

#include "base/errors.hpp"
#include "base/invariant.hpp"

namespace tidalcrust {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
/// TOML integers are signed 64-bit: a larger seed could not be written back.
constexpr std::uint64_t max_toml_integer = std::numeric_limits<std::int64_t>::max();

/// When a key's conditional readers read it: `text` for the key reference, `holds` decides.
struct Condition {
  std::string_view text;
  bool (*holds)(const Config&);
};

/// The stages whose results a key changes: `always`, and `conditional` too when `*condition`
/// holds. Empty: the key changes no result.
struct Readers {
  StageSet always;
  StageSet conditional{};
  const Condition* condition = nullptr;

  /// These readers, and `stages` when `when` holds.
  constexpr Readers and_when(const Condition& when, std::same_as<StageId> auto... stages) const {
    return {always, StageSet{stages...}, &when};
  }
};

/// The key changes the results of these stages.
constexpr Readers reads(std::same_as<StageId> auto... stages) { return {StageSet{stages...}}; }
/// A name, a checkpoint interval, a choice of kernel: no stage gives other results for it.
constexpr Readers changes_no_result{};

// The conditions under which a stage reads a key only in some configurations. The tree-code keys:
// a direct run's fingerprints stay what they were before the tree code existed. A [material]
// body derives interior.radius (read by stretch) from shell.enabled (resolve_material).
constexpr Condition tree_gravity{"gravity.method = \"tree\"",
                                 [](const Config& c) { return c.gravity.method == GravityMethod::tree; }};
constexpr Condition material_body{"a [material] body", [](const Config& c) { return c.from_material(); }};
/// The welded crust: a body with the paper's coupling keeps the fingerprints it had before the key.
/// Stretch reads it too: a [material] body's interior then fills the ball under the crust.
constexpr Condition welded_crust{"cross.coupling = \"welded\"",
                                 [](const Config& c) { return c.cross.coupling == CrossCoupling::welded; }};
/// Snapshots at a chosen interval: an encounter without them keeps the fingerprint it had before the key.
constexpr Condition snapshot_series{"encounter.snapshot_interval > 0",
                                    [](const Config& c) { return c.encounter.snapshot_interval > 0; }};
/// The griffith, critical_distance and both nonlocal rules (their flaw or segment length).
constexpr bool has_flaw_rule(FailureRuleKind kind) {
  return kind == FailureRuleKind::griffith || kind == FailureRuleKind::critical_distance ||
         kind == FailureRuleKind::nonlocal || kind == FailureRuleKind::nonlocal_principal;
}
/// The shadow rule's length (the griffith, critical_distance and nonlocal rules' too): the local rule's
/// fingerprints stay what they were before the key.
constexpr Condition shadow_rule{"encounter.failure_rule = \"shadow\", \"griffith\", \"critical_distance\", "
                                "\"nonlocal\" or \"nonlocal_principal\"",
                                [](const Config& c) {
                                  return c.encounter.failure_rule == FailureRuleKind::shadow ||
                                         has_flaw_rule(c.encounter.failure_rule);
                                }};
/// The griffith, critical_distance and nonlocal rules' length: the other rules' fingerprints stay
/// what they were before the key.
constexpr Condition flaw_rule{
    "encounter.failure_rule = \"griffith\", \"critical_distance\", \"nonlocal\" or \"nonlocal_principal\"",
    [](const Config& c) { return has_flaw_rule(c.encounter.failure_rule); }};
/// Without a crust the stretch balances the interior nodes within d_I/2 of the outermost one.
constexpr Condition no_shell{"shell.enabled = false", [](const Config& c) { return !c.shell.enabled; }};

/// The description of one configuration key whose value has type T (double, std::int64_t,
/// std::uint64_t, bool, std::string or a closed choice of model/choices.hpp): where it lives in
/// the TOML, the stages whose results it changes (the stage fingerprints are made of it:
/// model/stage_fingerprint.cpp), its unit and meaning (the comment to_toml writes; none when `unit`
/// is empty; a choice's is its table's, choice_doc), and for numbers the accepted range [min, max],
/// or (min, max] when `open_min`, [min, max) when `open_max`.
template <class T>
struct Key {
  using type = T;
  std::string_view section;
  std::string_view name;
  Readers readers;
  std::string_view unit;
  std::string_view doc;
  T min{};
  T max{};
  bool open_min = false;
  bool open_max = false;
};

template <class F> struct ValueOf { using type = F; };
template <class T> struct ValueOf<std::optional<T>> { using type = T; };
/// The value type of a field: T for T and for std::optional<T> (an optional key).
template <class F> using value_of = typename ValueOf<std::remove_const_t<F>>::type;

template <class F> constexpr bool is_optional = !std::is_same_v<value_of<F>, std::remove_const_t<F>>;

// The one description of the configuration: visit_keys calls visit(field, key) for every key, in
// to_toml order, with the field of `c` (const for a const Config) and its Key. parse_config,
// apply_override, validate, to_toml, scale_time_step, the key reference and the fingerprints
// (describe_keys) all go through it; the field's type is the key's type.
//
// Readers: every stage whose result (state, record or observables) changes when the value changes
// with everything else equal, also when the same change would change its parent too (stretch reads
// interior.radius). tests/stages/test_key_readers.cpp reruns every stage for a changed value of
// every key and fails when a stage whose result changed does not declare the key.

template <class C, class V>
  requires std::same_as<std::remove_const_t<C>, Config>
void visit_keys(C& c, V&& visit) {
  using enum StageId;
  auto key = [&]<class F>(F& field, const Key<value_of<F>>& k) { visit(field, k); };
  key(c.workflow.name, {"workflow", "name", changes_no_result, "-", "workflow name; default output folder checkpoints/<name>/ (letters, digits, -, _, .; at most 200 bytes)"});
  key(c.workflow.seed,
      {"workflow", "seed", reads(build), "-", "seed of the random interior (std::mt19937_64)", 0, max_toml_integer});

  key(c.interior.count, {"interior", "count", reads(build), "-", "N_I, target number of interior nodes", 1, 1'000'000});
  key(c.interior.radius, {"interior", "radius", reads(build, stretch), "R",
                          "r_I, radius of the sphere the interior nodes fill", 0.05, 1.0});
  key(c.interior.min_separation,
      {"interior", "min_separation", reads(build), "R", "d_IS, minimum distance between interior nodes", 1e-3, 1.0});
  key(c.interior.spring_distance,
      {"interior", "spring_distance", reads(build).and_when(no_shell, stretch), "R",
       "d_I, interior nodes closer than this are joined by a spring", 1e-3, 2.0});
  key(c.interior.spring_constant,
      {"interior", "spring_constant", reads(build), "G M^2/R^3", "k_I, interior spring constant", 0, inf});
  key(c.interior.max_trials,
      {"interior", "max_trials", reads(build), "-",
       "random sequential addition stops after this many trial points", 1, 1'000'000'000'000});

  key(c.shell.enabled, {"shell", "enabled", reads(build).and_when(material_body, stretch), "-",
                        "false for an interior-only body (paper run N)"});
  key(c.shell.level, {"shell", "level", reads(build), "-", "L, icosahedron subdivision level: 10*4^L+2 nodes", 0, 7});
  key(c.shell.mass, {"shell", "mass", reads(build), "M", "M_S, total shell mass", 0, 0.99});
  key(c.shell.spring_constant,
      {"shell", "spring_constant", reads(build), "G M^2/R^3", "k_S, shell spring constant", 0, inf});
  key(c.shell.bending_constant,
      {"shell", "bending_constant", reads(build), "G M^2/R^2", "k_e, hinge (bending) force constant", 0, inf});
  key(c.shell.failure_strain,
      {"shell", "failure_strain", reads(relax, encounter), "-", "eps_S, tensile strain at which a shell spring fails",
       1e-9, 10});
  key(c.shell.failed_stiffness_factor,
      {"shell", "failed_stiffness_factor", reads(relax, encounter), "-",
       "F_Sk, a failed spring keeps this fraction of its stiffness (never 0)", 1e-9, 1});

  key(c.cross.distance,
      {"cross", "distance", reads(build), "R", "d_C, shell-interior pairs closer than this are joined by a cross spring",
       0, 2.0});
  key(c.cross.spring_constant,
      {"cross", "spring_constant", reads(build), "G M^2/R^3", "k_C, cross spring constant", 0, inf});
  key(c.cross.nonlinear, {"cross", "nonlinear", reads(stretch, relax, encounter), "-",
                          "apply the softening law f(eps) of eq. 26 to cross springs"});
  key(c.cross.strain_scale, {"cross", "strain_scale", reads(stretch, relax, encounter), "-", "eps_C of eq. 26", 1e-9, 10});
  key(c.cross.min_force_factor,
      {"cross", "min_force_factor", reads(stretch, relax, encounter), "-", "F_Ck of eq. 26", 1e-9, 1});
  key(c.cross.min_per_shell_node,
      {"cross", "min_per_shell_node", reads(build), "-",
       "each shell node gets at least this many cross springs, spanning 3 directions when >= 3 (0: d_C only)", 0,
       12});
  key(c.cross.coupling, {"cross", "coupling", changes_no_result.and_when(welded_crust, build, stretch, relax), "-",
                         choice_doc<CrossCoupling>()});

  key(c.integrator.dt, {"integrator", "dt", reads(relax, encounter), "t_grav", "leapfrog time step", min_time_step, 1.0});
  key(c.integrator.softening_fraction,
      {"integrator", "softening_fraction", reads(build), "-",
       "Plummer softening as a fraction of the minimum initial spacing", 0, 1});

  key(c.stretch.enabled,
      {"stretch", "enabled", reads(stretch), "-", "false skips stretching and strengthening (for comparisons)"});
  key(c.stretch.max_iterations,
      {"stretch", "max_iterations", reads(stretch), "-", "iterations allowed to find the common stretch factor", 1,
       10'000});
  key(c.stretch.tolerance,
      {"stretch", "tolerance", reads(stretch), "G M/R^2", "target |mean radial acceleration| of the surface", 0, 1});
  key(c.stretch.cross_compression,
      {"stretch", "cross_compression", reads(stretch), "-", "extra compressive strain given to cross springs", 0, 0.5});
  key(c.stretch.hydrostatic_support,
      {"stretch", "hydrostatic_support", reads(stretch), "-", choice_doc<HydrostaticSupport>()});

  key(c.relax.damping, {"relax", "damping", reads(relax), "1/t_grav", "gamma during relaxation", 0, 1e4});
  key(c.relax.duration, {"relax", "duration", reads(relax), "t_grav", "T, length of the relaxation run", 0, 1e4});
  key(c.relax.rest_length_interval,
      {"relax", "rest_length_interval", reads(relax), "steps",
       "steps between moves of shell rest lengths toward current lengths", 1, 1'000'000'000});
  key(c.relax.rest_length_rate,
      {"relax", "rest_length_rate", reads(relax), "-", "fraction of (L - L0) a shell rest length moves per update", 0,
       1});
  key(c.relax.hinge_reset_interval,
      {"relax", "hinge_reset_interval", reads(relax), "steps",
       "steps between resets of hinge rest angles to current angles", 1, 1'000'000'000});
  key(c.relax.settle_duration,
      {"relax", "settle_duration", reads(relax), "t_grav",
       "last part of T: the crust is reset to zero stress, then the body settles without creep or resets", 0, 1e4});
  key(c.relax.checkpoint_interval,
      {"relax", "checkpoint_interval", changes_no_result, "steps", "steps between mid-stage checkpoints (0: none)", 0,
       1'000'000'000'000});
  key(c.relax.stability_probe,
      {"relax", "stability_probe", reads(relax), "-",
       "run the stability probe (encounter damping, failures on, no perturber) after relaxing"});
  key(c.relax.probe_damping,
      {"relax", "probe_damping", reads(relax), "1/t_grav", "gamma of the stability probe", 0, 1e4});
  key(c.relax.probe_duration,
      {"relax", "probe_duration", reads(relax), "t_grav", "length of the stability probe", 0, 1e4});
  key(c.relax.crust_support, {"relax", "crust_support", reads(relax), "-", choice_doc<CrustSupport>()});

  // The stability probe of relax fails springs as an encounter does: it reads the failure rule's keys.
  key(c.encounter.damping, {"encounter", "damping", reads(encounter), "1/t_grav", "gamma during encounters", 0, 1e4});
  key(c.encounter.fail_interval,
      {"encounter", "fail_interval", reads(relax, encounter), "steps",
       "t_fail: at most one shell spring fails per this many steps", 1, 1'000'000'000});
  key(c.encounter.start_distance,
      {"encounter", "start_distance", reads(encounter), "R",
       "perturber distance when the encounter starts (before pericenter)", 1e-3, 1e6});
  key(c.encounter.end_distance,
      {"encounter", "end_distance", reads(encounter), "R",
       "perturber distance when the encounter ends (after pericenter)", 1e-3, 1e6});
  key(c.encounter.checkpoint_interval,
      {"encounter", "checkpoint_interval", changes_no_result, "steps", "steps between mid-stage checkpoints (0: none)",
       0, 1'000'000'000'000});
  key(c.encounter.sample_interval,
      {"encounter", "sample_interval", reads(relax, encounter), "steps", "steps between timeseries samples", 1,
       1'000'000'000});
  key(c.encounter.snapshot_interval,
      {"encounter", "snapshot_interval", changes_no_result.and_when(snapshot_series, encounter), "t_grav",
       "snapshot checkpoints every this long, counted from pericenter (0: only 1 t_grav before and after "
       "pericenter, at it and at the end; every 0.5 for a body without a crust)",
       0, 1e4});
  key(c.encounter.failure_rule,
      {"encounter", "failure_rule", reads(relax, encounter), "-", choice_doc<FailureRuleKind>()});
  key(c.encounter.exclusion_radius,
      {"encounter", "exclusion_radius", reads(relax, encounter), "L_S",
       "local rule: crack neighbourhood radius in mean shell spacings (nonlocal rule: left out of the fit)", 0, 1e3, true});
  key(c.encounter.exclusion_distance,
      {"encounter", "exclusion_distance", reads(relax, encounter), "R",
       "the crack neighbourhood radius as a length, the same at every shell level; replaces exclusion_radius "
       "(unset: exclusion_radius L_S)",
       0, 2, true});
  key(c.encounter.relaxation_crossings,
      {"encounter", "relaxation_crossings", reads(relax, encounter), "L_S/V_SP",
       "local rule: relaxation interval in shell elastic crossing times", 0, 1e6, true});
  key(c.encounter.shadow_distance,
      {"encounter", "shadow_distance", changes_no_result.and_when(shadow_rule, relax, encounter), "R",
       "shadow rule: a new crack starts no closer than this to a failed spring (resolve it: >= 3 L_S)", 0, 2, true});
  key(c.encounter.flaw_length,
      {"encounter", "flaw_length", changes_no_result.and_when(flaw_rule, relax, encounter), "R",
       "griffith rule: a new crack opens as a flaw this long, it sets the toughness; critical_distance and nonlocal "
       "rules: the segment a crack opens or grows by, over which the strain is averaged (resolve it: >= 3 L_S)", 0, 2,
       true});

  // The kernel gives other bits but the same physics: it is recorded and checked on its own
  // (stages/gravity_kernel_check.hpp), not a fingerprint key.
  key(c.gravity.kernel, {"gravity", "kernel", changes_no_result, "-", choice_doc<GravityKernel>()});
  key(c.gravity.method, {"gravity", "method", changes_no_result.and_when(tree_gravity, stretch, relax, encounter), "-",
                         choice_doc<GravityMethod>()});
  key(c.gravity.force_error,
      {"gravity", "force_error", changes_no_result.and_when(tree_gravity, stretch, relax, encounter), "-",
       "tree: target median relative force error per particle", 0, 0.5, true});

  key(c.analysis.figures,
      {"analysis", "figures", changes_no_result, "-",
       "draw each encounter's figures (PNG + SVG); false: summary.json, cracks.json and figure_data.json only"});

  // issue 12: [material], [resolution], [core] (docs/material.md); all optional. They derive keys
  // of [interior], [shell], [cross] (resolve_material), so they reach the stages that read those.
  key(c.material.youngs_modulus,
      {"material", "youngs_modulus", reads(build), "e_g",
       "E_I, interior Young's modulus (eq. 15); gives the body by its material", 0, 1e6, true});
  key(c.material.crust_thickness,
      {"material", "crust_thickness", reads(build), "R", "h_S, crust thickness: E_2D = E_I h_S (eq. 21)", 0, 0.5, true});
  key(c.material.crust_modulus_2d,
      {"material", "crust_modulus_2d", reads(build), "e_g R",
       "E_2D, crust 2D Young's modulus (instead of crust_thickness, or with it: a crust of E_S = E_2D / h_S)", 0, 1e6,
       true});
  key(c.material.flexural_rigidity,
      {"material", "flexural_rigidity", reads(build), "e_g R^3",
       "D_F, crust flexural rigidity (eq. 23); default E_S h_S^3/(12 (1 - nu^2)), nu = 1/4, E_S = E_I or E_2D / h_S", 0, 1e6, true});
  key(c.material.crust_mass, {"material", "crust_mass", reads(build), "M", "M_S, crust mass", 0, 0.99, true});
  key(c.material.crust_density,
      {"material", "crust_density", reads(build), "M/R^3",
       "rho_S, crust density (instead of crust_mass): M_S = 4 pi h_S rho_S", 0, 100, true});
  key(c.material.coupling_speed_ratio,
      {"material", "coupling_speed_ratio", reads(build), "-", "V_Co / V_IP (eqs. 25, 16); default 1", 0, 100, true});
  // eps_S becomes shell.failure_strain; build is kept so that material bodies keep their fingerprints.
  key(c.material.failure_strain,
      {"material", "failure_strain", reads(build, relax, encounter), "-",
       "eps_S, tensile strain at which the crust fails", 0, 10, true});
  key(c.resolution.shell_level,
      {"resolution", "shell_level", reads(build, stretch), "-",
       "L, icosahedron level; default 4", 1, 7});
  key(c.resolution.interior_spacing,
      {"resolution", "interior_spacing", reads(build, stretch), "R",
       "d_IS, interior node spacing; default 0.10 * 2^((4 - L)/2)", 1e-3, 0.5});
  key(c.resolution.interior_count,
      {"resolution", "interior_count", reads(build), "-", "N_I; default paper-T's packing of d_IS spheres", 1,
       1'000'000});
  key(c.resolution.cross_per_shell_node,
      {"resolution", "cross_per_shell_node", reads(build), "-", "N_C / N_S from d_C; default 2.33 (paper-T)", 0, 12,
       true});
  key(c.core.radius, {"core", "radius", reads(build, stretch), "R", "r_c, radius of a denser, stiffer core", 0, 0.95, true});
  key(c.core.density_ratio,
      {"core", "density_ratio", reads(build, stretch), "-", "rho_core / rho_mantle; default 1", 0, 100, true});
  key(c.core.modulus_ratio,
      {"core", "modulus_ratio", reads(build, stretch), "-", "E_core / E_mantle; default 1", 0, 1000, true});

  // issue 26: [ocean], a liquid layer under the crust (docs/ocean.md); optional. The builder turns
  // the interior nodes within `thickness` of the shell into liquid particles; the stretch sets
  // their reference densities from the hydrostatic pressure and K.
  key(c.ocean.thickness, {"ocean", "thickness", reads(build, stretch), "R",
                          "from the crust down to the ocean floor (unset: no ocean)", 0, 0.9, true});
  key(c.ocean.bulk_modulus, {"ocean", "bulk_modulus", reads(build, stretch), "e_g",
                             "K of the liquid; default the interior's, E_I / 1.5 (nu = 1/4)", 0, 1e6, true});
  key(c.ocean.shear_fraction, {"ocean", "shear_fraction", reads(build), "-",
                               "stiffness the liquid's springs keep, of the interior's: a small static shear modulus "
                               "that steadies the liquid (docs/ocean.md); default 0.01", 1e-4, 1, true});
  key(c.ocean.maxwell_time, {"ocean", "maxwell_time", reads(build), "t_grav",
                             "tau_M: from the end of the relaxation the liquid's springs relax their stress on this "
                             "time, their resting forces kept as a fixed support (a Maxwell liquid, docs/ocean.md); "
                             "unset: they stay elastic", 1e-3, 1e6, true});

  // issue 25: [moon], the moon in SI (docs/moon.md); all optional. Quantities are strings with their
  // unit (the key's unit is the SI unit they are converted to). They fill [material] and [core]
  // (resolve_moon): each declares the stages that read the values it fills.
  key(c.moon.preset, {"moon", "preset", reads(build, stretch, relax, encounter), "-",
                      "a moon of docs/moon.md (any case: tethys, europa, ...): fills every [moon] value not given"});
  key(c.moon.radius, {"moon", "radius", reads(build, stretch), "m", "R, the moon's radius, a length: \"531 km\""});
  key(c.moon.mass, {"moon", "mass", reads(build, stretch), "kg", "M, the moon's mass: \"6.17e20 kg\" (or mean_density)"});
  key(c.moon.mean_density, {"moon", "mean_density", reads(build, stretch), "kg/m^3",
                            "3 M / (4 pi R^3), instead of mass: \"0.98 g/cm3\""});
  key(c.moon.youngs_modulus, {"moon", "youngs_modulus", reads(build, stretch, relax, encounter), "Pa",
                              "E_I, the interior's Young's modulus (nu = 1/4): \"9 GPa\""});
  key(c.moon.crust_thickness, {"moon", "crust_thickness", reads(build, stretch), "m", "h_S, the crust's thickness: \"20 km\""});
  key(c.moon.crust_density, {"moon", "crust_density", reads(build, stretch), "kg/m^3", "rho_S, the crust's density: \"0.93 g/cm3\""});
  key(c.moon.crust_youngs_modulus, {"moon", "crust_youngs_modulus", reads(build, relax, encounter), "Pa",
                                    "E_S, the crust's Young's modulus; default E_I: \"0.9 GPa\""});
  key(c.moon.tensile_strength, {"moon", "tensile_strength", reads(build, relax, encounter), "Pa",
                                "sigma_t, the crust's tensile strength: eps_S = sigma_t / E_S: \"1 MPa\""});
  key(c.moon.failure_strain, {"moon", "failure_strain", reads(build, relax, encounter), "-",
                              "eps_S, instead of tensile_strength", 0, 10, true});
  key(c.moon.core_radius, {"moon", "core_radius", reads(build, stretch), "m", "r_c, radius of a denser, stiffer core: \"150 km\""});
  key(c.moon.core_density, {"moon", "core_density", reads(build, stretch), "kg/m^3", "rho_c, the core's density (with core_radius)"});
  key(c.moon.core_youngs_modulus, {"moon", "core_youngs_modulus", reads(build, stretch), "Pa",
                                   "E_c, the core's Young's modulus; default E_I"});
  key(c.moon.spin_period, {"moon", "spin_period", reads(relax, encounter), "s",
                           "P, the moon's rotation period: \"45.3 h\" (gives spin.angular_velocity = 2 pi t_grav / P)"});

  // issue 25: [crust], a crust that varies over the surface (docs/crust.md, model/crust_field.hpp); all
  // optional. The builder samples the field into the body (node masses, spring and hinge
  // stiffnesses, each shell spring's strength factor), so only build reads them: the later stages
  // read the body.
  key(c.crust.thickness_harmonics,
      {"crust", "thickness_harmonics", reads(build), "-",
       "thickness h_S t(x), t = 1 + sum of real harmonics (Schmidt): \"c10 = 0.5\" thick north, \"s11 = 0.5\" thick "
       "toward +y (lon 90)"});
  key(c.crust.strength_harmonics,
      {"crust", "strength_harmonics", reads(build), "-",
       "failure strain eps_S f(x), f = 1 + sum of real harmonics (Schmidt), as thickness_harmonics"});
  key(c.crust.weak_lines,
      {"crust", "weak_lines", reads(build), "-",
       "circles of lowered strength, ';' between lines: \"pole_lon = 0, pole_lat = 0, radius = 90, half_width = 4, "
       "factor = 0.5\" (deg; radius 90: a great circle)"});
  key(c.crust.map_file,
      {"crust", "map_file", reads(build), "-",
       "CSV lon,lat,thickness_factor,strength_factor on a regular lat/lon grid; multiplies t and f (its content "
       "is map_digest)"});
  key(c.crust.map_digest,
      {"crust", "map_digest", reads(build), "-",
       "XXH3-64 of map_file's bytes, recorded when the workflow is read (a changed file is refused)"});

  // issue 26: [spin], the body spins about its z axis (docs/spin.md); optional, so that a body
  // without spin keeps its stored text and fingerprints (0 is the same as unset: normalize_spin).
  // Relax relaxes the body in the co-rotating frame; the encounter's analysis maps the failures
  // in the body's frame.
  key(c.spin.angular_velocity,
      {"spin", "angular_velocity", reads(relax, encounter), "1/t_grav",
       "Omega, the body's spin about its z axis (north), rad/t_grav = fraction of breakup sqrt(GM/R^3); default 0",
       0, max_spin, false, true});
}

/// The keys of one [[encounters]] table (paper Table 4). The encounter stage reads its own table
/// (its name is in its record); the stability probe of relax also probes every encounter's eps_S.
template <class E, class V>
  requires std::same_as<std::remove_const_t<E>, Encounter>
void visit_keys(E& e, V&& visit) {
  using enum StageId;
  auto key = [&]<class F>(F& field, const Key<value_of<F>>& k) { visit(field, k); };
  key(e.name, {"encounters", "name", reads(encounter), "", "name of the encounter (required): its folder and label (letters, digits, -, _, .; not body, body-seed<N>, slurm, validate, analysis, status.json, dt<F>)"});
  key(e.perturber_mass, {"encounters", "perturber_mass", reads(encounter), "M", "M2", 0, inf, true});
  key(e.pericenter, {"encounters", "pericenter", reads(encounter), "R", "q", 1, inf, true});  // outside the body
  key(e.pericenter_speed,
      {"encounters", "pericenter_speed", reads(encounter), "sqrt(GM/R)",
       "V_q; default parabolic, sqrt(2 (1 + M2) / q) of the table's M2 and q", 0, inf, true});
  key(e.failure_strain, {"encounters", "failure_strain", reads(relax, encounter), "-", "eps_S override", 0, inf, true});
  key(e.relaxation_crossings,
      {"encounters", "relaxation_crossings", reads(encounter), "L_S/V_SP",
       "local failure rule: relaxation interval override", 0, 1e6, true});
  key(e.body_seed, {"encounters", "body_seed", reads(encounter), "-",
                    "seed of the body this encounter branches from (its own body chain in body-seed<N>/); none: "
                    "workflow.seed, the workflow's body",
                    0, max_toml_integer});
  // issue 25: encounter histories and the orbit's orientation (docs/encounter-history.md). Optional,
  // so that encounters without them keep their stored text and fingerprints.
  key(e.after, {"encounters", "after", reads(encounter), "-",
                "name of the encounter whose final state this one begins from (its failures carried over); none: "
                "the relaxed body"});
  key(e.inclination, {"encounters", "inclination", reads(encounter), "deg",
                      "i, the orbit's inclination to the xy plane of the maps; default 0 (180: retrograde)", 0, 180});
  key(e.ascending_node, {"encounters", "ascending_node", reads(encounter), "deg",
                         "Omega, longitude of the ascending node from +x; default 0", -360, 360});
  key(e.argument_of_pericenter,
      {"encounters", "argument_of_pericenter", reads(encounter), "deg",
       "omega, from the ascending node to the pericenter; default 90 (with i = Omega = 0: the subsatellite point at "
       "longitude 90, latitude 0)",
       -360, 360});
}

/// The sections of Config in to_toml order (without "encounters").
const std::vector<std::string_view>& section_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> out;
    const Config defaults;
    visit_keys(defaults, [&](const auto&, const auto& key) {
      if (out.empty() || out.back() != key.section) out.push_back(key.section);
    });
    return out;
  }();
  return names;
}

/// "a, b, c": the keys of `section` in a `Target` (Config or Encounter), for error messages.
template <class Target>
std::string known_keys(std::string_view section) {
  std::string out;
  const Target defaults{};
  visit_keys(defaults, [&](const auto&, const auto& key) {
    if (key.section == section) out += fmt::format("{}{}", out.empty() ? "" : ", ", key.name);
  });
  return out;
}

// ---- values as TOML text ----------------------------------------------------------------------

std::string toml_text(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // keep it a TOML float
  return s;
}
std::string toml_text(std::int64_t v) { return fmt::format("{}", v); }
std::string toml_text(std::uint64_t v) { return fmt::format("{}", v); }
std::string toml_text(bool v) { return v ? "true" : "false"; }
std::string toml_text(const std::string& s) {
  std::ostringstream out;
  out << toml::value<std::string>(s);
  return out.str();
}
template <Choice E>
std::string toml_text(E value) {
  return toml_text(std::string(choice_name(value)));
}

/// "name = value  # [unit] doc\n" ("name = value\n" without a unit); nothing for an unset
/// optional key.
template <class F, class T>
std::string toml_line(const F& field, const Key<T>& key) {
  if constexpr (is_optional<F>) {
    return field ? toml_line(*field, key) : std::string();
  } else {
    std::string line = fmt::format("{} = {}", key.name, toml_text(field));
    if (!key.unit.empty()) line += fmt::format("  # [{}] {}", key.unit, key.doc);
    return line + "\n";
  }
}

// ---- reading and checking values --------------------------------------------------------------

/// The value of a TOML node for `key`; `where` prefixes the message of a wrong type, `origin`
/// (the file or --set) that of a value that is not one of a choice's.
template <class T>
T read_value(const toml::node& node, const Key<T>& key, const std::string& where, const std::string& origin) {
  auto wrong = [&](const char* expected) {
    return InputError(fmt::format("{}: '{}' must be {}", where, key.name, expected));
  };
  if constexpr (std::is_same_v<T, double>) {
    if (auto v = node.value_exact<double>()) return *v;
    if (auto i = node.value_exact<std::int64_t>()) return static_cast<double>(*i);
    // A string here is most often a quantity with its unit: say where those go.
    if (node.is_string() && !key.unit.empty() && key.unit != "-")
      throw InputError(fmt::format("{}: '{}' must be a number in {} (model units G = M = R = 1); a quantity with "
                                   "its unit (\"0.9 GPa\", \"531 km\") goes in [moon] (docs/moon.md)",
                                   where, key.name, key.unit));
    throw wrong("a number");
  } else if constexpr (std::is_same_v<T, std::int64_t>) {
    if (auto i = node.value_exact<std::int64_t>()) return *i;
    throw wrong("an integer");
  } else if constexpr (std::is_same_v<T, std::uint64_t>) {
    auto i = node.value_exact<std::int64_t>();
    if (!i) throw wrong("an integer");
    if (*i < 0) throw wrong(">= 0");
    return static_cast<std::uint64_t>(*i);
  } else if constexpr (std::is_same_v<T, bool>) {
    if (auto b = node.value_exact<bool>()) return *b;
    throw wrong("true or false");
  } else if constexpr (Choice<T>) {
    if (auto s = node.value_exact<std::string>())
      return parse_choice<T>(*s, fmt::format("{}: {}.{}", origin, key.section, key.name));
    throw wrong(fmt::format("one of: {}", choice_names<T>()).c_str());
  } else {
    static_assert(std::is_same_v<T, std::string>);
    if (auto s = node.value_exact<std::string>()) return *s;
    if (const auto dimension = dimension_of_si_unit(key.unit); dimension && node.is_number())
      throw wrong(fmt::format("{} with its unit, as a string (e.g. \"{}\"): a plain number has no unit",
                              dimension_name(*dimension), dimension_example(*dimension))
                      .c_str());
    throw wrong("a string");
  }
}

/// The deepest nesting toml++ would build for `text`, checked before it parses: its parser
/// descends once per dotted-key part (unbounded: 40,000 parts overflow the stack) and per array
/// or inline table. A light scan (strings and comments skipped) adds up the table header's parts,
/// the dotted parts of the keys on the way in and the open arrays and inline tables; more than
/// max_toml_nesting is an InputError naming `origin` and the line. Workflows nest 3 deep.
constexpr int max_toml_nesting = 64;

void check_toml_nesting(std::string_view text, const std::string& origin) {
  int line = 1;
  int header_parts = 0;   // parts of the last [table] header beyond the first
  int path_parts = 0;     // dotted parts of the keys enclosing the current position
  int key_parts = 0;      // dots of the key being read
  bool in_key = true;     // reading a key (or a table header), not a value
  bool in_header = false;
  struct Open {
    char kind;
    int path_parts;
  };
  std::vector<Open> open;
  auto check = [&] {
    if (header_parts + path_parts + key_parts + static_cast<int>(open.size()) > max_toml_nesting)
      throw InputError(fmt::format("{}:{}: nested deeper than {} levels (table names, dotted keys, arrays and inline "
                                   "tables together)",
                                   origin, line, max_toml_nesting));
  };
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n; ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      if (open.empty()) in_key = true, path_parts = 0, key_parts = 0, in_header = false;
    } else if (c == '#') {
      while (i + 1 < n && text[i + 1] != '\n') ++i;
    } else if (c == '"' || c == '\'') {
      const bool triple = i + 2 < n && text[i + 1] == c && text[i + 2] == c;
      const std::size_t quotes = triple ? 3 : 1;
      i += quotes;
      for (; i < n; ++i) {
        if (text[i] == '\n') ++line;
        if (c == '"' && text[i] == '\\') {
          ++i;
          if (i < n && text[i] == '\n') ++line;
          continue;
        }
        if (text[i] == c && (!triple || (i + 2 < n && text[i + 1] == c && text[i + 2] == c))) {
          if (triple) {
            i += 2;
            while (i + 1 < n && text[i + 1] == c) ++i;  // up to two more quotes belong to the string
          }
          break;
        }
        if (!triple && text[i] == '\n') break;  // unterminated: the parser reports it
      }
    } else if (in_key) {
      if (c == '.') {
        ++key_parts;
        check();
      } else if (c == '=') {
        in_key = false;
        path_parts += key_parts;
        key_parts = 0;
      } else if (c == '[' && open.empty()) {
        in_header = true;
      } else if (c == ']' && in_header) {
        header_parts = key_parts;
        key_parts = 0;
        in_header = false;
      } else if (c == '}' && !open.empty()) {  // an empty inline table, or a trailing comma
        path_parts = open.back().path_parts;
        open.pop_back();
        in_key = false;
      }
    } else if (c == '[' || c == '{') {
      open.push_back({c, path_parts});
      check();
      in_key = c == '{';
    } else if ((c == ']' || c == '}') && !open.empty()) {
      path_parts = open.back().path_parts;
      open.pop_back();
    } else if (c == ',' && !open.empty() && open.back().kind == '{') {
      path_parts = open.back().path_parts;
      in_key = true;
    }
  }
}

/// Sets the key `name` of `section` in `target` (a Config or an Encounter) from a TOML node;
/// false when there is no such key. `where` and `origin`: as for read_value.
template <class Target>
bool set_key(Target& target, std::string_view section, std::string_view name, const toml::node& node,
             const std::string& where, const std::string& origin) {
  bool found = false;
  visit_keys(target, [&](auto& field, const auto& key) {
    if (key.section != section || key.name != name) return;
    field = read_value(node, key, where, origin);
    found = true;
  });
  return found;
}

/// InputError "<what> = <value> is out of range [min, max] (unit)" for a number outside its
/// key's range (NaN and infinities included); bool, text and unset optional keys have no range.
template <class F, class T>
void check_range(const F& field, const Key<T>& key, const std::string& what) {
  if constexpr (is_optional<F>) {
    if (field) check_range(*field, key, what);
  } else if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
    bool inside = field >= key.min && field <= key.max && !(key.open_min && field == key.min) &&
                  !(key.open_max && field == key.max);
    if constexpr (std::is_floating_point_v<T>) inside = inside && std::isfinite(field);
    if (!inside)
      throw InputError(fmt::format("{} = {} is out of range {}{}, {}{} ({})", what, field, key.open_min ? '(' : '[',
                                   key.min, key.max, key.open_max ? ')' : ']', key.unit));
  }
}

/// Names of the encounter folders' neighbours in an output root: the body chain, the Slurm
/// scripts, validate's results and the status file (and dt<F>/, the folders of --dt-factor).
bool reserved_encounter_name(std::string_view name) {
  for (std::string_view taken : {"body", "slurm", "validate", "status.json", "analysis"})
    if (name == taken) return true;
  if (name.starts_with("body-seed")) return true;  // the body chains of other seeds (body_seed)
  return name.size() > 2 && name.starts_with("dt") &&
         (std::isdigit(static_cast<unsigned char>(name[2])) || name[2] == '.');
}

void check_encounter_name(const std::string& name, const std::string& origin) {
  if (name.empty()) throw InputError(fmt::format("{}: encounter needs a non-empty 'name'", origin));
  if (const std::string problem = path_name_problem(name); !problem.empty())
    throw InputError(fmt::format("{}: encounter name {}", origin, problem));
  if (reserved_encounter_name(name))
    throw InputError(fmt::format("{}: encounter name '{}' is reserved (the output folder holds body/, body-seed<N>/, "
                                 "slurm/, validate/, status.json and dt<F>/ beside the encounters)",
                                 origin, name));
}

/// InputError unless `listed` [[encounters]] tables and `swept` encounters of [sweep] are at most
/// max_encounters together: the one limit and its one message.
void check_encounter_count(std::size_t listed, std::size_t swept, const std::string& origin) {
  if (listed <= max_encounters && swept <= max_encounters - listed) return;
  const std::size_t total = swept > std::numeric_limits<std::size_t>::max() - listed ? std::numeric_limits<std::size_t>::max()
                                                                                     : listed + swept;
  throw InputError(fmt::format("{}: the workflow has {} encounters ({} [[encounters]] tables, {} from [sweep]); at most {}",
                               origin, total, listed, swept, max_encounters));
}

/// Gives `e` the parabolic speed of its M2 and q (the one default speed) once both are within
/// their ranges (else validate names the one that is not, and the speed stays); InputError naming
/// both when their speed is not a finite number (M2 = 1e308).
void make_parabolic(Encounter& e, const std::string& where) {
  const double m = e.perturber_mass, q = e.pericenter;
  if (!(std::isfinite(m) && m > 0 && std::isfinite(q) && q > 1)) return;
  const double v = parabolic_speed(m, q);
  if (!std::isfinite(v))
    throw InputError(fmt::format("{}: encounters.perturber_mass = {} and pericenter = {} give a parabolic "
                                 "pericenter_speed that is not a finite number (give pericenter_speed)",
                                 where, m, q));
  e.pericenter_speed = v;
}

/// An encounter value given in SI ("977 km"): converted with the moon's units once [moon] is read
/// (convert_encounter_quantities).
struct EncounterQuantity {
  std::size_t encounter;  ///< index in the [[encounters]] tables
  std::string key;        ///< perturber_mass, pericenter or pericenter_speed
  std::string text;
  std::string where;
};

/// The dimension of an [[encounters]] key that may be given in SI; none for the others.
std::optional<Dimension> encounter_dimension(std::string_view key) {
  if (key == "perturber_mass") return Dimension::mass;
  if (key == "pericenter") return Dimension::length;
  if (key == "pericenter_speed") return Dimension::speed;
  return std::nullopt;
}

std::vector<Encounter> parse_encounters(const toml::node& node, const std::string& origin,
                                        std::vector<EncounterQuantity>& in_si) {
  auto* array = node.as_array();
  if (!array) throw InputError(fmt::format("{}: 'encounters' must be an array of tables ([[encounters]])", origin));
  check_encounter_count(array->size(), 0, origin);
  std::vector<Encounter> encounters;
  for (auto&& element : *array) {
    const std::string where = fmt::format("{}: encounters[{}]", origin, encounters.size());
    auto* table = element.as_table();
    if (!table) throw InputError(where + ": must be a table");
    Encounter& e = encounters.emplace_back();
    bool given_in_si = false;
    for (auto&& [k, value] : *table) {
      if (value.is_string() && encounter_dimension(k.str())) {  // in SI: converted once [moon] is read
        in_si.push_back({encounters.size() - 1, std::string(k.str()), *value.value<std::string>(), where});
        given_in_si = true;
        continue;
      }
      if (!set_key(e, "encounters", k.str(), value, where, origin))
        throw InputError(fmt::format("{}: unknown key '{}' (known: {})", where, k.str(),
                                     known_keys<Encounter>("encounters")));
    }
    // The one default speed, as a [sweep]'s: parabolic for this table's M2 and q (of values in
    // SI: once they are converted).
    if (table->get("pericenter_speed") == nullptr && !given_in_si) make_parabolic(e, where);
  }
  return encounters;
}

/// Converts the [[encounters]] values given in SI to model units with the units of the moon of
/// [moon] (M, R, v_c = sqrt(G M / R)); an encounter given in SI without its own speed gets the
/// parabolic one. InputError naming the encounter and key when there is no [moon] or a bad quantity.
void convert_encounter_quantities(std::vector<Encounter>& encounters, const std::vector<EncounterQuantity>& in_si,
                                  const MoonConfig& moon, const std::string& origin) {
  if (in_si.empty()) return;
  if (!moon.given())
    throw InputError(fmt::format("{}: {} = \"{}\": a string is a quantity with its unit, which needs the moon in SI "
                                 "([moon]); without it give a number in model units",
                                 in_si.front().where, in_si.front().key, in_si.front().text));
  const ModelUnits units = moon_model_values(moon, origin).units;
  std::set<std::size_t> with_speed;
  for (const EncounterQuantity& q : in_si) {
    const Dimension dimension = *encounter_dimension(q.key);
    const double value = si_to_model(units, dimension, quantity_si(q.text, dimension, fmt::format("{}: {}", q.where, q.key)));
    Encounter& e = encounters[q.encounter];
    (q.key == "perturber_mass" ? e.perturber_mass : q.key == "pericenter" ? e.pericenter : e.pericenter_speed) = value;
    if (q.key == "pericenter_speed") with_speed.insert(q.encounter);
  }
  for (const EncounterQuantity& q : in_si)
    if (!with_speed.contains(q.encounter)) make_parabolic(encounters[q.encounter], q.where);
}

/// The values of one [sweep] axis: a list of numbers, or {from, to, count} (count values evenly
/// spaced from `from` to `to`, both included). Empty when the key is absent.
std::vector<double> sweep_axis(const toml::table& sweep, std::string_view key, const std::string& origin) {
  const toml::node* node = sweep.get(key);
  if (!node) return {};
  const std::string where = fmt::format("{}: sweep.{}", origin, key);
  std::vector<double> values;
  if (auto* list = node->as_array()) {
    for (auto&& item : *list) {
      const auto v = item.value<double>();
      if (!v || !std::isfinite(*v)) throw InputError(where + ": every entry must be a finite number");
      values.push_back(*v);
    }
  } else if (auto* range = node->as_table()) {
    for (auto&& [k, unused] : *range)
      if (k.str() != "from" && k.str() != "to" && k.str() != "count")
        throw InputError(fmt::format("{}: unknown key '{}' (a range has from, to, count)", where, k.str()));
    constexpr double missing = std::numeric_limits<double>::quiet_NaN();
    const toml::node* count_node = range->get("count");
    const double from = range->get("from") ? range->get("from")->value<double>().value_or(missing) : missing;
    const double to = range->get("to") ? range->get("to")->value<double>().value_or(missing) : missing;
    if (!std::isfinite(from) || !std::isfinite(to) || !count_node || !count_node->is_integer())
      throw InputError(where + ": a range needs numbers from, to and an integer count");
    const std::int64_t count = count_node->value<std::int64_t>().value_or(0);
    if (count < 1 || count > 1000) throw InputError(fmt::format("{}: count = {} is out of range [1, 1000]", where, count));
    // Each value is the double of the decimal it stands for (1.9 .. 2.4 in 6 steps gives 2.2, not
    // 2.1999999999999997, which would also name its folder): rounded to 15 significant digits,
    // which every decimal of at most 15 digits survives; the ends are from and to themselves.
    for (std::int64_t i = 0; i < count; ++i) {
      const double v = from + (to - from) * static_cast<double>(i) / static_cast<double>(count - 1);
      values.push_back(count == 1 || i == 0 ? from : i == count - 1 ? to : std::strtod(fmt::format("{:.15g}", v).c_str(), nullptr));
    }
  } else {
    throw InputError(where + ": must be a list of numbers or a range {from, to, count}");
  }
  if (values.empty()) throw InputError(where + ": has no values");
  return values;
}

/// A number as it appears in a sweep encounter's name: the shortest form that reads back the
/// same double, without '+' (names allow letters, digits, '-', '_', '.').
std::string name_number(double v) {
  std::string text = fmt::format("{}", v);
  std::erase(text, '+');
  return text;
}

/// [sweep] as a SweepConfig (perturber_mass and pericenter required), not yet expanded.
SweepConfig parse_sweep(const toml::node& node, const std::string& origin) {
  auto* table = node.as_table();
  if (!table) throw InputError(fmt::format("{}: 'sweep' must be a table", origin));
  static constexpr std::string_view axes[] = {"perturber_mass", "pericenter", "pericenter_speed", "failure_strain"};
  for (auto&& [k, unused] : *table)
    if (std::find(std::begin(axes), std::end(axes), k.str()) == std::end(axes))
      throw InputError(fmt::format("{}: unknown key 'sweep.{}' (known: {})", origin, k.str(), fmt::join(axes, ", ")));
  SweepConfig sweep;
  sweep.perturber_mass = sweep_axis(*table, "perturber_mass", origin);
  sweep.pericenter = sweep_axis(*table, "pericenter", origin);
  sweep.pericenter_speed = sweep_axis(*table, "pericenter_speed", origin);
  sweep.failure_strain = sweep_axis(*table, "failure_strain", origin);
  if (sweep.perturber_mass.empty() || sweep.pericenter.empty())
    throw InputError(fmt::format("{}: [sweep] needs perturber_mass and pericenter", origin));
  return sweep;
}

/// The keys of [ensemble], for the unknown-key errors.
constexpr const char* ensemble_keys = "members, pericenter_perturbation, vary";

/// [ensemble] as an EnsembleConfig (members required; ranges checked by validate).
EnsembleConfig parse_ensemble(const toml::node& node, const std::string& origin) {
  auto* table = node.as_table();
  if (!table) throw InputError(fmt::format("{}: 'ensemble' must be a table", origin));
  EnsembleConfig ensemble;
  for (auto&& [k, value] : *table) {
    const std::string where = fmt::format("{}: ensemble.{}", origin, k.str());
    if (k.str() == "members") {
      if (!value.is_integer()) throw InputError(where + ": must be an integer");
      ensemble.members = value.value<std::int64_t>().value_or(0);
    } else if (k.str() == "pericenter_perturbation") {
      const auto v = value.value<double>();
      if (!v || !value.is_number()) throw InputError(where + ": must be a number");
      ensemble.pericenter_perturbation = *v;
    } else if (k.str() == "vary") {
      if (!value.is_string()) throw InputError(where + ": must be a string");
      ensemble.vary = parse_choice<EnsembleVariation>(*value.value<std::string>(), where);
    } else {
      throw InputError(fmt::format("{}: unknown key 'ensemble.{}' (known: {})", origin, k.str(), ensemble_keys));
    }
  }
  if (!table->get("members")) throw InputError(fmt::format("{}: [ensemble] needs members", origin));
  return ensemble;
}

/// The [ensemble] table of to_toml.
std::string ensemble_toml(const EnsembleConfig& ensemble) {
  return fmt::format("[ensemble]\nmembers = {}\npericenter_perturbation = {}  # relative change of q, -\nvary = \"{}\"  # "
                     "{}\n",
                     ensemble.members, toml_text(ensemble.pericenter_perturbation), choice_name(ensemble.vary),
                     choice_doc<EnsembleVariation>());
}

/// Refuses an [ensemble] whose values are out of range or whose members would be too many
/// encounters (`count` encounters before the expansion).
void check_ensemble(const EnsembleConfig& ensemble, std::size_t count, const std::string& origin) {
  if (ensemble.members < 3 || ensemble.members > max_ensemble_members)
    throw InputError(fmt::format("{}: ensemble.members = {} is out of range [3, {}]", origin, ensemble.members,
                                 max_ensemble_members));
  if (!(ensemble.pericenter_perturbation > 0 && ensemble.pericenter_perturbation <= 0.05))
    throw InputError(fmt::format("{}: ensemble.pericenter_perturbation = {} is out of range (0, 0.05]", origin,
                                 ensemble.pericenter_perturbation));
  if (count > max_encounters / static_cast<std::size_t>(ensemble.members))
    throw InputError(fmt::format("{}: the workflow has {} encounters of {} members each ({} in all); at most {}", origin,
                                 count, ensemble.members, count * static_cast<std::size_t>(ensemble.members),
                                 max_encounters));
}

/// config.encounters = the members of config.ensemble_bases (the one place the expansion is
/// stored). InputError naming `origin` when [ensemble] is out of range or a member's body seed
/// would pass the largest seed.
void expand_ensemble_of(Config& config, const std::string& origin) {
  const EnsembleConfig& ensemble = *config.ensemble;
  check_ensemble(ensemble, config.ensemble_bases.size(), origin);
  if (ensemble.vary != EnsembleVariation::pericenter)
    for (const Encounter& base : config.ensemble_bases) {
      const std::uint64_t seed = base.body_seed.value_or(config.workflow.seed);
      const auto last = static_cast<std::uint64_t>(ensemble.members - 1);
      if (seed > max_toml_integer || max_toml_integer - seed < last)
        throw InputError(fmt::format("{}: ensemble.vary = \"{}\": encounter '{}' on the body of seed {} would give "
                                     "member {} the seed {} + {}, past the largest seed {}",
                                     origin, choice_name(ensemble.vary), base.name, seed, last, seed, last,
                                     max_toml_integer));
    }
  config.encounters = expand_ensemble(config.ensemble_bases, ensemble, config.workflow.seed);
}

/// How many of `config.encounters` to_toml writes as [[encounters]] tables: all of them, unless
/// the last sweep_size(*config.sweep) are exactly the sweep's expansion (then [sweep] stands for them).
std::size_t listed_encounter_count(const std::vector<Encounter>& encounters, const std::optional<SweepConfig>& sweep) {
  if (!sweep) return encounters.size();
  const std::size_t swept = sweep_size(*sweep);
  if (swept > encounters.size()) return encounters.size();
  const std::size_t listed = encounters.size() - swept;
  const std::vector<Encounter> expanded = expand_sweep(*sweep);
  return std::equal(expanded.begin(), expanded.end(), encounters.begin() + static_cast<std::ptrdiff_t>(listed))
             ? listed
             : encounters.size();
}

/// The [sweep] table of to_toml: each axis as the list of its values, read back bit for bit.
std::string sweep_toml(const SweepConfig& sweep) {
  std::string out = fmt::format("[sweep]  # {} encounters\n", sweep_size(sweep));
  const auto axis = [&](std::string_view name, const std::vector<double>& values) {
    if (values.empty()) return;
    std::vector<std::string> texts;
    for (double v : values) texts.push_back(toml_text(v));
    out += fmt::format("{} = [{}]\n", name, fmt::join(texts, ", "));
  };
  axis("perturber_mass", sweep.perturber_mass);
  axis("pericenter", sweep.pericenter);
  axis("pericenter_speed", sweep.pericenter_speed);
  axis("failure_strain", sweep.failure_strain);
  return out;
}

/// One [section] of to_toml.
std::string section_toml(const Config& config, std::string_view section) {
  std::string out = fmt::format("[{}]\n", section);
  visit_keys(config, [&](const auto& field, const auto& key) {
    if (key.section == section && !derived_by_material(config, key.section, key.name) &&
        !(config.choose_dt && key.section == "integrator" && key.name == "dt"))
      out += toml_line(field, key);
  });
  return out;
}

/// The keys a [material] body derives (beyond eps_S, which material.failure_strain derives).
constexpr std::string_view material_derived_keys[] = {
    "interior.count", "interior.radius", "interior.min_separation", "interior.spring_distance",
    "interior.spring_constant", "shell.level", "shell.mass", "shell.spring_constant", "shell.bending_constant",
    "cross.distance", "cross.spring_constant"};

/// InputError when [material] and a key it derives are both given ("both" names the file).
void refuse_derived_key(const Config& config, std::string_view section, std::string_view name,
                        const std::string& origin) {
  if (derived_by_material(config, section, name))
    throw InputError(fmt::format("{}: {}.{} is derived from [material]; give either the spring constants or "
                                 "[material], not both",
                                 origin, section, name));
}

/// A [material] or [core] field a [moon] table fills, and the value it fills in (none: not filled).
struct MoonField {
  std::string_view key;     ///< "material.youngs_modulus"
  std::string_view source;  ///< the [moon] keys it comes from
  std::optional<double>* field;
  std::optional<double> value;
};

/// The fields a [moon] table fills in `c`, with the values `v` of moon_model_values.
std::vector<MoonField> moon_fields(Config& c, const MoonModelValues& v) {
  return {{"material.youngs_modulus", "moon.youngs_modulus", &c.material.youngs_modulus, v.youngs_modulus},
          {"material.crust_thickness", "moon.crust_thickness", &c.material.crust_thickness, v.crust_thickness},
          {"material.crust_density", "moon.crust_density", &c.material.crust_density, v.crust_density},
          {"material.crust_modulus_2d", "moon.crust_youngs_modulus", &c.material.crust_modulus_2d, v.crust_modulus_2d},
          {"material.failure_strain", "moon.tensile_strength or moon.failure_strain", &c.material.failure_strain,
           v.failure_strain},
          {"core.radius", "moon.core_radius", &c.core.radius, v.core_radius},
          {"core.density_ratio", "moon.core_density", &c.core.density_ratio, v.core_density_ratio},
          {"core.modulus_ratio", "moon.core_youngs_modulus", &c.core.modulus_ratio, v.core_modulus_ratio},
          {"spin.angular_velocity", "moon.spin_period", &c.spin.angular_velocity, v.spin_angular_velocity}};
}

/// A spin of 0 is no spin: unset, so that its text and fingerprints are those of a body without [spin].
void normalize_spin(Config& c) {
  if (c.spin.angular_velocity == 0.0) c.spin.angular_velocity.reset();
}

/// Unsets the [material] and [core] values the [moon] table of `c` filled (before it changes).
void forget_moon_values(Config& c, const std::string& origin) {
  if (!c.moon.given()) return;
  for (MoonField& f : moon_fields(c, moon_model_values(c.moon, origin)))
    if (f.value && *f.field == f.value) f.field->reset();
}

}  // namespace

void resolve_moon(Config& c, const std::string& origin) {
  if (!c.moon.given()) return;
  const MoonModelValues values = moon_model_values(c.moon, origin);
  if (values.spin_angular_velocity && !(*values.spin_angular_velocity < max_spin))
    throw InputError(fmt::format("{}: moon.spin_period = \"{}\" gives spin.angular_velocity = {:.4g} rad/t_grav, "
                                 "at or beyond {} of breakup (a longer period, or no spin)",
                                 origin, *c.moon.spin_period, *values.spin_angular_velocity, max_spin));
  for (MoonField& f : moon_fields(c, values)) {
    if (!f.value) continue;
    if (*f.field && **f.field != *f.value)
      throw InputError(fmt::format("{}: {} = {} and [moon] ({}, giving {}) both set it; give one of them", origin, f.key,
                                   toml_text(**f.field), f.source, toml_text(*f.value)));
    *f.field = f.value;
  }
}

std::optional<MoonScale> output_moon(const Config& config, const std::string& origin) {
  if (!config.moon.given()) return std::nullopt;
  return moon_scale(config.moon, origin);
}

std::optional<MoonScale> stored_moon(const std::string& config_toml, const std::string& origin) {
  if (config_toml.empty()) return std::nullopt;  // a checkpoint made in memory (tests), not by a stage
  return output_moon(parse_config(config_toml, origin), origin);
}

std::string path_name_problem(std::string_view name) {
  // Shown with control characters escaped, so that the message stays one line.
  std::string shown;
  for (unsigned char ch : name.substr(0, 60))
    shown += ch < 0x20 || ch == 0x7f ? fmt::format("\\x{:02x}", ch) : std::string(1, static_cast<char>(ch));
  if (name.size() > 60) shown += "...";
  if (name.empty()) return "is empty";
  if (name.size() > max_path_name_bytes)
    return fmt::format("'{}' is {} bytes long (at most {})", shown, name.size(), max_path_name_bytes);
  if (name == "." || name == "..") return fmt::format("'{}' names a folder itself, not a new one", shown);
  if (name.front() == '-') return fmt::format("'{}' must not begin with '-' (it would read as an option)", shown);
  for (unsigned char ch : name)
    if (!((ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-' ||
          ch == '_' || ch == '.'))
      return fmt::format("'{}' may only use letters, digits, '-', '_', '.' ({} is not one)", shown,
                         ch < 0x20 || ch == 0x7f || ch >= 0x80 ? fmt::format("byte 0x{:02x}", ch)
                                                              : fmt::format("'{}'", static_cast<char>(ch)));
  return {};
}

bool derived_by_material(const Config& config, std::string_view section, std::string_view name) {
  if (!config.from_material()) return false;
  const std::string full = fmt::format("{}.{}", section, name);
  if (full == "shell.failure_strain") return config.material.failure_strain.has_value();
  return std::find(std::begin(material_derived_keys), std::end(material_derived_keys), full) !=
         std::end(material_derived_keys);
}

double material_crust_modulus_2d(const MaterialConfig& m) {
  if (m.crust_modulus_2d) return *m.crust_modulus_2d;
  return m.youngs_modulus.value_or(0) * m.crust_thickness.value_or(0);
}

double material_flexural_rigidity(const MaterialConfig& m) {
  if (m.flexural_rigidity) return *m.flexural_rigidity;
  const double nu = material_poisson_ratio;
  // A crust of its own modulus E_S = E_2D / h_S: D_F = E_S h_S^3 / (12 (1 - nu^2)); with E_S = E_I
  // the same bits as below.
  if (m.crust_modulus_2d && m.crust_thickness)
    return *m.crust_modulus_2d * *m.crust_thickness * *m.crust_thickness / (12 * (1 - nu * nu));
  const double E = m.youngs_modulus.value_or(0);
  const double h = m.crust_thickness.value_or(E > 0 ? material_crust_modulus_2d(m) / E : 0.0);
  return E * h * h * h / (12 * (1 - nu * nu));
}

void resolve_crust(Config& c, const std::filesystem::path& relative_to) {
  if (!c.crust.map_file || c.crust.map_digest) return;
  std::filesystem::path file(*c.crust.map_file);
  if (file.is_relative()) file = std::filesystem::absolute(relative_to / file);
  c.crust.map_file = file.lexically_normal().string();
  read_crust_map(*c.crust.map_file);  // a bad table is refused now, naming its line, before anything runs
  c.crust.map_digest = crust_map_digest(*c.crust.map_file);
}

void resolve_material(Config& c, const std::string& origin) {
  if (!c.from_material()) return;
  // The material's own ranges first: a bad value must be named, not the key derived from it.
  visit_keys(c, [&](const auto& field, const auto& key) {
    if (key.section == "material" || key.section == "resolution" || key.section == "core")
      check_range(field, key, fmt::format("{}: {}.{}", origin, key.section, key.name));
  });
  const MaterialConfig& m = c.material;
  auto need = [&](bool given, const char* what) {
    if (!given) throw InputError(fmt::format("{}: [material] needs {}", origin, what));
  };
  auto refuse_both = [&](bool a, bool b, const char* what) {
    if (a && b) throw InputError(fmt::format("{}: [material] takes {}, not both", origin, what));
  };
  refuse_both(m.crust_mass.has_value(), m.crust_density.has_value(), "material.crust_mass or material.crust_density");
  if (c.shell.enabled) {
    need(m.crust_thickness || m.crust_modulus_2d, "material.crust_thickness or material.crust_modulus_2d");
    need(m.crust_mass || m.crust_density, "material.crust_mass or material.crust_density");
  }
  // Resolution: paper-T's geometry (d_IS = 0.10 at level 4, d_I = 2.3 d_IS, r_I = 1 - 1.03 d_IS,
  // N_I filling the ball at its packing fraction 1869 (d_IS/2)^3 / 0.897^3 = 0.324), with the
  // interior spacing shrinking as the square root of the shell's (docs/material.md).
  const std::int64_t level = c.resolution.shell_level.value_or(4);
  const double spacing = c.resolution.interior_spacing.value_or(0.10 * std::pow(2.0, 0.5 * static_cast<double>(4 - level)));
  constexpr double packing_fraction = 1869 * 0.05 * 0.05 * 0.05 / (0.897 * 0.897 * 0.897);
  c.shell.level = level;
  c.interior.min_separation = spacing;
  c.interior.spring_distance = 2.3 * spacing;
  c.interior.radius = c.shell.enabled ? 1.0 - 1.03 * spacing : 1.0 - 0.5 * spacing;
  if (c.shell.enabled && c.cross.coupling == CrossCoupling::welded) {
    // The welded interior reaches the crust: it fills the ball under the crust's thickness.
    const double e2d_welded = material_crust_modulus_2d(m);
    c.interior.radius = 1.0 - m.crust_thickness.value_or(e2d_welded / *m.youngs_modulus);
  }
  const double cells = 2 * c.interior.radius / spacing;
  c.interior.count = c.resolution.interior_count.value_or(std::llround(packing_fraction * cells * cells * cells));
  // The crust: E_2D = (2/sqrt 3) k_S (eq. 20), resolution-free; M_S; eps_S.
  const double e2d = material_crust_modulus_2d(m);
  c.shell.spring_constant = std::sqrt(3.0) / 2.0 * e2d;
  const double thickness = m.crust_thickness.value_or(e2d / *m.youngs_modulus);
  c.shell.mass = m.crust_mass ? *m.crust_mass : 4 * std::numbers::pi * thickness * m.crust_density.value_or(0);
  if (c.shell.enabled && !(c.shell.mass > 0 && c.shell.mass < 0.99))
    throw InputError(fmt::format("{}: material.crust_density gives a crust mass of {:.4g} M (must be in (0, 0.99))",
                                 origin, c.shell.mass));
  if (m.failure_strain) c.shell.failure_strain = *m.failure_strain;
  // Built from the network by the build stage; these values are placeholders that nothing reads.
  c.cross.distance = 1.0 - c.interior.radius + c.interior.spring_distance;
}

const Encounter& Config::find_encounter(const std::string& name) const {
  if (const std::string problem = path_name_problem(name); !problem.empty())
    throw InputError(fmt::format("encounter name {}", problem));
  if (const Encounter* e = encounter_or_null(name)) return *e;
  std::string known;  // the first 20 names: a sweep's 10,000 would not make one line
  for (std::size_t i = 0; i < std::min<std::size_t>(encounters.size(), 20); ++i)
    known += (known.empty() ? "" : ", ") + encounters[i].name;
  if (encounters.size() > 20) known += fmt::format(" and {} more", encounters.size() - 20);
  throw InputError(fmt::format("unknown encounter '{}' (this workflow has: {})", name,
                               known.empty() ? "none" : known));
}

const Encounter* Config::encounter_or_null(std::string_view name) const {
  const auto found =
      std::find_if(encounters.begin(), encounters.end(), [&](const Encounter& e) { return e.name == name; });
  return found == encounters.end() ? nullptr : &*found;
}

std::vector<Encounter> Config::encounters_named(const std::string& name) const {
  const bool is_base = ensemble && std::any_of(ensemble_bases.begin(), ensemble_bases.end(),
                                               [&](const Encounter& b) { return b.name == name; });
  if (!is_base) return {find_encounter(name)};
  std::vector<Encounter> members;
  for (std::int64_t k = 0; k < ensemble->members; ++k) members.push_back(find_encounter(fmt::format("{}_m{}", name, k)));
  return members;
}

void scale_time_step(Config& config, double factor) {
  config.integrator.dt *= factor;
  visit_keys(config, [factor](auto& steps, const auto& key) {
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(steps)>, std::int64_t>)
      if (key.unit == "steps" && steps > 0)
        steps = std::max<std::int64_t>(1, std::llround(static_cast<double>(steps) / factor));
  });
}

std::size_t sweep_size(const SweepConfig& sweep) {
  std::size_t total = 1;
  for (const auto* axis : {&sweep.perturber_mass, &sweep.pericenter, &sweep.pericenter_speed, &sweep.failure_strain}) {
    const std::size_t n = std::max<std::size_t>(1, axis->size());
    total = total > std::numeric_limits<std::size_t>::max() / n ? std::numeric_limits<std::size_t>::max() : total * n;
  }
  return total;
}

std::vector<Encounter> expand_sweep(const SweepConfig& sweep) {
  const auto& speeds = sweep.pericenter_speed;
  const auto& strains = sweep.failure_strain;
  std::vector<Encounter> out;
  out.reserve(sweep_size(sweep));
  for (double m : sweep.perturber_mass)
    for (double q : sweep.pericenter)
      for (std::size_t v = 0; v < std::max<std::size_t>(1, speeds.size()); ++v)
        for (std::size_t s = 0; s < std::max<std::size_t>(1, strains.size()); ++s) {
          Encounter& e = out.emplace_back();
          e.perturber_mass = m;
          e.pericenter = q;
          e.pericenter_speed = speeds.empty() ? parabolic_speed(m, q) : speeds[v];
          e.name = fmt::format("M{}_q{}_V{}", name_number(m), name_number(q),
                               speeds.empty() ? std::string("par") : name_number(speeds[v]));
          if (!strains.empty()) {
            e.failure_strain = strains[s];
            e.name += "_eps" + name_number(strains[s]);
          }
        }
  return out;
}

double ensemble_pericenter_offset(const EnsembleConfig& ensemble, std::int64_t member) {
  if (ensemble.vary == EnsembleVariation::body_seed) return 0.0;
  const double n = static_cast<double>(ensemble.members);
  return ensemble.pericenter_perturbation * ((2.0 * static_cast<double>(member) + 1.0) / n - 1.0);
}

std::vector<Encounter> expand_ensemble(const std::vector<Encounter>& encounters, const EnsembleConfig& ensemble,
                                       std::uint64_t workflow_seed) {
  std::vector<Encounter> out;
  out.reserve(encounters.size() * static_cast<std::size_t>(std::max<std::int64_t>(0, ensemble.members)));
  for (const Encounter& base : encounters)
    for (std::int64_t k = 0; k < ensemble.members; ++k) {
      Encounter& member = out.emplace_back(base);
      member.name = fmt::format("{}_m{}", base.name, k);
      // A history runs per member: member k follows member k of the encounter it comes after.
      if (base.after) member.after = fmt::format("{}_m{}", *base.after, k);
      member.pericenter = base.pericenter * (1.0 + ensemble_pericenter_offset(ensemble, k));
      if (ensemble.vary != EnsembleVariation::pericenter && k > 0) {
        // Seeds count from the encounter's own body; member 0 stays on it (and keeps its name of it).
        const std::uint64_t seed = base.body_seed.value_or(workflow_seed) + static_cast<std::uint64_t>(k);
        member.body_seed = seed == workflow_seed ? std::nullopt : std::optional<std::uint64_t>(seed);
      }
    }
  return out;
}

std::uint64_t body_seed_of(const Config& config, const Encounter& encounter) {
  // An encounter of a history is on the body of the first encounter of its chain (the chain is
  // checked by validate; the bound stops at a cycle of an unvalidated configuration).
  const Encounter* first = &encounter;
  for (std::size_t hops = 0; first->after && hops < config.encounters.size(); ++hops) {
    const Encounter* before = config.encounter_or_null(*first->after);
    if (!before) break;
    first = before;
  }
  return first->body_seed.value_or(config.workflow.seed);
}

void check_encounter_histories(const Config& config, const std::string& origin) {
  for (const Encounter& e : config.encounters) {
    if (!e.after) continue;
    const std::string where = fmt::format("{}: encounter '{}': after = \"{}\"", origin, e.name, *e.after);
    const Encounter* before = config.encounter_or_null(*e.after);
    if (!before) throw InputError(where + ": no encounter of that name in the workflow");
    std::set<std::string_view> seen{e.name};
    for (const Encounter* step = before; step; step = step->after ? config.encounter_or_null(*step->after) : nullptr)
      if (!seen.insert(step->name).second)
        throw InputError(fmt::format("{}: the history returns to '{}' (a cycle)", where, step->name));
    if (e.body_seed && *e.body_seed != body_seed_of(config, *before))
      throw InputError(fmt::format("{}: body_seed = {} differs from the body of '{}' (seed {}), which this encounter "
                                   "continues; leave body_seed out",
                                   where, *e.body_seed, before->name, body_seed_of(config, *before)));
  }
}

Config body_config_of(const Config& config, const Encounter& encounter) {
  Config out = config;
  out.workflow.seed = body_seed_of(config, encounter);
  return out;
}

void validate_encounter(const Encounter& e, const std::string& origin) {
  check_encounter_name(e.name, origin);
  visit_keys(e, [&](const auto& field, const auto& key) {
    check_range(field, key, fmt::format("{}: encounter '{}': {}", origin, e.name, key.name));
  });
}

void validate(const Config& config, const std::string& origin) {
  visit_keys(config, [&](const auto& field, const auto& key) {
    check_range(field, key, fmt::format("{}: {}.{}", origin, key.section, key.name));
  });
  if (!config.from_material()) {
    std::string resolution_given;
    visit_keys(config, [&](const auto& field, const auto& key) {
      if constexpr (is_optional<std::remove_cvref_t<decltype(field)>>)
        if (field && key.section == "material")
          throw InputError(fmt::format("{}: material.{} needs material.youngs_modulus", origin, key.name));
      if constexpr (is_optional<std::remove_cvref_t<decltype(field)>>)
        if (field && key.section == "resolution" && resolution_given.empty()) resolution_given = key.name;
    });
    if (!resolution_given.empty())
      throw InputError(fmt::format("{}: resolution.{}: [resolution] applies only to a [material] body", origin,
                                   resolution_given));
  }
  // r_ex has one value: as a length (exclusion_distance) or in L_S (exclusion_radius), not both.
  if (config.encounter.exclusion_distance && config.encounter.exclusion_radius != EncounterDefaults{}.exclusion_radius)
    throw InputError(fmt::format("{}: encounter.exclusion_distance = {} R and encounter.exclusion_radius = {} L_S both "
                                 "give the crack neighbourhood's radius; give one of them",
                                 origin, *config.encounter.exclusion_distance, config.encounter.exclusion_radius));
  if (config.core.present() && *config.core.radius >= config.interior.radius)
    throw InputError(fmt::format("{}: core.radius = {} must be smaller than the interior radius {}", origin,
                                 *config.core.radius, config.interior.radius));
  if (!config.core.present() && (config.core.density_ratio || config.core.modulus_ratio))
    throw InputError(fmt::format("{}: core.{} needs core.radius ([core] needs core.radius)", origin,
                                 config.core.density_ratio ? "density_ratio" : "modulus_ratio"));
  if (config.ocean.present() != (config.relax.crust_support == CrustSupport::floating))
    throw InputError(fmt::format("{}: {}", origin,
                                 config.ocean.present()
                                     ? fmt::format("ocean.thickness = {}: a crust on an ocean floats: it needs "
                                                   "relax.crust_support = \"floating\"", *config.ocean.thickness)
                                     : "relax.crust_support = \"floating\" needs an ocean to float on ([ocean] thickness)"));
  if (config.ocean.present() && !config.shell.enabled)
    throw InputError(fmt::format("{}: [ocean] needs a crust to float (shell.enabled = true)", origin));
  if (config.ocean.present() && !config.from_material() && !config.ocean.bulk_modulus)
    throw InputError(fmt::format("{}: ocean.bulk_modulus is needed without [material] (its default is the "
                                 "interior's, from material.youngs_modulus)", origin));
  if (!config.ocean.present() && config.ocean.bulk_modulus)
    throw InputError(fmt::format("{}: ocean.bulk_modulus needs ocean.thickness ([ocean] needs ocean.thickness)", origin));
  if (!config.ocean.present() && config.ocean.shear_fraction)
    throw InputError(fmt::format("{}: ocean.shear_fraction needs ocean.thickness ([ocean] needs ocean.thickness)", origin));
  if (!config.ocean.present() && config.ocean.maxwell_time)
    throw InputError(fmt::format("{}: ocean.maxwell_time needs ocean.thickness ([ocean] needs ocean.thickness)", origin));
  // The support is a force fixed in the inertial frame; a spinning body would turn under it.
  if (config.ocean.maxwell_time && config.spin.rate() != 0)
    throw InputError(fmt::format("{}: ocean.maxwell_time (a Maxwell liquid) is not available on a spinning body "
                                 "(spin.angular_velocity = {}): its support does not turn with the body",
                                 origin, config.spin.rate()));
  if (config.ocean.present() && config.core.present() && *config.core.radius >= 1 - *config.ocean.thickness)
    throw InputError(fmt::format("{}: core.radius = {} reaches into the ocean (its floor lies at 1 - ocean.thickness "
                                 "= {})", origin, *config.core.radius, 1 - *config.ocean.thickness));
  // The welded springs continue the interior network up to the shell; they do not bridge a missing
  // layer (docs/crust-support.md, "The interior must reach the crust"). A [material] body fills
  // r_I = 1 - h_S itself; an ocean lies between on purpose.
  if (config.cross.coupling == CrossCoupling::welded && config.shell.enabled && !config.from_material() &&
      !config.ocean.present() && 1 - config.interior.radius > config.interior.min_separation / 2)
    throw InputError(fmt::format("{}: cross.coupling = \"welded\" needs an interior that reaches the crust: "
                                 "interior.radius = {} leaves {:.3g} R under the shell, more than half "
                                 "interior.min_separation ({}); raise interior.radius to at least {:.4g}",
                                 origin, config.interior.radius, 1 - config.interior.radius,
                                 config.interior.min_separation, 1 - config.interior.min_separation / 2));
  // The [crust] grammar (model/crust_field.hpp); the map file was read by resolve_crust.
  const std::string crust = origin + ": crust";
  if (config.crust.thickness_harmonics) parse_harmonics(*config.crust.thickness_harmonics, crust + ".thickness_harmonics");
  if (config.crust.strength_harmonics) parse_harmonics(*config.crust.strength_harmonics, crust + ".strength_harmonics");
  if (config.crust.weak_lines) parse_weak_lines(*config.crust.weak_lines, crust + ".weak_lines");
  if (config.crust.given() && !config.shell.enabled)
    throw InputError(fmt::format("{}: [crust] needs a crust (shell.enabled = true)", crust));
  if (config.workflow.name.empty())
    throw InputError(fmt::format("{}: workflow.name must not be empty", origin));
  if (const std::string problem = path_name_problem(config.workflow.name); !problem.empty())
    throw InputError(fmt::format("{}: workflow.name {}", origin, problem));
  if (config.interior.min_separation >= config.interior.spring_distance)
    throw InputError(fmt::format("{}: interior.min_separation ({}) must be smaller than interior.spring_distance ({})",
                                 origin, config.interior.min_separation, config.interior.spring_distance));
  if (config.interior.min_separation > 2 * config.interior.radius)
    throw InputError(fmt::format("{}: interior.min_separation is larger than the interior", origin));
  if (config.relax.settle_duration > config.relax.duration)
    throw InputError(fmt::format("{}: relax.settle_duration ({}) must not exceed relax.duration ({})", origin,
                                 config.relax.settle_duration, config.relax.duration));
  if (config.encounter.snapshot_interval > 0 && config.encounter.snapshot_interval < config.integrator.dt)
    throw InputError(fmt::format("{}: encounter.snapshot_interval = {} is shorter than integrator.dt = {}: at most one "
                                 "snapshot per step (0: no series)",
                                 origin, config.encounter.snapshot_interval, config.integrator.dt));
  if (config.relax.crust_support != CrustSupport::paper && config.cross.nonlinear)
    throw InputError(fmt::format("{}: relax.crust_support = \"{}\" needs linear cross springs "
                                 "(cross.nonlinear = false): the balance solves for linear spring tensions",
                                 origin, choice_name(config.relax.crust_support)));
  if (config.relax.crust_support == CrustSupport::lithostatic &&
      (config.cross.coupling != CrossCoupling::welded || !config.shell.enabled))
    throw InputError(fmt::format("{}: relax.crust_support = \"lithostatic\" needs a crust welded to the interior "
                                 "(cross.coupling = \"welded\"): its compression is derived for a welded crust",
                                 origin));
  if (config.cross.coupling == CrossCoupling::welded && config.cross.nonlinear)
    throw InputError(fmt::format("{}: cross.coupling = \"welded\" needs linear cross springs (cross.nonlinear = "
                                 "false): the welded springs continue the linear interior network",
                                 origin));
  const std::vector<Encounter>& unexpanded = config.ensemble ? config.ensemble_bases : config.encounters;
  const std::size_t swept = config.sweep ? std::min(sweep_size(*config.sweep), unexpanded.size()) : 0;
  check_encounter_count(unexpanded.size() - swept, swept, origin);
  if (config.ensemble && config.ensemble->members == 0)
    throw InputError(fmt::format("{}: [ensemble] needs members (e.g. --set ensemble.members=10)", origin));
  if (config.ensemble) check_ensemble(*config.ensemble, unexpanded.size(), origin);
  std::set<std::string> names;
  for (const auto& e : config.encounters) {
    validate_encounter(e, origin);
    if (!names.insert(e.name).second)
      throw InputError(fmt::format("{}: encounter name '{}' appears twice", origin, e.name));
  }
  check_encounter_histories(config, origin);
}

Config parse_config(const std::string& toml_text, const std::string& origin, const std::filesystem::path& relative_to) {
  check_toml_nesting(toml_text, origin);
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& err) {
    const auto& where = err.source().begin;
    throw InputError(fmt::format("{}:{}:{}: malformed TOML: {}", origin, where.line, where.column,
                                 err.description()));
  }
  Config config;
  std::vector<EncounterQuantity> in_si;  // [[encounters]] values with units
  for (auto&& [sk, snode] : root) {
    const std::string section(sk.str());
    if (section == "encounters") {
      auto listed = parse_encounters(snode, origin, in_si);
      config.encounters.insert(config.encounters.begin(), listed.begin(), listed.end());
      continue;
    }
    if (section == "sweep") {  // expanded below, after the [[encounters]] tables
      config.sweep = parse_sweep(snode, origin);
      continue;
    }
    if (section == "ensemble") {  // expanded below, after the sweep
      config.ensemble = parse_ensemble(snode, origin);
      continue;
    }
    if (std::find(section_names().begin(), section_names().end(), section) == section_names().end())
      throw InputError(fmt::format("{}: unknown section '{}' (known: {}, encounters, sweep, ensemble)", origin, section,
                                   fmt::join(section_names(), ", ")));
    auto* table = snode.as_table();
    if (!table) throw InputError(fmt::format("{}: '{}' must be a table", origin, section));
    for (auto&& [k, node] : *table) {
      if (section == "moon" && k.str() == "poisson_ratio") {  // checked, not kept: the network's nu is 1/4
        check_moon_poisson_ratio(node.value<double>().value_or(std::numeric_limits<double>::quiet_NaN()),
                                 fmt::format("{}: moon.poisson_ratio", origin));
        continue;
      }
      if (!set_key(config, section, k.str(), node, fmt::format("{}: {}", origin, section), origin))
        throw InputError(fmt::format("{}: unknown key '{}.{}' (known: {})", origin, section, k.str(),
                                     known_keys<Config>(section)));
    }
  }
  convert_encounter_quantities(config.encounters, in_si, config.moon, origin);  // the tables come first
  if (config.sweep) {
    check_encounter_count(config.encounters.size(), sweep_size(*config.sweep), origin);
    const std::vector<Encounter> swept = expand_sweep(*config.sweep);
    config.encounters.insert(config.encounters.end(), swept.begin(), swept.end());
  }
  if (config.ensemble) {
    config.ensemble_bases = std::move(config.encounters);
    expand_ensemble_of(config, origin);
  }
  resolve_moon(config, origin);  // [moon] fills [material] and [core]
  normalize_spin(config);
  if (config.from_material())  // [material] derives these: giving them too is ambiguous
    for (auto&& [sk, snode] : root)
      if (auto* table = snode.as_table())
        for (auto&& [k, unused] : *table) refuse_derived_key(config, sk.str(), k.str(), origin);
  resolve_material(config, origin);
  const toml::table* integrator = root["integrator"].as_table();
  config.choose_dt = config.from_material() && !(integrator && integrator->get("dt") != nullptr);
  // A [material] body keeps its moduli at every resolution unless the file asks otherwise.
  const toml::table* stretch = root["stretch"].as_table();
  if (config.from_material() && !(stretch && stretch->get("hydrostatic_support") != nullptr))
    config.stretch.hydrostatic_support = HydrostaticSupport::compress;
  resolve_crust(config, relative_to);
  validate(config, origin);
  return config;
}

Config load_config(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open configuration file: {}", file.string(), std::strerror(errno)));
  try {
    std::stringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw InputError(fmt::format("{}: cannot read configuration file: {}", file.string(), std::strerror(errno)));
    return parse_config(buffer.str(), file.string(), file.parent_path());
  } catch (const std::bad_alloc&) {
    throw InputError(fmt::format("{}: not enough memory to read the configuration file", file.string()));
  }
}

void apply_override(Config& config, const std::string& assignment) {
  const std::string where = fmt::format("--set '{}'", assignment);
  const auto eq = assignment.find('=');
  const auto dot = assignment.substr(0, eq).find('.');
  if (eq == std::string::npos || dot == std::string::npos)
    throw InputError(where + ": expected section.key=value");
  const std::string section = assignment.substr(0, dot);
  std::string key = assignment.substr(dot + 1, eq - dot - 1);
  std::string value = assignment.substr(eq + 1);
  // A bare word is a string (--set relax.crust_support=balanced): shells eat the TOML quotes.
  const bool bare_word = !value.empty() && std::all_of(value.begin(), value.end(), [](unsigned char ch) {
    return std::isalpha(ch) || ch == '_' || ch == '-' || (std::isdigit(ch) != 0);
  }) && std::isalpha(static_cast<unsigned char>(value[0])) && value != "true" && value != "false" && value != "inf" && value != "nan";
  if (bare_word) value = "\"" + value + "\"";
  check_toml_nesting("v = " + value, where);
  toml::table parsed;
  try {
    parsed = toml::parse(std::string_view("v = " + value), std::string_view("--set"));
  } catch (const toml::parse_error& err) {
    throw InputError(fmt::format("{}: value is not valid TOML: {}", where, err.description()));
  }
  const toml::node& node = *parsed.get("v");
  if (section == "ensemble") {
    // Members of the encounters as they are now (an ensemble given here branches every one).
    if (!config.ensemble) config.ensemble_bases = config.encounters, config.ensemble = EnsembleConfig{};
    if (key == "members" && node.is_integer())
      config.ensemble->members = node.value<std::int64_t>().value_or(0);
    else if (key == "pericenter_perturbation" && node.is_number())
      config.ensemble->pericenter_perturbation = node.value<double>().value_or(0);
    else if (key == "vary" && node.is_string())
      config.ensemble->vary = parse_choice<EnsembleVariation>(*node.value<std::string>(), where + ": ensemble.vary");
    else if (key == "members" || key == "pericenter_perturbation" || key == "vary")
      throw InputError(fmt::format("{}: ensemble.{} must be {}", where, key,
                                   key == "members" ? "an integer" : key == "vary" ? "a string" : "a number"));
    else
      throw InputError(fmt::format("{}: unknown key 'ensemble.{}' (known: {})", where, key, ensemble_keys));
    // Expanded once members is given (the keys may come in either order); validate refuses an
    // ensemble left without members.
    if (config.ensemble->members != 0)
      expand_ensemble_of(config, where);
    else
      config.encounters = config.ensemble_bases;
    return;
  }
  if (section == "moon") {
    if (key == "poisson_ratio")
      return check_moon_poisson_ratio(node.value<double>().value_or(std::numeric_limits<double>::quiet_NaN()),
                                      where + ": moon.poisson_ratio");
    // The [material] and [core] values the old [moon] filled give way to the new ones.
    forget_moon_values(config, where);
    if (!set_key(config, section, key, node, "--set", "--set"))
      throw InputError(fmt::format("{}: unknown key '{}.{}'", where, section, key));
    resolve_moon(config, where);
    resolve_material(config, where);
    return;
  }
  if (section != "encounters") {
    if (!set_key(config, section, key, node, "--set", "--set"))
      throw InputError(fmt::format("{}: unknown key '{}.{}'", where, section, key));
    refuse_derived_key(config, section, key, where);
    if (section == "crust" && key == "map_file") config.crust.map_digest.reset();  // the new file's
    resolve_crust(config, {});
    resolve_moon(config, where);  // a value [moon] filled: given again only with the same value
    normalize_spin(config);
    if (section == "integrator" && key == "dt") config.choose_dt = false;
    // Members of an ensemble that varies the body branch from seeds counted from workflow.seed.
    if (section == "workflow" && key == "seed" && config.ensemble && config.ensemble->members != 0)
      expand_ensemble_of(config, where);
    resolve_material(config, where);
    return;
  }
  const auto dot2 = key.rfind('.');  // encounters.NAME.key=value (a name may hold dots: M0.5_q1.6_V1.8)
  if (dot2 == std::string::npos) throw InputError(where + ": expected encounters.NAME.key=value");
  const std::string name = key.substr(0, dot2);
  key = key.substr(dot2 + 1);
  const auto named = [&](const Encounter& spec) { return spec.name == name; };
  // A parabolic encounter stays parabolic when --set changes its M2 or q (its speed was derived
  // from them, parse_encounters); a speed given otherwise is kept.
  const auto set_encounter_key = [&](Encounter& spec) {
    const bool parabolic = spec.pericenter_speed == parabolic_speed(spec.perturber_mass, spec.pericenter);
    if (!set_key(spec, "encounters", key, node, where, where))
      throw InputError(fmt::format("{}: unknown key '{}' (known: {})", where, key, known_keys<Encounter>("encounters")));
    if (parabolic && (key == "perturber_mass" || key == "pericenter")) make_parabolic(spec, where);
  };
  if (config.ensemble) {  // an encounter before the expansion: all its members change
    const auto base = std::find_if(config.ensemble_bases.begin(), config.ensemble_bases.end(), named);
    if (base != config.ensemble_bases.end()) {
      set_encounter_key(*base);
      expand_ensemble_of(config, where);
      return;
    }
  }
  const auto e = std::find_if(config.encounters.begin(), config.encounters.end(), named);
  if (e == config.encounters.end()) throw InputError(fmt::format("{}: no encounter named '{}'", where, name));
  set_encounter_key(*e);
}

namespace {

template <class T>
constexpr const char* type_name() {
  if constexpr (std::is_same_v<T, double>) return "number";
  else if constexpr (std::is_same_v<T, bool>) return "boolean";
  else if constexpr (std::is_same_v<T, std::string>) return "string";
  else if constexpr (Choice<T>) return "choice";
  else return "integer";
}

std::string range_text(double v) {
  if (v == inf) return "inf";
  return fmt::format("{}", v);
}
std::string range_text(std::int64_t v) { return fmt::format("{}", v); }
std::string range_text(std::uint64_t v) { return fmt::format("{}", v); }

/// The KeyInfo of one key of `visit_keys`, with the value of `field`.
template <class F, class T>
KeyInfo key_info(const F& field, const Key<T>& key, const Config& config) {
  KeyInfo info;
  info.section = key.section;
  info.name = key.name;
  info.type = type_name<T>();
  info.unit = key.unit;
  info.doc = key.doc;
  if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>)
    info.range = fmt::format("{}{}, {}{}", key.open_min ? '(' : '[', range_text(key.min), range_text(key.max),
                             key.open_max ? ')' : ']');
  if constexpr (Choice<T>) info.range = fmt::format("one of: {}", choice_names<T>());
  info.optional = is_optional<F>;
  if constexpr (is_optional<F>) {
    if (field) info.value = toml_text(*field);
  } else {
    info.value = toml_text(field);
  }
  info.readers = key.readers.always;
  info.read_by = key.readers.always;
  if (key.readers.condition) {
    info.conditional_readers = key.readers.conditional;
    info.condition = key.readers.condition->text;
    if (key.readers.condition->holds(config)) info.read_by = info.read_by | key.readers.conditional;
  }
  return info;
}

}  // namespace

std::vector<KeyInfo> describe_keys(const Config& config) {
  std::vector<KeyInfo> keys;
  visit_keys(config, [&](const auto& field, const auto& key) { keys.push_back(key_info(field, key, config)); });
  return keys;
}

std::vector<KeyInfo> describe_keys(const Encounter& encounter, const Config& config) {
  std::vector<KeyInfo> keys;
  visit_keys(encounter, [&](const auto& field, const auto& key) { keys.push_back(key_info(field, key, config)); });
  return keys;
}

std::int64_t integer_key_value(const Config& config, std::string_view section, std::string_view name) {
  std::optional<std::int64_t> value;
  visit_keys(config, [&](const auto& field, const auto& key) {
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(field)>, std::int64_t>)
      if (key.section == section && key.name == name) value = field;
  });
  TIDALCRUST_ASSERT(value.has_value(), fmt::format("no integer configuration key {}.{}", section, name));
  return *value;
}

std::string encounter_toml(const Encounter& encounter) {
  std::string out = "[[encounters]]\n";
  visit_keys(encounter, [&](const auto& field, const auto& key) { out += toml_line(field, key); });
  return out;
}

std::string to_toml(const Config& config) {
  std::string out = "# tidalcrust resolved configuration (every key, defaults included)\n";
  for (auto section : section_names()) out += "\n" + section_toml(config, section);
  // The bases and [ensemble] while the encounters are exactly their members (else, after a --set
  // of one member, every member as a table), each list with [sweep] standing for its expansion.
  const bool as_ensemble =
      config.ensemble &&
      config.encounters == expand_ensemble(config.ensemble_bases, *config.ensemble, config.workflow.seed);
  const std::vector<Encounter>& encounters = as_ensemble ? config.ensemble_bases : config.encounters;
  const std::size_t listed = listed_encounter_count(encounters, config.sweep);
  for (std::size_t i = 0; i < listed; ++i) out += "\n" + encounter_toml(encounters[i]);
  if (listed < encounters.size()) out += "\n" + sweep_toml(*config.sweep);
  if (as_ensemble) out += "\n" + ensemble_toml(*config.ensemble);
  return out;
}

}  // namespace tidalcrust
