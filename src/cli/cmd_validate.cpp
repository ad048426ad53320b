// `tidalcrust validate WORKFLOW.toml`: runs (or reuses) the workflow's body chain, then measures
// the relaxed body against continuum elasticity (analysis/elastic_validation.hpp): the breathing
// period, the Love number h2, the crust's flexural rigidity and the P-wave travel time. Writes
// <out>/validate/validation.json and figures, and prints a table. docs/validation.md.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "analysis/elastic_validation.hpp"
#include "base/errors.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "figures/validation_figures.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint_file.hpp"
#include "io/json.hpp"
#include "model/center_of_mass.hpp"
#include "physics/continuum_elasticity.hpp"
#include "stages/workflow.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

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
     "layered eq. 15/16 times the measured non-affine factors", 0.10, false}};

const Check& check_named(const std::string& name) {
  for (const auto& c : checks)
    if (name == c.name && c.selectable) return c;
  throw InputError(fmt::format("--measure: unknown measurement '{}' (known: breathing, love, flexure, p-wave)", name));
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
  double ratio() const { return measured / theory; }
  bool within() const { return std::abs(ratio() - 1) <= check->tolerance; }
};

Json row_json(const Row& r) {
  return Json{{"quantity", r.check->quantity}, {"unit", r.check->unit},
              {"measured", r.measured},        {"theory", r.theory},
              {"ratio", r.ratio()},            {"tolerance", r.check->tolerance},
              {"within_tolerance", r.within()}, {"source", r.check->source}};
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
      "measure", "comma-separated subset of breathing,love,flexure,p-wave",
      cxxopts::value<std::string>()->default_value("breathing,love,flexure,p-wave"));
  options.parse_positional({"workflow"});
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  // Everything is checked before anything is written: the measurements, then the workflow.
  const std::set<std::string> chosen = selected_measurements(parsed["measure"].as<std::string>());
  Config config = workflow_config(parsed);
  const int threads = checked_thread_count(parsed["threads"].as<int>());
  WorkflowOptions workflow_options;
  workflow_options.root = parsed.count("out") ? fs::path(parsed["out"].as<std::string>())
                                              : fs::path("checkpoints") / config.workflow.name;
  workflow_options.quiet = parsed.count("quiet") > 0;  // no encounters: the body chain alone
  apply_thread_count(threads);
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
  const auto add = [&](const char* name, double measured, double theory) {
    for (const auto& c : checks)
      if (name == std::string(c.name)) rows.push_back({&c, measured, theory});
  };

  Json json;
  json["workflow"] = config.workflow.name;
  json["relaxed_body"] = relaxed_file.string();
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
    write_signal_plot(b.time, b.signal, marks, out / "breathing",
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
    write_signal_plot(p.time, p.signal, marks, out / "p_wave",
                      fmt::format("P-wave pulse of {}: mean |dv| at the far pole\narrival {:.4f}, path/V_IP {:.4f} t_grav",
                                  config.workflow.name, p.arrival_time, p.theory_time),
                      "|dv| [sqrt(GM/R)]");
  }
  Json comparisons = Json::object();
  for (const auto& r : rows) comparisons[r.check->name] = row_json(r);
  json["comparisons"] = comparisons;
  json["details"] = details.is_null() ? Json::object() : details;
  write_file_atomically(out / "validation.json", json_text(json));

  fmt::print("\n{:<18} {:>12} {:>12} {:>8} {:>6}  {}\n", "check", "measured", "theory", "ratio", "tol", "");
  for (const auto& r : rows)
    fmt::print("{:<18} {:>12.5g} {:>12.5g} {:>8.4f} {:>5.0f}%  {}\n", r.check->name, r.measured, r.theory, r.ratio(),
               100 * r.check->tolerance, r.within() ? "ok" : "outside");
  if (measured_moduli)
    fmt::print("network moduli: E = {:.4g} e_g = {:.3f} E_I (eq. 15), nu = {:.3f} (non-affine K x {:.3f}, G x {:.3f})\n",
             network_material.youngs_modulus, moduli.youngs_factor, network_material.poisson_ratio, moduli.bulk_factor,
             moduli.shear_factor);
  fmt::print("results: {}\n", (out / "validation.json").string());
  return exit_ok;
}

}  // namespace tidalcrust
