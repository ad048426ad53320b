// `tidalcrust validate WORKFLOW.toml`: runs (or reuses) the workflow's body chain, then measures
// the relaxed body against continuum elasticity (analysis/elastic_validation.hpp): the breathing
// period, the Love number h2, the crust's flexural rigidity and the P-wave travel time. Writes
// <out>/validate/validation.json and figures, and prints a table. docs/validation.md.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "analysis/elastic_validation.hpp"
#include "build_info.hpp"
#include "analysis/tidal_response.hpp"
#include "analysis/layer_moduli.hpp"
#include "base/errors.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "analysis/plot_data.hpp"
#include "figures/figure_script.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint_file.hpp"
#include "io/json.hpp"
#include "model/center_of_mass.hpp"
#include "physics/continuum_elasticity.hpp"
#include "io/stop_signal.hpp"
#include "stages/workflow.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

/// The static tide of a floating shell (validate --measure tide on a body with an ocean): drag
/// (1/t_grav) and duration (t_grav) of the slow approach, for the shell's slowest mode (docs/ocean.md).
constexpr double floating_shell_drag = 4.0;
constexpr double floating_shell_tide_duration = 15.0;
/// On a Maxwell liquid the shell sinks into the tide as the liquid's shear relaxes: h2 reaches its
/// plateau after about 60 t_grav on ocean-L3 at tau_M = 0.05 (docs/ocean.md, "A Maxwell liquid").
constexpr double maxwell_ocean_tide_duration = 60.0;

/// What each check compares, with its published source and the tolerance of its target
/// (docs/validation.md).
struct Check {
  const char* name;
  const char* doing;  ///< the progress line
  const char* quantity;
  const char* unit;
  const char* source;
  double tolerance;
  bool selectable = true;  ///< a measurement of --measure; false: another theory for one of them
};
const Check checks[] = {
    {"breathing", "breathing mode", "period of the fundamental radial mode", "t_grav",
     "Lamb (1882); Love (1927) sec. 195: homogeneous sphere, E_I (eq. 15), nu = 1/4, rho = 3/(4 pi)", 0.05},
    {"love", "Love number h2 in a static tidal field", "degree-2 Love number h2", "",
     "Takeuchi & Saito (1972) eq. 82, static: homogeneous compressible self-gravitating sphere", 0.10},
    {"flexure", "flexural rigidity of the crust lattice", "flexural rigidity D", "G M^2/R",
     "eq. 23: D_F = k_e L_S / 2; thin plate w0 = q0/(D k^4) (Timoshenko & Woinowsky-Krieger 1959)", 0.20},
    {"p-wave", "P-wave travel time", "P-wave travel time pole to pole", "t_grav", "eq. 16: straight path / V_IP",
     0.10},
    // The same measurements against theory with the network's measured moduli (docs/validation.md,
    // "The network's own moduli"): E_I and nu = 1/4 replaced by the static strain test's.
    {"breathing-network", "", "period of the fundamental radial mode", "t_grav",
     "Lamb (1882) with the measured network moduli (static strain test, non-affine)", 0.05, false},
    {"love-network", "", "degree-2 Love number h2", "",
     "Takeuchi & Saito (1972), homogeneous sphere with the measured network moduli", 0.10, false},
    {"love-layered", "", "degree-2 Love number h2", "",
     "Takeuchi & Saito (1972), radial layers (eq. 15 per layer, cross-spring crust layer) times the measured "
     "non-affine factors",
     0.10, false},
    {"p-wave-network", "", "P-wave travel time pole to pole", "t_grav",
     "straight path / V_P of the measured network moduli", 0.10, false},
    {"p-wave-layered", "", "P-wave travel time pole to pole", "t_grav",
     "layered eq. 15/16 times the measured non-affine factors", 0.10, false},
    // The static degree-2 tide and the crust's strain (analysis/tidal_response.hpp), against the
    // homogeneous self-gravitating sphere of the measured network moduli (eq. 15 without them).
    {"tide", "static degree-2 tide: h2, l2 and every crust spring's strain", "h2 fitted from the shell displacement",
     "", "Takeuchi & Saito (1972) eq. 82, static, homogeneous, measured network moduli", 0.05},
    // A body with an ocean (docs/ocean.md): h2 and l2 also against the same layers with a fluid ocean.
    {"tide-fluid-ocean", "", "h2 fitted from the shell displacement", "",
     "Takeuchi & Saito (1972), static, the body's layers with a fluid ocean (mu -> 0)", 0.10, false},
    {"tide-l2-fluid-ocean", "", "l2 fitted from the shell's tangential displacement", "",
     "Takeuchi & Saito (1972), static, the body's layers with a fluid ocean (mu -> 0)", 0.10, false},
    {"tide-l2", "", "l2 fitted from the shell's tangential displacement", "",
     "Takeuchi & Saito (1972) eq. 82, static, homogeneous, measured network moduli", 0.10, false},
    {"tide-l2-over-h2", "", "l2 / h2", "", "the same sphere", 0.10, false},
    {"tide-correlation", "", "correlation of the crust springs' strain with the continuum's", "",
     "chord strain of the continuum surface displacement (h2, l2 of the same sphere)", 0.05, false},
    {"tide-median-ratio", "", "median of measured / continuum strain, spring by spring (|continuum| >= rms/2)", "",
     "the same chord strains; the scatter (half the 16-84% range) is in the JSON", 0.10, false},
    {"tide-peak-tension", "", "meridional tension at 75-90 deg from the tidal axis", "per unit eps",
     "eps_psipsi = h2 P2 - 3 l2 cos 2 gamma of the same sphere, fitted over the same springs", 0.15, false},
    {"tide-subsatellite", "", "mean crust strain within 15 deg of the tidal axis (sign)", "per unit eps",
     "the same sphere (within tolerance: the same sign)", 1.0, false},
    {"ringdown", "degree-2 ring-down after the tide is released", "period of 0S2", "t_grav",
     "Takeuchi & Saito (1972) eq. 82 with omega: homogeneous self-gravitating sphere, measured network moduli",
     0.03},
    {"ringdown-lamb", "", "period of 0S2", "t_grav",
     "Lamb (1882) without gravity: omega a / V_S = 2.640 at nu = 1/4, measured network moduli", 0.03, false}};

/// The theory of the tide's and the ring-down's rows for a body with a core (no homogeneous sphere).
constexpr const char* layered_tide_source =
    "Takeuchi & Saito (1972), static, radially layered sphere of the body's own layers (eq. 15 per layer times "
    "the measured non-affine factor): the body has a core";
/// ... and for a body with an ocean: its liquid with the small shear modulus of its springs.
constexpr const char* ocean_tide_source =
    "Takeuchi & Saito (1972), static, radial layers: the solid interior (eq. 15 per layer times the measured "
    "non-affine factor), the liquid with its springs' shear modulus (eq. 15), the crust (E_2D / h, nu = 1/3)";
/// The fluid limit of the same layers, the ocean's shear modulus 1e-6 K.
constexpr const char* ocean_fluid_source =
    "Takeuchi & Saito (1972), static, the same layers with a fluid ocean (mu = 1e-6 K)";
constexpr const char* layered_ringdown_source =
    "Takeuchi & Saito (1972) with omega, radially layered self-gravitating sphere of the body's own layers: the "
    "body has a core";

/// The measurements --measure knows, for its usage and errors.
constexpr const char* measurement_names = "breathing, love, flexure, p-wave, tide, ringdown";

const Check& check_named(const std::string& name) {
  for (const auto& c : checks)
    if (name == c.name && c.selectable) return c;
  throw InputError(fmt::format("--measure: unknown measurement '{}' (known: {})", name, measurement_names));
}

/// The measurements named in a comma-separated list; InputError naming an unknown one.
std::set<std::string> selected_measurements(const std::string& list) {
  std::set<std::string> chosen;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    chosen.insert(check_named(name).name);
  }
  if (chosen.empty()) throw InputError("--measure: no measurement named");
  return chosen;
}

/// One row of the printed table and of the JSON "comparisons" object.
struct Row {
  const Check* check;
  double measured = 0, theory = 0;
  const char* source = nullptr;  ///< the theory used, where it is not the check's own (a body with a core)
  double ratio() const { return measured / theory; }
  bool within() const { return std::abs(ratio() - 1) <= check->tolerance; }
};

Json row_json(const Row& r) {
  return Json{{"quantity", r.check->quantity}, {"unit", r.check->unit},
              {"measured", r.measured},        {"theory", r.theory},
              {"ratio", r.ratio()},            {"tolerance", r.check->tolerance},
              {"within_tolerance", r.within()}, {"source", r.source ? r.source : r.check->source}};
}

}  // namespace

int command_validate(int argc, char** argv) {
  cxxopts::Options options = command_options(
      "validate", "Runs (or reuses) the body chain; measures the breathing period, Love number h2, flexural "
                  "rigidity and P-wave travel time.");
  options.positional_help("WORKFLOW.toml");
  options.add_options()("workflow", "workflow TOML file", cxxopts::value<std::string>())(
      "out", "output root (default checkpoints/<workflow name>); results in <out>/validate/",
      cxxopts::value<std::string>())("threads", "number of threads (results do not depend on it)",
                                     cxxopts::value<int>()->default_value("0"))(
      "set", "override one value: section.key=value (repeatable)", cxxopts::value<std::vector<std::string>>())(
      "quiet", "no progress lines")("h,help", "show this help")(
      "measure", "comma-separated subset of breathing,love,flexure,p-wave,tide,ringdown",
      cxxopts::value<std::string>()->default_value("breathing,love,flexure,p-wave"))(
      "tide-duration", "t_grav of the tide's slow approach (default: 60 on a Maxwell liquid, 15 on another floating "
                       "shell, else 30 over the breathing mode's angular frequency, at least 3)",
      cxxopts::value<double>());
  options.parse_positional({"workflow"});
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  // Everything is checked before anything is written: the measurements, then the workflow.
  const std::set<std::string> chosen = selected_measurements(parsed["measure"].as<std::string>());
  const double tide_duration = parsed.count("tide-duration") ? parsed["tide-duration"].as<double>() : 0.0;
  if (parsed.count("tide-duration") && !(tide_duration > 0 && tide_duration <= 1e4))
    throw InputError(fmt::format("--tide-duration = {} t_grav: expected a number in (0, 10000]", tide_duration));
  Config config = workflow_config(parsed);
  const int threads = checked_thread_count(parsed["threads"].as<int>());
  WorkflowOptions workflow_options;
  workflow_options.root = parsed.count("out") ? fs::path(parsed["out"].as<std::string>())
                                              : fs::path("checkpoints") / config.workflow.name;
  workflow_options.quiet = parsed.count("quiet") > 0;  // no encounters: the body chain alone
  workflow_options.config_file = parsed["workflow"].as<std::string>();
  apply_thread_count(threads);
  // SIGINT/SIGTERM end a measurement too (exit 130), also when the body chain is up to date.
  install_stop_handlers();
  if (run_workflow(config, workflow_options).interrupted) return exit_interrupted;

  const fs::path relaxed_file = workflow_options.root / "body" / "relax.h5";
  const Checkpoint relaxed = read_checkpoint(relaxed_file);
  const BodyMaterial material = body_material(relaxed, config);
  if (!workflow_options.quiet) fmt::print("validate: the interior network's static moduli\n");
  std::optional<InteriorModuli> measured_moduli;
  std::string no_moduli;
  try {
    measured_moduli = measure_interior_moduli(relaxed, material);
  } catch (const InputError& e) {
    no_moduli = e.what();  // a network too small for the strain test: the eq. 15 checks still run
  }
  const fs::path out = workflow_options.root / "validate";
  std::error_code error;
  fs::create_directories(out, error);
  if (error) throw InputError(fmt::format("{}: cannot create the folder: {}", out.string(), error.message()));
  std::vector<Row> rows;
  // Whether check `name` was asked for; says so when it starts.
  const auto wanted = [&](const char* name) {
    if (!chosen.count(name)) return false;
    if (!workflow_options.quiet) fmt::print("validate: {}\n", check_named(name).doing);
    return true;
  };
  const auto add = [&](const char* name, double measured, double theory, const char* source = nullptr) {
    for (const auto& c : checks)
      if (name == std::string(c.name)) rows.push_back({&c, measured, theory, source});
  };

  Json json;
  json["workflow"] = config.workflow.name;
  json["relaxed_body"] = relaxed_file.string();
  json["git_commit"] = build_info::git_commit;  // the code that measured (the body's is in its checkpoint)
  json["material"] = Json{{"youngs_modulus", material.youngs_modulus}, {"poisson_ratio", material.poisson_ratio},
                          {"density", material.density},               {"radius", material.radius},
                          {"p_wave_speed", material.p_wave_speed},     {"shell_spacing", material.shell_spacing},
                          {"shell_spring_constant", material.shell_spring_constant},
                          {"hinge_stiffness", material.hinge_stiffness}};
  const auto moduli_json = [](const NetworkModuli& n) {
    const auto iso = [](const IsotropicModuli& m) {
      return Json{{"bulk", m.bulk}, {"shear", m.shear}, {"youngs", m.youngs}, {"poisson", m.poisson}};
    };
    return Json{{"relaxed", iso(n.relaxed_moduli)}, {"affine", iso(n.affine_moduli)},
                {"eq15_youngs", n.eq15_youngs},   {"reference_pressure", n.reference_pressure},
                {"free_nodes", n.free_nodes},     {"held_nodes", n.held_nodes}};
  };
  if (!measured_moduli) json["network_moduli"] = Json{{"skipped", no_moduli}};
  const InteriorModuli& moduli = measured_moduli ? *measured_moduli : InteriorModuli{};
  const BodyMaterial& network_material = moduli.material;
  if (measured_moduli)
    json["network_moduli"] =
      Json{{"hold_radius", moduli.hold_radius},   {"measure_radius", moduli.measure_radius},
           {"bulk_factor", moduli.bulk_factor},   {"shear_factor", moduli.shear_factor},
           {"youngs_factor", moduli.youngs_factor}, {"youngs_modulus", network_material.youngs_modulus},
           {"poisson_ratio", network_material.poisson_ratio}, {"p_wave_speed", network_material.p_wave_speed},
           {"geometric", moduli_json(moduli.geometric)}, {"network", moduli_json(moduli.network)}};
  json["units"] = Json{{"time", "t_grav"}, {"length", "R"}, {"modulus", "e_g"}, {"rigidity", "G M^2/R"},
                       {"speed", "sqrt(GM/R)"}};
  Json details;
  Json plots = Json::object();  // the figures, drawn from validate/figure_data.json
  if (wanted("breathing")) {
    const BreathingResult b = measure_breathing(relaxed, config, material);
    add("breathing", b.period, b.lamb_period);
    if (measured_moduli) add("breathing-network", b.period, continuum_prediction(network_material, 1.0).breathing_period);
    details["breathing"] = Json{{"self_gravitating_period", b.self_gravitating_period},
                                {"self_gravitating_ratio", b.period / b.self_gravitating_period},
                                {"amplitude", b.amplitude}, {"samples", b.time.size()}};
    std::vector<TimeMark> marks;
    for (int n = 1; n * b.lamb_period <= b.time.back(); ++n)
      marks.push_back({n * b.lamb_period, n == 1 ? "Lamb period" : "", false});
    marks.push_back({b.self_gravitating_period, "", false});  // just after Lamb's first: no label
    for (int n = 1; n * b.period <= b.time.back(); ++n) marks.push_back({n * b.period, n == 1 ? "measured" : "", true});
    plots["breathing"] = signal_plot_json((out / "breathing").string(), b.time, b.signal, marks,
                      fmt::format("Breathing mode of {}\nmeasured period {:.4f}, Lamb {:.4f}, with self-gravity {:.4f} t_grav",
                                  config.workflow.name, b.period, b.lamb_period, b.self_gravitating_period),
                      "mean radius change [R]");
  }
  if (wanted("love")) {
    const LoveResult l = measure_love_h2(relaxed, config, material);
    add("love", l.h2, l.theory_h2);
    std::vector<ElasticLayer> layers =
        body_layers(relaxed, body_center_of_mass(relaxed.body, relaxed.state), 6, true);
    const double eq15_layered_h2 = layered_sphere_love_numbers(2, layers).h;
    if (measured_moduli) {
      add("love-network", l.h2, continuum_prediction(network_material, 1.0).h2);
      for (auto& layer : layers) {
        layer.youngs_modulus *= moduli.youngs_factor;
        layer.poisson_ratio = network_material.poisson_ratio;
      }
      add("love-layered", l.h2, layered_sphere_love_numbers(2, layers).h);
    }
    details["love"] = Json{{"h2_at_two_thirds", l.h2_early}, {"incompressible_h2", l.incompressible_h2},
                           {"tidal_strength", l.tidal_strength}, {"shell_radius", l.shell_radius},
                           {"drag", l.drag}, {"duration", l.duration},
                           {"eq15_layered_h2", eq15_layered_h2}, {"surface_radius", layers.back().outer_radius}};
  }
  if (wanted("flexure")) {
    if (material.hinge_stiffness > 0) {
      const FlexureResult f =
          measure_plate_flexure(material.hinge_stiffness, material.shell_spacing, material.shell_spring_constant);
      add("flexure", f.rigidity, f.paper_rigidity);
      details["flexure"] = Json{{"lattice_rigidity", f.lattice_rigidity}, {"lattice_ratio", f.lattice_ratio},
                                {"rigidity_at_two_thirds", f.early_rigidity}, {"deflection", f.deflection},
                                {"theory_deflection", f.theory_deflection}, {"nodes", f.nodes}};
    } else {
      details["flexure"] = Json{{"skipped", "the body has no crust hinges"}};
    }
  }
  if (wanted("p-wave")) {
    const PWaveResult p = measure_p_wave(relaxed, config, material);
    add("p-wave", p.arrival_time, p.theory_time);
    if (measured_moduli) {
      add("p-wave-network", p.arrival_time, continuum_prediction(network_material, p.path_length).p_wave_time);
      // Every layer's speed scales alike: V_P(E f_E, nu_measured) / V_P(E, 1/4).
      add("p-wave-layered", p.arrival_time,
          p.layered_time * material.p_wave_speed / network_material.p_wave_speed);
    }
    details["p-wave"] = Json{{"path_length", p.path_length}, {"layered_time", p.layered_time},
                             {"layered_ratio", p.layered_ratio}, {"threshold", p.threshold}};
    std::vector<TimeMark> marks = {{p.theory_time, "path / V_IP", false},
                                   {p.layered_time, "layered", false},
                                   {p.arrival_time, "arrival", true}};
    plots["p_wave"] = signal_plot_json((out / "p_wave").string(), p.time, p.signal, marks,
                      fmt::format("P-wave pulse of {}: mean |dv| at the far pole\narrival {:.4f}, path/V_IP {:.4f} t_grav",
                                  config.workflow.name, p.arrival_time, p.theory_time),
                      "|dv| [sqrt(GM/R)]");
  }
  if (chosen.count("tide") || chosen.count("ringdown")) {
    if (!workflow_options.quiet) fmt::print("validate: {}\n", check_named("tide").doing);
    // The continuum: the homogeneous sphere of the measured network moduli (eq. 15's without). A
    // body with a core is no homogeneous sphere (the strain test's region mixes core and mantle),
    // so its tide and ring-down are compared with the radially layered sphere of its own layers
    // (eq. 15 per layer times the measured non-affine factor; Takeuchi & Saito 1972 with layers).
    const BodyMaterial& sphere = measured_moduli ? network_material : material;
    // A body with an ocean: its solid interior's layers, then the liquid (mu -> 0) and the crust.
    const bool ocean = relaxed.body.liquid.present();
    const Vec3 centre = body_center_of_mass(relaxed.body, relaxed.state);
    std::vector<ElasticLayer> layers = body_layers(relaxed, centre, 6, !ocean);
    for (auto& layer : layers) {
      layer.youngs_modulus *= measured_moduli ? moduli.youngs_factor : 1.0;
      layer.poisson_ratio = sphere.poisson_ratio;
    }
    // Its own liquid (the springs' small shear modulus) is the reference; the fluid limit beside it.
    // A Maxwell liquid's springs keep no static shear: its own liquid is the fluid one.
    const bool maxwell = ocean && relaxed.body.liquid.maxwell_time > 0;
    std::optional<LoveNumbers> fluid_limit;
    if (ocean) {
      if (!config.material.crust_thickness)
        throw InputError("validate --measure tide on a body with an ocean needs material.crust_thickness (the crust layer's h)");
      std::vector<ElasticLayer> fluid_layers = layers;
      for (const ElasticLayer& layer : ocean_layers(relaxed, centre, *config.material.crust_thickness, maxwell))
        layers.push_back(layer);
      for (const ElasticLayer& layer : ocean_layers(relaxed, centre, *config.material.crust_thickness, true))
        fluid_layers.push_back(layer);
      fluid_limit = layered_sphere_love_numbers(2, fluid_layers);
    }
    const LoveNumbers layered = layered_sphere_love_numbers(2, layers);
    const bool layered_reference = config.core.radius.has_value() || ocean;
    const LoveNumbers theory =
        layered_reference
            ? layered
            : homogeneous_sphere_love_numbers(2, sphere.youngs_modulus, sphere.poisson_ratio, sphere.density, sphere.radius);
    const char* tide_source = maxwell ? ocean_fluid_source : ocean ? ocean_tide_source : layered_reference ? layered_tide_source : nullptr;
    // A floating shell answers on its own slow time: the shell bobbing on the liquid (period ~2.8
    // t_grav on ocean-L3, docs/ocean.md), not the elastic sphere's: drag near critical for it and
    // several of its relaxation times.
    const double drag = ocean ? floating_shell_drag : 0.0;
    const double duration = tide_duration > 0 ? tide_duration
                            : maxwell         ? maxwell_ocean_tide_duration
                            : ocean           ? floating_shell_tide_duration
                                              : 0.0;
    const TideResult t = measure_tide(relaxed, config, sphere, theory, /*surface_displacement=*/1e-3, drag, duration,
                                      !workflow_options.quiet);
    if (chosen.count("tide")) {
      // The layer under the crust: affine moduli of the interior and cross springs crossing each
      // sphere (analysis/layer_moduli.hpp), against the interior's 6E/5 and 2E/5.
      const Body& body = relaxed.body;
      std::vector<bool> use(body.spring_count());
      for (std::size_t k = 0; k < body.spring_count(); ++k)
        use[k] = body.spring_kind[k] != static_cast<std::uint8_t>(SpringKind::shell) && !relaxed.state.springs.failed[k];
      std::vector<double> radii;
      for (double r = 0.30; r < 0.995; r += 0.01) radii.push_back(r);
      Json profile = Json::array();
      for (const auto& m : crossing_moduli(relaxed.state.position, body_center_of_mass(body, relaxed.state), body.springs,
                                           relaxed.state.springs.stiffness, relaxed.state.springs.rest_length, use,
                                           radii))
        profile.push_back(Json{{"radius", m.radius}, {"compression", m.compression}, {"shear", m.shear}});
      details["layer_moduli"] = Json{{"eq15_compression", 1.2 * material.youngs_modulus},
                                     {"eq15_shear", 0.4 * material.youngs_modulus}, {"profile", profile}};
      add("tide", t.fit.h2, theory.h, tide_source);
      if (fluid_limit) {
        add("tide-fluid-ocean", t.fit.h2, fluid_limit->h, ocean_fluid_source);
        add("tide-l2-fluid-ocean", t.fit.l2, fluid_limit->l, ocean_fluid_source);
      }
      add("tide-l2", t.fit.l2, theory.l, tide_source);
      add("tide-l2-over-h2", t.fit.l2 / t.fit.h2, theory.l / theory.h, tide_source);
      add("tide-correlation", t.correlation, 1.0, tide_source);
      add("tide-median-ratio", t.ratio.median, 1.0, tide_source);
      add("tide-peak-tension", t.peak_tension, t.theory_peak_tension, tide_source);
      add("tide-subsatellite", t.subsatellite_strain, t.theory_subsatellite_strain, tide_source);
      Json bins = Json::array();
      for (const auto& b : t.bins)
        bins.push_back(Json{{"gamma_low", b.gamma_low}, {"gamma_high", b.gamma_high}, {"springs", b.springs},
                            {"measured_meridional", b.measured_meridional}, {"measured_azimuthal", b.measured_azimuthal},
                            {"theory_meridional", b.theory_meridional}, {"theory_azimuthal", b.theory_azimuthal}});
      details["tide"] = Json{{"tidal_strength", t.tidal_strength}, {"drag", t.drag}, {"duration", t.duration},
                             {"h2_at_two_thirds", t.early_fit.h2}, {"l2_at_two_thirds", t.early_fit.l2},
                             {"shell_radius", t.fit.mean_radius}, {"uniform_radial_shift", t.fit.uniform},
                             {"rms_azimuthal_displacement", t.fit.rms_azimuthal},
                             {"reference", layered_reference ? "layered" : "homogeneous"},
                             {"theory_youngs_modulus", sphere.youngs_modulus},
                             {"theory_poisson_ratio", sphere.poisson_ratio},
                             {"layered_h2", layered.h}, {"layered_l2", layered.l},
                             {"springs", t.springs}, {"slope", t.slope}, {"rms_residual", t.rms_residual},
                             {"own_correlation", t.own_correlation}, {"own_slope", t.own_slope},
                             {"median_ratio", t.ratio.median}, {"ratio_scatter", t.ratio.scatter},
                             {"ratio_springs", t.ratio.springs},
                             {"strain_unit", "per unit eps (G M / R^3)"}, {"bands", bins}};
      plots["tide_strain"] = tidal_strain_plot_json((out / "tide_strain").string(), t.bins, theory.h, theory.l,
                              fmt::format("Crust strain under a static degree-2 tide, {}\nh2 {:.4f} (TS72 {:.4f}), "
                                          "l2 {:.4f} (TS72 {:.4f}), correlation {:.3f}",
                                          config.workflow.name, t.fit.h2, theory.h, t.fit.l2, theory.l, t.correlation));
    }
    if (wanted("ringdown")) {
      std::vector<ElasticLayer> sphere_layer = {
          {sphere.radius, sphere.youngs_modulus, sphere.poisson_ratio, sphere.density}};
      const double omega =
          spheroidal_fundamental_frequency(2, layered_reference ? layers : sphere_layer, true);
      const double omega_lamb = spheroidal_fundamental_frequency(2, sphere_layer, false);
      const double omega_layered = spheroidal_fundamental_frequency(2, layers, true);
      const RingdownResult d =
          measure_ringdown(relaxed, config, t, omega, 6 * 2 * std::numbers::pi / omega, !workflow_options.quiet);
      add("ringdown", d.period, 2 * std::numbers::pi / omega, layered_reference ? layered_ringdown_source : nullptr);
      if (!layered_reference)  // Lamb's sphere has one layer: no theory for a body with a core
        add("ringdown-lamb", d.period, 2 * std::numbers::pi / omega_lamb);
      const double shear_speed = std::sqrt(sphere.youngs_modulus / (2 * (1 + sphere.poisson_ratio)) / sphere.density);
      details["ringdown"] = Json{{"amplitude", d.amplitude}, {"initial", d.initial}, {"samples", d.time.size()},
                                 {"omega_a_over_vs_measured", 2 * std::numbers::pi / d.period * sphere.radius / shear_speed},
                                 {"omega_a_over_vs_lamb", omega_lamb * sphere.radius / shear_speed},
                                 {"omega_a_over_vs_self_gravitating", omega * sphere.radius / shear_speed},
                                 {"layered_period", 2 * std::numbers::pi / omega_layered}};
      std::vector<TimeMark> marks;
      for (int n = 1; n * 2 * std::numbers::pi / omega <= d.time.back(); ++n)
        marks.push_back({n * 2 * std::numbers::pi / omega, n == 1 ? "0S2 (TS72)" : "", false});
      for (int n = 1; n * d.period <= d.time.back(); ++n) marks.push_back({n * d.period, n == 1 ? "measured" : "", true});
      plots["ringdown"] = signal_plot_json((out / "ringdown").string(), d.time, d.signal, marks,
                        fmt::format("Degree-2 ring-down of {}\nmeasured period {:.4f}, 0S2 {:.4f}, Lamb {:.4f} t_grav",
                                    config.workflow.name, d.period, 2 * std::numbers::pi / omega,
                                    2 * std::numbers::pi / omega_lamb),
                        "P2 radial amplitude [R]");
    }
  }
  Json comparisons = Json::object();
  for (const auto& r : rows) comparisons[r.check->name] = row_json(r);
  json["comparisons"] = comparisons;
  json["details"] = details.is_null() ? Json::object() : details;
  write_file_atomically(out / "validation.json", json_text(json));
  if (!plots.empty()) {
    write_figure_data_file(out, plots);
    draw_figures("validate", {out.string()});
  }

  fmt::print("\n{:<18} {:>12} {:>12} {:>8} {:>6}  {}\n", "check", "measured", "theory", "ratio", "tol", "");
  for (const auto& r : rows)
    fmt::print("{:<18} {:>12.5g} {:>12.5g} {:>8.4f} {:>5.0f}%  {}\n", r.check->name, r.measured, r.theory, r.ratio(),
               100 * r.check->tolerance, r.within() ? "ok" : "outside");
  if (measured_moduli)
    fmt::print("network moduli: E = {:.4g} e_g = {:.3f} E_I (eq. 15), nu = {:.3f} (non-affine K x {:.3f}, G x {:.3f})\n",
             network_material.youngs_modulus, moduli.youngs_factor, network_material.poisson_ratio, moduli.bulk_factor,
             moduli.shear_factor);
  if (std::any_of(rows.begin(), rows.end(), [](const Row& r) { return r.source != nullptr; }))
    fmt::print("tide and ring-down against the layered sphere of the body's own layers (it has {})\n",
               relaxed.body.liquid.present() ? "an ocean" : "a core");
  fmt::print("results: {}\n", (out / "validation.json").string());
  return exit_ok;
}

}  // namespace tidalcrust
