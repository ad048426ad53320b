#pragma once
// The workflow configuration: every parameter of the paper with a default, a unit and a range.
// Read from TOML (toml++); unknown keys and out-of-range values are InputErrors naming the key.
// Each key (section, name, the stages whose results it changes, type, unit, range, meaning) is
// described once, in config.cpp (visit_keys), and parsing, --set, validation, the resolved TOML
// text, the key reference (`tidalcrust config --defaults`, docs/configuration.md) and the stage
// fingerprints (model/stage_fingerprint.hpp) all read that description.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "model/choices.hpp"
#include "model/crust_field.hpp"
#include "model/encounter.hpp"
#include "model/moon_units.hpp"
#include "model/stage_records.hpp"

namespace tidalcrust {

struct WorkflowConfig {
  std::string name = "unnamed";
  std::uint64_t seed = 1;
};

/// Random isotropic interior (paper section 2.2, Kot 2015).
struct InteriorConfig {
  std::int64_t count = 1869;       ///< N_I target number of nodes
  double radius = 0.92;            ///< r_I, R
  double min_separation = 0.10;    ///< d_IS, R
  double spring_distance = 0.23;   ///< d_I, R
  double spring_constant = 0.076;  ///< k_I, G M^2 / R^3
  std::int64_t max_trials = 2000000;  ///< random sequential addition gives up after this many
};

/// Icosahedral crust (sections 2.4-2.6).
struct ShellConfig {
  bool enabled = true;
  std::int64_t level = 4;                  ///< L: 10*4^L+2 nodes
  double mass = 0.07;                      ///< M_S, M
  double spring_constant = 0.06;           ///< k_S, G M^2 / R^3
  double bending_constant = 0.0075;        ///< k_e, G M^2 / R^2
  double failure_strain = 0.003;           ///< eps_S
  double failed_stiffness_factor = 0.005;  ///< F_Sk
};

/// Cross springs between shell and interior (section 2.7, eq. 26).
struct CrossConfig {
  double distance = 0.18;         ///< d_C, R
  double spring_constant = 0.005; ///< k_C, G M^2 / R^3
  bool nonlinear = false;         ///< apply f(eps) of eq. 26
  double strain_scale = 0.03;     ///< eps_C
  double min_force_factor = 0.1;  ///< F_Ck
  /// Every shell node gets at least this many cross springs (to its nearest interior nodes,
  /// spanning three directions when >= 3) although d_C gives fewer; 0 keeps the paper's d_C rule.
  /// Default 3: what the default crust support, "balanced", needs (docs/crust-support.md).
  std::int64_t min_per_shell_node = 3;
  /// How the shell is tied to the interior (model/choices.hpp): paper (the d_C rule with k_C,
  /// section 2.7) or welded (bodies/welded_coupling.hpp, docs/crust-support.md). A [material] body
  /// with welded fills its interior out to r_I = 1 - h_S (the crust's thickness), not 1 - 1.03 d_IS.
  CrossCoupling coupling = CrossCoupling::paper;
};

/// The smallest integrator.dt a configuration may give (t_grav): the one home of that bound, also
/// of the check that a built body's springs can be integrated at all (bodies/build_body.cpp).
inline constexpr double min_time_step = 1e-7;

struct IntegratorConfig {
  double dt = 0.002;                 ///< t_grav
  double softening_fraction = 0.01;  ///< Plummer softening / min initial spacing
};

/// Stretch and strengthen (section 2.3).
struct StretchConfig {
  bool enabled = true;
  std::int64_t max_iterations = 60;
  double tolerance = 1e-6;            ///< |mean radial surface acceleration|, G M / R^2
  double cross_compression = 0.002;   ///< extra compressive strain of cross springs
  /// How the interior carries its hydrostatic pressure (model/choices.hpp): strengthen (the
  /// stiffening depends on the resolution) or compress (the body keeps the material's moduli at
  /// any resolution). Default compress for a [material] body, strengthen otherwise. docs/material.md.
  HydrostaticSupport hydrostatic_support = HydrostaticSupport::strengthen;
};

/// Damped relaxation and stability probe (section 2.8).
struct RelaxConfig {
  double damping = 50.0;                  ///< gamma, 1/t_grav
  double duration = 3.0;                  ///< T, t_grav
  std::int64_t rest_length_interval = 10; ///< steps between shell rest-length updates
  double rest_length_rate = 0.5;          ///< fraction of (L - L0) moved per update
  std::int64_t hinge_reset_interval = 100;///< steps between hinge rest-angle resets
  double settle_duration = 1.0;           ///< final part of T without creep or resets, t_grav
  std::int64_t checkpoint_interval = 500; ///< steps between mid-stage checkpoints (0: none)
  bool stability_probe = true;
  double probe_damping = 0.01;            ///< gamma of the probe, 1/t_grav
  double probe_duration = 3.0;            ///< t_grav
  /// How the relaxed crust is supported (model/choices.hpp; docs/crust-support.md).
  /// Default balanced (no pre-stress: failure strains below ~2e-3 can be simulated); the
  /// paper's workflows name "paper".
  CrustSupport crust_support = CrustSupport::balanced;
};

/// Defaults shared by all encounters (sections 2.6, 2.9).
struct EncounterDefaults {
  double damping = 0.01;                   ///< gamma, 1/t_grav
  std::int64_t fail_interval = 3;          ///< t_fail in steps
  double start_distance = 3.0;             ///< perturber distance at start, R
  double end_distance = 3.0;               ///< perturber distance at end, R
  std::int64_t checkpoint_interval = 250;  ///< steps between mid-stage checkpoints (0: none)
  std::int64_t sample_interval = 10;       ///< steps between timeseries samples
  /// Snapshot checkpoints every this long (t_grav), counted from pericenter, besides the four of
  /// Figure 6; 0: those four only (a body without a crust: every 0.5 t_grav). encounter_stage.cpp.
  double snapshot_interval = 0.0;
  /// Which springs fail when (model/choices.hpp; docs/failure-rule.md): paper, the single most
  /// strained spring every fail_interval steps (section 2.6); local, every over-strained spring,
  /// most strained first, at most one per crack neighbourhood per relaxation interval; shadow,
  /// local with no new crack within shadow_distance of a crack; griffith, shadow with new cracks
  /// opening as flaws of flaw_length and growing at a fixed fracture toughness; critical_distance,
  /// shadow where a crack opens or grows by a segment of flaw_length once the mean strain of the
  /// springs across it reaches eps_S (the line method of the theory of critical distances); nonlocal,
  /// critical_distance where the candidate's strain is the crust's strain tensor fitted over half a
  /// segment around it, without the crack neighbourhood (a nonlocal strain over a material length);
  /// nonlocal_principal, nonlocal judged by that tensor's largest principal strain, the segment
  /// opening across its direction. Default local (its statistics converge with dt); the paper's workflows name "paper".
  FailureRuleKind failure_rule = FailureRuleKind::local;
  double exclusion_radius = 2.0;           ///< local: neighbourhood radius, in mean shell spacings L_S
  /// The crack neighbourhood radius r_ex as a length, R; unset: exclusion_radius L_S. A length keeps
  /// r_ex the same at every shell level (a resolution study of the nonlocal rule); given, it replaces
  /// exclusion_radius, which must then keep its default (docs/failure-rule.md).
  std::optional<double> exclusion_distance;
  double relaxation_crossings = 2.0;       ///< local: relaxation interval, in shell crossing times L_S/V_SP
  double shadow_distance = 0.2;            ///< shadow: stress-shadow radius of a crack, R (physical, not in L_S)
  double flaw_length = 0.3;                ///< griffith: a_0, a new crack's flaw length; critical_distance, nonlocal*: the segment, R
};

/// How self-gravity is computed.
struct GravityConfig {
  /// fast (AVX-512 estimate and Newton steps where available) or portable (plain IEEE
  /// arithmetic: the same bits on every x86-64 CPU); model/choices.hpp, docs/determinism.md.
  GravityKernel kernel = GravityKernel::fast;
  /// direct (every pair: the reference) or tree (octree with softened multipoles, for large N);
  /// model/choices.hpp, docs/architecture.md, "Self-gravity methods".
  GravityMethod method = GravityMethod::direct;
  double force_error = 1e-4;  ///< tree: target median relative force error per particle
};

/// What `run` writes after each encounter besides its checkpoint (stages/analysis_stage.hpp).
struct AnalysisConfig {
  /// Draw the figures (PNG + SVG, ~16 files, a few seconds of the Python package per encounter);
  /// false writes summary.json, cracks.json and figure_data.json only (a large sweep's encounters
  /// are compared in `report`'s figures). Changes no checkpoint.
  bool figures = true;
};

// ---- issue 12: a body described by its material, its resolution and a rocky core ----------------
// docs/material.md. Every key is optional: a workflow without [material] keeps the printed spring
// constants of [interior], [shell], [cross] bit for bit.

/// The material of the body, apart from resolution (paper eqs. 15-25). Given (youngs_modulus
/// set), the keys listed by derived_by_material() are derived from it and must not be given.
struct MaterialConfig {
  std::optional<double> youngs_modulus;         ///< E_I, interior Young's modulus (eq. 15), e_g
  std::optional<double> crust_thickness;        ///< h_S (eq. 21: E_2D = E_S h_S, E_S = E_I), R
  std::optional<double> crust_modulus_2d;       ///< E_2D (instead of h_S, or with it: a crust of E_S = E_2D / h_S), e_g R
  std::optional<double> flexural_rigidity;      ///< D_F (eq. 23), e_g R^3; default E_S h_S^3/(12 (1 - 1/16)), E_S = E_I or E_2D / h_S
  std::optional<double> crust_mass;             ///< M_S, M
  std::optional<double> crust_density;          ///< rho_S (instead of M_S: M_S = 4 pi R^2 h_S rho_S), M/R^3
  std::optional<double> coupling_speed_ratio;   ///< V_Co / V_IP (eqs. 25, 16); default 1
  std::optional<double> failure_strain;         ///< eps_S (becomes shell.failure_strain)
};

/// How finely a [material] body is resolved (only with [material]).
struct ResolutionConfig {
  std::optional<std::int64_t> shell_level;      ///< L; default 4
  std::optional<double> interior_spacing;       ///< d_IS, R; default 0.10 * 2^((4 - L)/2)
  std::optional<std::int64_t> interior_count;   ///< N_I; default: paper-T's packing of d_IS spheres
  std::optional<double> cross_per_shell_node;   ///< N_C / N_S (sets d_C); default 2.33 (paper-T)
};

/// A denser, stiffer core inside the icy mantle (any body). Interior nodes inside `radius` get
/// density_ratio times the mass, interior springs whose midpoint lies inside it modulus_ratio
/// times the stiffness; total mass stays 1.
struct CoreConfig {
  std::optional<double> radius;          ///< r_c, R (unset: no core)
  std::optional<double> density_ratio;   ///< rho_core / rho_mantle; default 1
  std::optional<double> modulus_ratio;   ///< E_core / E_mantle; default 1
  bool present() const { return radius.has_value() && *radius > 0; }
};
// ---- end of issue 12 ---------------------------------------------------------------------------

/// A liquid layer under the crust (docs/ocean.md; issue 26): the interior nodes deeper than the
/// shell by less than `thickness` become liquid particles (forces/liquid_pressure.hpp), which
/// have no springs; the crust floats on them.
struct OceanConfig {
  std::optional<double> thickness;      ///< from the shell down to the ocean floor, R (unset: no ocean)
  std::optional<double> bulk_modulus;   ///< K of the liquid, e_g; default the interior's K = E_I / (3 (1 - 2 nu)) at nu = 1/4
  /// The fraction of their stiffness the liquid's springs keep: a small static shear modulus that
  /// holds the liquid's zero-energy modes (docs/ocean.md measures what it costs in h2)
  /// (default default_shear_fraction)
  std::optional<double> shear_fraction;
  static constexpr double default_shear_fraction = 1e-2;
  /// tau_M, t_grav: the liquid's springs relax their stress on this time from the end of the
  /// relaxation on, a Maxwell liquid (docs/ocean.md, "A Maxwell liquid"); unset: they stay elastic
  std::optional<double> maxwell_time;
  bool present() const { return thickness.has_value() && *thickness > 0; }
};

/// A [sweep] table (docs/cluster.md): the axes of a product of encounters, each as the list of
/// its values (a range {from, to, count} of the file is kept as the values it gives). Stored
/// as itself in every checkpoint's configuration (to_toml), so that a checkpoint's size does not
/// grow with the number of encounters; Config::encounters holds its expansion.
struct SweepConfig {
  std::vector<double> perturber_mass;    ///< M2, M (required)
  std::vector<double> pericenter;        ///< q, R (required)
  std::vector<double> pericenter_speed;  ///< V_q; empty: the parabolic speed sqrt(2 (1 + M2) / q)
  std::vector<double> failure_strain;    ///< eps_S; empty: shell.failure_strain
  bool operator==(const SweepConfig&) const = default;
};

/// The most encounters one workflow may have: its [[encounters]] tables and the expansion of its
/// [sweep] together (checked before a sweep is expanded).
inline constexpr std::size_t max_encounters = 10'000;

/// How many encounters `sweep` expands into (the product of its axes), without expanding it.
std::size_t sweep_size(const SweepConfig& sweep);
/// The one expansion of a [sweep]: the product of its axes, M2 outermost, then q, V_q, eps_S,
/// each named M<M2>_q<q>_V<V_q, or "par">[_eps<eps_S>] (numbers in their shortest form, no '+').
std::vector<Encounter> expand_sweep(const SweepConfig& sweep);

/// An [ensemble] table (docs/ensembles.md): every encounter of the workflow (its [[encounters]]
/// tables and its [sweep]) run as `members` encounters whose trajectories differ by a stated
/// perturbation, so that each statistic comes with its spread. Member k of n (k = 0 .. n-1) is
/// named <encounter>_m<k> and has pericenter q (1 + delta u_k), u_k = (2k + 1)/n - 1 in (-1, 1):
/// stratified offsets, symmetric about q, so the members' mean q is q to first order.
struct EnsembleConfig {
  std::int64_t members = 0;                 ///< n, 3 .. max_ensemble_members (a trend and its scatter need 3)
  double pericenter_perturbation = 5e-3;    ///< delta, relative, (0, 0.05]; read when vary is pericenter or both
  EnsembleVariation vary = EnsembleVariation::pericenter;  ///< what differs between the members
  bool operator==(const EnsembleConfig&) const = default;
};
inline constexpr std::int64_t max_ensemble_members = 1000;

/// The one expansion of [ensemble]: each of `encounters` in order becomes its n members in
/// member order (A_m0, A_m1, ..., B_m0, ...). When the ensemble varies the body, member k branches
/// from the body of seed s + k, s = the encounter's body_seed or else `workflow_seed` (member 0:
/// the encounter's own body), so that member k of every encounter shares one body.
std::vector<Encounter> expand_ensemble(const std::vector<Encounter>& encounters, const EnsembleConfig& ensemble,
                                       std::uint64_t workflow_seed);
/// The relative pericenter offset delta u_k of member k of `ensemble` (k in [0, members)); 0 when
/// the ensemble varies only the body.
double ensemble_pericenter_offset(const EnsembleConfig& ensemble, std::int64_t member);


/// The [spin] table (docs/spin.md): the body spins about its z axis (the body frame's north).
/// Unset (or 0): the body does not spin, and every result is what it was before the key.
struct SpinConfig {
  /// Omega, rad/t_grav: the fraction of the breakup rate sqrt(GM/R^3) = 1; [0, max_spin).
  std::optional<double> angular_velocity;
  /// Omega, 0 when unset.
  double rate() const { return angular_velocity.value_or(0.0); }
};
/// The fastest spin a workflow may ask for (exclusive), in units of the breakup rate: beyond it
/// the equator's centrifugal acceleration is most of gravity and the body sheds its crust.
inline constexpr double max_spin = 0.9;

struct Config {
  WorkflowConfig workflow;
  InteriorConfig interior;
  ShellConfig shell;
  CrossConfig cross;
  IntegratorConfig integrator;
  StretchConfig stretch;
  RelaxConfig relax;
  EncounterDefaults encounter;
  GravityConfig gravity;
  AnalysisConfig analysis;
  /// Every encounter: the [[encounters]] tables in file order, then the expansion of `sweep`.
  std::vector<Encounter> encounters;
  /// The [sweep] table, when the workflow has one. to_toml writes it instead of its expansion
  /// while the last sweep_size(*sweep) encounters are exactly expand_sweep(*sweep) (else, after
  /// a --set of one of them, every encounter as a table).
  std::optional<SweepConfig> sweep;
  /// The [ensemble] table, when the workflow has one; `ensemble_bases` then holds the encounters
  /// before the expansion ([[encounters]] tables, then [sweep]) and `encounters` their members.
  /// to_toml writes the bases and [ensemble] while `encounters` is exactly their expansion.
  std::optional<EnsembleConfig> ensemble;
  std::vector<Encounter> ensemble_bases;
  MaterialConfig material;
  ResolutionConfig resolution;
  CoreConfig core;
  /// The [moon] table (docs/moon.md): the moon in SI. Given, it fills [material] and [core]
  /// (resolve_moon); the resolved text keeps both.
  MoonConfig moon;
  /// The [crust] table (docs/crust.md): a crust whose thickness and strength vary over the surface.
  CrustConfig crust;
  /// The [ocean] table (docs/ocean.md): a liquid layer under the crust.
  OceanConfig ocean;
  /// The [spin] table (docs/spin.md): the body's spin about its z axis; given by moon.spin_period
  /// in a [moon] workflow (resolve_moon).
  SpinConfig spin;
  /// No integrator.dt given in a [material] workflow: dt is chosen from the stability bound of
  /// the stretched body (stages/time_step.hpp); to_toml leaves dt out while this is set.
  bool choose_dt = false;

  /// True when the body is described by [material] (material.youngs_modulus given).
  bool from_material() const { return material.youngs_modulus.has_value(); }

  /// The encounter with this name; InputError listing the known names otherwise.
  const Encounter& find_encounter(const std::string& name) const;
  /// The encounter with this name, or nullptr.
  const Encounter* encounter_or_null(std::string_view name) const;
  /// The encounters `run --only NAME` means: the encounter of that name, or, for the name of an
  /// [ensemble]'s base encounter, all its members (NAME_m0, NAME_m1, ...) in order. InputError as
  /// find_encounter when there is neither.
  std::vector<Encounter> encounters_named(const std::string& name) const;
};

/// Whether the state's path takes its transcendental functions from base/portable_math.hpp: in
/// the portable mode (`[gravity] kernel = "portable"`), and for fast in a build without AVX-512
/// (uses_portable_math; docs/determinism.md).
inline bool portable_mode(const Config& config) { return uses_portable_math(config.gravity.kernel); }

/// The seed of the body `encounter` branches from: its body_seed, or workflow.seed; for an
/// encounter with `after`, that of the first encounter of its history.
std::uint64_t body_seed_of(const Config& config, const Encounter& encounter);
/// The configuration of the body chain `encounter` branches from: `config` with workflow.seed =
/// body_seed_of (the same configuration when the encounter is on the workflow's body).
Config body_config_of(const Config& config, const Encounter& encounter);

/// Parses TOML text. `origin` (a file name) prefixes every error message. A relative
/// crust.map_file is taken relative to `relative_to` (load_config: the workflow file's folder;
/// empty: the current folder) and stored absolute.
Config parse_config(const std::string& toml_text, const std::string& origin,
                    const std::filesystem::path& relative_to = {});
/// Reads and parses a TOML file; a missing file is an InputError.
Config load_config(const std::filesystem::path& file);
/// Applies one "section.key=value" or "encounters.NAME.key=value" override (value in TOML
/// syntax, e.g. 0.002 or true); InputError for an unknown key or a value of the wrong type.
/// Ranges are checked by validate() once all overrides are applied (they may depend on each other).
void apply_override(Config& config, const std::string& assignment);
/// The resolved configuration, every key with its default, as TOML with unit comments.
/// parse_config(to_toml(c)) == c, and equal configs give equal text.
std::string to_toml(const Config& config);
/// One configuration key as visit_keys (config.cpp) describes it, with its value in one
/// configuration: what the key reference prints and the stage fingerprints are made of.
struct KeyInfo {
  std::string section;  ///< "interior", ...; "encounters" for a key of an [[encounters]] table
  std::string name;
  std::string type;     ///< "number", "integer", "boolean", "string" or "choice" (model/choices.hpp)
  std::string unit;     ///< "-" for a pure number, "" for none (a name)
  std::string doc;      ///< meaning, one line
  std::string range;    ///< accepted values: of a number "[min, max]" or "(min, max]", of a choice
                        ///< "one of: a, b"; "" for others
  bool optional = false;  ///< may be left unset (then nothing is derived from it)
  std::optional<std::string> value;  ///< as to_toml writes it; none for an unset optional key
  /// The stages whose results the key changes: `readers` always, `conditional_readers` too when
  /// `condition` holds (e.g. gravity.force_error: stretch, relax and encounter when
  /// gravity.method = "tree"). Both empty: the key changes no result (a name, a checkpoint interval).
  StageSet readers;
  StageSet conditional_readers;
  std::string condition;  ///< "" or the condition, as text ("gravity.method = \"tree\"")
  /// The stages that read the key in this configuration: readers, and conditional_readers when
  /// the condition holds. A stage's fingerprint holds exactly the keys it reads, when set.
  StageSet read_by;
};

/// Every key of the configuration in to_toml order ([workflow] ... [core]), with its value in `config`.
std::vector<KeyInfo> describe_keys(const Config& config);
/// The keys of one [[encounters]] table, with the values of `encounter` (conditions evaluated on `config`).
std::vector<KeyInfo> describe_keys(const Encounter& encounter, const Config& config);
/// The value of the integer key `section.name` (e.g. relax.checkpoint_interval);
/// InternalError (TIDALCRUST_ASSERT) when there is no such integer key.
std::int64_t integer_key_value(const Config& config, std::string_view section, std::string_view name);
/// One [[encounters]] table of to_toml.
std::string encounter_toml(const Encounter& encounter);
/// Scales the time step by `factor` (--dt-factor) and every schedule counted in steps (the keys
/// whose unit is "steps") by 1/factor (rounded, at least 1), so schedules keep their length in
/// time: at half dt the failure interval t_fail is 6 steps instead of 3, and the run checks dt
/// alone.
void scale_time_step(Config& config, double factor);
/// The longest name that becomes a file or folder name (workflow.name, an encounter's name):
/// with the suffixes added to it (".tmp-<pid>.<host>", ".snap-<step>.h5") it stays within the
/// 255 bytes every common file system accepts.
inline constexpr std::size_t max_path_name_bytes = 200;
/// Empty if `name` can be used as one file or folder name, else what is wrong with it
/// ("'..' names a folder itself, not a new one"), the name shown with control characters
/// escaped: only letters and digits (ASCII), '-', '_' and '.', not "." or "..", not beginning with
/// '-', 1 to max_path_name_bytes bytes. The one check of every name that becomes a path; validate
/// applies it to workflow.name and to every encounter (listed or from [sweep]).
std::string path_name_problem(std::string_view name);
/// Checks every value's range and the relations between values; InputError naming the key.
void validate(const Config& config, const std::string& origin);
/// The checks validate makes of one encounter: its name and the range of each of its values
/// (without copying the configuration: a sweep checks each of its 10,000 encounters).
void validate_encounter(const Encounter& encounter, const std::string& origin);

/// Keys that [material] and [resolution] derive ("interior.spring_constant", ...): given together
/// with [material] they are an error; to_toml leaves them out of a material body's text.
bool derived_by_material(const Config& config, std::string_view section, std::string_view name);
/// Fills the keys a [material] body derives before building (geometry from [resolution], shell
/// mass, k_S = (sqrt 3 / 2) E_2D, eps_S); no-op without [material]. The spring constants that
/// need the built network (k_I, k_e, k_C, d_C) are derived by the build stage (docs/material.md).
/// InputError naming the key for a missing or inconsistent material value.
void resolve_material(Config& config, const std::string& origin);
/// Fills the [material] and [core] keys a [moon] table gives (moon_model_values), as a user
/// could have written them; no-op without [moon]. A key given with another value is an
/// InputError naming both (the resolved text carries the same value beside [moon], accepted).
void resolve_moon(Config& config, const std::string& origin);

/// The moon of a [moon] workflow, whose units the output gives beside the model's (docs/moon.md,
/// "Output in SI"); none without [moon]. InputError naming `origin` as moon_model_values.
std::optional<MoonScale> output_moon(const Config& config, const std::string& origin);
/// The same of a checkpoint's stored (resolved) configuration text; none for an empty text.
std::optional<MoonScale> stored_moon(const std::string& config_toml, const std::string& origin);
/// Makes crust.map_file absolute (relative to `relative_to`, empty: the current folder), reads it
/// (read_crust_map: InputError naming the file and line) and records its digest in
/// crust.map_digest, unless a digest is recorded already (a stored configuration); no-op without
/// crust.map_file.
void resolve_crust(Config& config, const std::filesystem::path& relative_to);
/// Poisson ratio of the random isotropic network (Kot 2015), also taken for the crust's D_F.
inline constexpr double material_poisson_ratio = 0.25;
/// The crust's E_2D (e_g R) and D_F (e_g R^3) of a [material] body.
double material_crust_modulus_2d(const MaterialConfig& material);
double material_flexural_rigidity(const MaterialConfig& material);

}  // namespace tidalcrust
