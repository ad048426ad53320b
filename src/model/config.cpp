#include "model/config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "base/errors.hpp"

namespace tidalcrust {
namespace {

enum class ParamType { real, integer, boolean, text };

/// One configuration key: where it lives, its type, its range, its unit and what it means.
struct Param {
  const char* section;
  const char* key;
  ParamType type;
  std::function<void*(Config&)> field;
  double min;
  double max;
  const char* unit;
  const char* doc;
};

constexpr double inf = std::numeric_limits<double>::infinity();

#define TC_FIELD(expr) [](Config& c) -> void* { return &c.expr; }

const std::vector<Param>& params() {
  static const std::vector<Param> table = {
      {"workflow", "name", ParamType::text, TC_FIELD(workflow.name), 0, 0, "-",
       "workflow name; default output folder checkpoints/<name>/"},
      {"workflow", "seed", ParamType::integer, TC_FIELD(workflow.seed), 0, 9.0e18, "-",
       "seed of the random interior (std::mt19937_64)"},

      {"interior", "count", ParamType::integer, TC_FIELD(interior.count), 1, 1e6, "-",
       "N_I, target number of interior nodes"},
      {"interior", "radius", ParamType::real, TC_FIELD(interior.radius), 0.05, 1.0, "R",
       "r_I, radius of the sphere the interior nodes fill"},
      {"interior", "min_separation", ParamType::real, TC_FIELD(interior.min_separation), 1e-3, 1.0, "R",
       "d_IS, minimum distance between interior nodes"},
      {"interior", "spring_distance", ParamType::real, TC_FIELD(interior.spring_distance), 1e-3, 2.0, "R",
       "d_I, interior nodes closer than this are joined by a spring"},
      {"interior", "spring_constant", ParamType::real, TC_FIELD(interior.spring_constant), 0, inf, "G M^2/R^3",
       "k_I, interior spring constant"},
      {"interior", "max_trials", ParamType::integer, TC_FIELD(interior.max_trials), 1, 1e12, "-",
       "random sequential addition stops after this many trial points"},

      {"shell", "enabled", ParamType::boolean, TC_FIELD(shell.enabled), 0, 0, "-",
       "false for an interior-only body (paper run N)"},
      {"shell", "level", ParamType::integer, TC_FIELD(shell.level), 0, 7, "-",
       "L, icosahedron subdivision level: 10*4^L+2 nodes"},
      {"shell", "mass", ParamType::real, TC_FIELD(shell.mass), 0, 0.99, "M", "M_S, total shell mass"},
      {"shell", "spring_constant", ParamType::real, TC_FIELD(shell.spring_constant), 0, inf, "G M^2/R^3",
       "k_S, shell spring constant"},
      {"shell", "bending_constant", ParamType::real, TC_FIELD(shell.bending_constant), 0, inf, "G M^2/R^2",
       "k_e, hinge (bending) force constant"},
      {"shell", "failure_strain", ParamType::real, TC_FIELD(shell.failure_strain), 1e-9, 10, "-",
       "eps_S, tensile strain at which a shell spring fails"},
      {"shell", "failed_stiffness_factor", ParamType::real, TC_FIELD(shell.failed_stiffness_factor), 1e-9, 1,
       "-", "F_Sk, a failed spring keeps this fraction of its stiffness (never 0)"},

      {"cross", "distance", ParamType::real, TC_FIELD(cross.distance), 0, 2.0, "R",
       "d_C, shell-interior pairs closer than this are joined by a cross spring"},
      {"cross", "spring_constant", ParamType::real, TC_FIELD(cross.spring_constant), 0, inf, "G M^2/R^3",
       "k_C, cross spring constant"},
      {"cross", "nonlinear", ParamType::boolean, TC_FIELD(cross.nonlinear), 0, 0, "-",
       "apply the softening law f(eps) of eq. 26 to cross springs"},
      {"cross", "strain_scale", ParamType::real, TC_FIELD(cross.strain_scale), 1e-9, 10, "-",
       "eps_C of eq. 26"},
      {"cross", "min_force_factor", ParamType::real, TC_FIELD(cross.min_force_factor), 1e-9, 1, "-",
       "F_Ck of eq. 26"},

      {"integrator", "dt", ParamType::real, TC_FIELD(integrator.dt), 1e-7, 1.0, "t_grav",
       "leapfrog time step"},
      {"integrator", "softening_fraction", ParamType::real, TC_FIELD(integrator.softening_fraction), 0, 1, "-",
       "Plummer softening as a fraction of the minimum initial spacing"},

      {"stretch", "enabled", ParamType::boolean, TC_FIELD(stretch.enabled), 0, 0, "-",
       "false skips stretching and strengthening (for comparisons)"},
      {"stretch", "max_iterations", ParamType::integer, TC_FIELD(stretch.max_iterations), 1, 10000, "-",
       "iterations allowed to find the common stretch factor"},
      {"stretch", "tolerance", ParamType::real, TC_FIELD(stretch.tolerance), 0, 1, "G M/R^2",
       "target |mean radial acceleration| of the surface"},
      {"stretch", "cross_compression", ParamType::real, TC_FIELD(stretch.cross_compression), 0, 0.5, "-",
       "extra compressive strain given to cross springs"},

      {"relax", "damping", ParamType::real, TC_FIELD(relax.damping), 0, 1e4, "1/t_grav",
       "gamma during relaxation"},
      {"relax", "duration", ParamType::real, TC_FIELD(relax.duration), 0, 1e4, "t_grav",
       "T, length of the relaxation run"},
      {"relax", "rest_length_interval", ParamType::integer, TC_FIELD(relax.rest_length_interval), 1, 1e9,
       "steps", "steps between moves of shell rest lengths toward current lengths"},
      {"relax", "rest_length_rate", ParamType::real, TC_FIELD(relax.rest_length_rate), 0, 1, "-",
       "fraction of (L - L0) a shell rest length moves per update"},
      {"relax", "hinge_reset_interval", ParamType::integer, TC_FIELD(relax.hinge_reset_interval), 1, 1e9,
       "steps", "steps between resets of hinge rest angles to current angles"},
      {"relax", "settle_duration", ParamType::real, TC_FIELD(relax.settle_duration), 0, 1e4, "t_grav",
       "last part of T: the crust is reset to zero stress, then the body settles without creep or resets"},
      {"relax", "checkpoint_interval", ParamType::integer, TC_FIELD(relax.checkpoint_interval), 0, 1e12,
       "steps", "steps between mid-stage checkpoints (0: none)"},
      {"relax", "stability_probe", ParamType::boolean, TC_FIELD(relax.stability_probe), 0, 0, "-",
       "run the stability probe (encounter damping, failures on, no perturber) after relaxing"},
      {"relax", "probe_damping", ParamType::real, TC_FIELD(relax.probe_damping), 0, 1e4, "1/t_grav",
       "gamma of the stability probe"},
      {"relax", "probe_duration", ParamType::real, TC_FIELD(relax.probe_duration), 0, 1e4, "t_grav",
       "length of the stability probe"},

      {"encounter", "damping", ParamType::real, TC_FIELD(encounter.damping), 0, 1e4, "1/t_grav",
       "gamma during encounters"},
      {"encounter", "fail_interval", ParamType::integer, TC_FIELD(encounter.fail_interval), 1, 1e9, "steps",
       "t_fail: at most one shell spring fails per this many steps"},
      {"encounter", "start_distance", ParamType::real, TC_FIELD(encounter.start_distance), 1e-3, 1e6, "R",
       "perturber distance when the encounter starts (before pericenter)"},
      {"encounter", "end_distance", ParamType::real, TC_FIELD(encounter.end_distance), 1e-3, 1e6, "R",
       "perturber distance when the encounter ends (after pericenter)"},
      {"encounter", "checkpoint_interval", ParamType::integer, TC_FIELD(encounter.checkpoint_interval), 0,
       1e12, "steps", "steps between mid-stage checkpoints (0: none)"},
      {"encounter", "sample_interval", ParamType::integer, TC_FIELD(encounter.sample_interval), 1, 1e9,
       "steps", "steps between timeseries samples"},
  };
  return table;
}
#undef TC_FIELD

const std::vector<const char*>& section_order() {
  static const std::vector<const char*> order = {"workflow", "interior", "shell",   "cross",
                                                 "integrator", "stretch", "relax", "encounter"};
  return order;
}

const Param* find_param(std::string_view section, std::string_view key) {
  for (const auto& p : params())
    if (section == p.section && key == p.key) return &p;
  return nullptr;
}

std::string format_real(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // keep it a TOML float
  return s;
}

std::string quote(const std::string& s) {
  std::ostringstream out;
  out << toml::value<std::string>(s);
  return out.str();
}

/// Stores a TOML node into a parameter; `where` names the key for messages.
void assign(Config& config, const Param& p, const toml::node& node, const std::string& where) {
  void* field = p.field(config);
  switch (p.type) {
    case ParamType::real:
      if (auto v = node.value_exact<double>()) {
        *static_cast<double*>(field) = *v;
      } else if (auto i = node.value_exact<std::int64_t>()) {
        *static_cast<double*>(field) = static_cast<double>(*i);
      } else {
        throw InputError(fmt::format("{}: '{}' must be a number", where, p.key));
      }
      break;
    case ParamType::integer: {
      auto i = node.value_exact<std::int64_t>();
      if (!i) throw InputError(fmt::format("{}: '{}' must be an integer", where, p.key));
      if (std::string_view(p.key) == "seed") {
        if (*i < 0) throw InputError(fmt::format("{}: 'seed' must be >= 0", where));
        *static_cast<std::uint64_t*>(field) = static_cast<std::uint64_t>(*i);
      } else {
        *static_cast<std::int64_t*>(field) = *i;
      }
      break;
    }
    case ParamType::boolean: {
      auto b = node.value_exact<bool>();
      if (!b) throw InputError(fmt::format("{}: '{}' must be true or false", where, p.key));
      *static_cast<bool*>(field) = *b;
      break;
    }
    case ParamType::text: {
      auto s = node.value_exact<std::string>();
      if (!s) throw InputError(fmt::format("{}: '{}' must be a string", where, p.key));
      *static_cast<std::string*>(field) = *s;
      break;
    }
  }
}

Encounter parse_encounter(const toml::table& t, const std::string& where) {
  Encounter e;
  for (auto&& [k, node] : t) {
    std::string key(k.str());
    auto number = [&](const char* name) {
      if (auto v = node.value<double>()) {
        if (node.is_number()) return *v;
      }
      throw InputError(fmt::format("{}: '{}' must be a number", where, name));
    };
    if (key == "name") {
      auto s = node.value_exact<std::string>();
      if (!s) throw InputError(fmt::format("{}: 'name' must be a string", where));
      e.name = *s;
    } else if (key == "perturber_mass") {
      e.perturber_mass = number("perturber_mass");
    } else if (key == "pericenter") {
      e.pericenter = number("pericenter");
    } else if (key == "pericenter_speed") {
      e.pericenter_speed = number("pericenter_speed");
    } else if (key == "failure_strain") {
      e.failure_strain = number("failure_strain");
    } else {
      throw InputError(fmt::format(
          "{}: unknown key '{}' (known: name, perturber_mass, pericenter, pericenter_speed, failure_strain)",
          where, key));
    }
  }
  return e;
}

void check_encounter(const Encounter& e, const std::string& where) {
  if (e.name.empty()) throw InputError(fmt::format("{}: encounter needs a non-empty 'name'", where));
  for (char ch : e.name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '-' || ch == '_' || ch == '.'))
      throw InputError(fmt::format("{}: encounter name '{}' may only use letters, digits, '-', '_', '.'",
                                   where, e.name));
  if (!std::isfinite(e.perturber_mass) || e.perturber_mass <= 0)
    throw InputError(fmt::format("{}: encounter '{}': perturber_mass must be a finite number > 0, got {}",
                                 where, e.name, e.perturber_mass));
  if (!std::isfinite(e.pericenter) || e.pericenter <= 1.0)
    throw InputError(fmt::format(
        "{}: encounter '{}': pericenter must be > 1 (outside the body, in R), got {}", where, e.name,
        e.pericenter));
  if (!std::isfinite(e.pericenter_speed) || e.pericenter_speed <= 0)
    throw InputError(fmt::format("{}: encounter '{}': pericenter_speed must be a finite number > 0, got {}",
                                 where, e.name, e.pericenter_speed));
  if (e.failure_strain && (!std::isfinite(*e.failure_strain) || *e.failure_strain <= 0))
    throw InputError(fmt::format("{}: encounter '{}': failure_strain must be > 0", where, e.name));
}

}  // namespace

const Encounter& Config::find_encounter(const std::string& name) const {
  std::string known;
  for (const auto& e : encounters) {
    if (e.name == name) return e;
    known += (known.empty() ? "" : ", ") + e.name;
  }
  throw InputError(fmt::format("unknown encounter '{}' (this workflow has: {})", name,
                               known.empty() ? "none" : known));
}

void scale_time_step(Config& config, double factor) {
  config.integrator.dt *= factor;
  auto rescale = [factor](std::int64_t& steps) {
    if (steps > 0) steps = std::max<std::int64_t>(1, std::llround(static_cast<double>(steps) / factor));
  };
  rescale(config.relax.rest_length_interval);
  rescale(config.relax.hinge_reset_interval);
  rescale(config.relax.checkpoint_interval);
  rescale(config.encounter.fail_interval);
  rescale(config.encounter.checkpoint_interval);
  rescale(config.encounter.sample_interval);
}

void validate(const Config& config, const std::string& origin) {
  Config& c = const_cast<Config&>(config);  // only read through the field accessors
  for (const auto& p : params()) {
    double v = 0;
    if (p.type == ParamType::real) v = *static_cast<double*>(p.field(c));
    else if (p.type == ParamType::integer && std::string_view(p.key) != "seed")
      v = static_cast<double>(*static_cast<std::int64_t*>(p.field(c)));
    else continue;
    if (!std::isfinite(v) || v < p.min || v > p.max)
      throw InputError(fmt::format("{}: {}.{} = {} is out of range [{}, {}] ({})", origin, p.section, p.key,
                                   v, p.min, p.max, p.unit));
  }
  if (config.workflow.name.empty())
    throw InputError(fmt::format("{}: workflow.name must not be empty", origin));
  if (config.interior.min_separation >= config.interior.spring_distance)
    throw InputError(fmt::format("{}: interior.min_separation ({}) must be smaller than interior.spring_distance ({})",
                                 origin, config.interior.min_separation, config.interior.spring_distance));
  if (config.interior.min_separation > 2 * config.interior.radius)
    throw InputError(fmt::format("{}: interior.min_separation is larger than the interior", origin));
  if (config.relax.settle_duration > config.relax.duration)
    throw InputError(fmt::format("{}: relax.settle_duration ({}) must not exceed relax.duration ({})", origin,
                                 config.relax.settle_duration, config.relax.duration));
  std::set<std::string> names;
  for (const auto& e : config.encounters) {
    check_encounter(e, origin);
    if (!names.insert(e.name).second)
      throw InputError(fmt::format("{}: encounter name '{}' appears twice", origin, e.name));
  }
}

Config parse_config(const std::string& toml_text, const std::string& origin) {
  toml::table root;
  try {
    root = toml::parse(toml_text, origin);
  } catch (const toml::parse_error& err) {
    const auto& where = err.source().begin;
    throw InputError(fmt::format("{}:{}:{}: malformed TOML: {}", origin, where.line, where.column,
                                 err.description()));
  }
  Config config;
  for (auto&& [sk, snode] : root) {
    std::string section(sk.str());
    if (section == "encounters") {
      auto* arr = snode.as_array();
      if (!arr) throw InputError(fmt::format("{}: 'encounters' must be an array of tables ([[encounters]])", origin));
      std::size_t idx = 0;
      for (auto&& el : *arr) {
        auto* t = el.as_table();
        std::string where = fmt::format("{}: encounters[{}]", origin, idx++);
        if (!t) throw InputError(where + ": must be a table");
        config.encounters.push_back(parse_encounter(*t, where));
      }
      continue;
    }
    bool known_section = false;
    for (auto s : section_order()) known_section |= (section == s);
    if (!known_section)
      throw InputError(fmt::format("{}: unknown section '{}' (known: workflow, interior, shell, cross, integrator, "
                                   "stretch, relax, encounter, encounters)", origin, section));
    auto* table = snode.as_table();
    if (!table) throw InputError(fmt::format("{}: '{}' must be a table", origin, section));
    for (auto&& [k, node] : *table) {
      std::string key(k.str());
      const Param* p = find_param(section, key);
      if (!p) throw InputError(fmt::format("{}: unknown key '{}.{}'", origin, section, key));
      assign(config, *p, node, fmt::format("{}: {}", origin, section));
    }
  }
  validate(config, origin);
  return config;
}

Config load_config(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open configuration file", file.string()));
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_config(buffer.str(), file.string());
}

void apply_override(Config& config, const std::string& assignment) {
  auto eq = assignment.find('=');
  if (eq == std::string::npos)
    throw InputError(fmt::format("--set '{}': expected section.key=value", assignment));
  std::string path = assignment.substr(0, eq);
  std::string value = assignment.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse(std::string_view("v = " + value), std::string_view("--set"));
  } catch (const toml::parse_error& err) {
    throw InputError(fmt::format("--set '{}': value is not valid TOML: {}", assignment, err.description()));
  }
  const toml::node& node = *parsed.get("v");
  auto dot = path.find('.');
  if (dot == std::string::npos)
    throw InputError(fmt::format("--set '{}': expected section.key=value", assignment));
  std::string section = path.substr(0, dot);
  std::string key = path.substr(dot + 1);
  if (section == "encounters") {  // encounters.NAME.key=value
    auto dot2 = key.find('.');
    if (dot2 == std::string::npos)
      throw InputError(fmt::format("--set '{}': expected encounters.NAME.key=value", assignment));
    std::string name = key.substr(0, dot2);
    std::string field = key.substr(dot2 + 1);
    for (auto& e : config.encounters) {
      if (e.name != name) continue;
      toml::table t;
      t.insert("name", e.name);
      t.insert(field, node);
      Encounter updated = parse_encounter(t, fmt::format("--set '{}'", assignment));
      if (field == "perturber_mass") e.perturber_mass = updated.perturber_mass;
      if (field == "pericenter") e.pericenter = updated.pericenter;
      if (field == "pericenter_speed") e.pericenter_speed = updated.pericenter_speed;
      if (field == "failure_strain") e.failure_strain = updated.failure_strain;
      return;
    }
    throw InputError(fmt::format("--set '{}': no encounter named '{}'", assignment, name));
  }
  const Param* p = find_param(section, key);
  if (!p) throw InputError(fmt::format("--set '{}': unknown key '{}'", assignment, path));
  assign(config, *p, node, "--set");
}

std::string section_toml(const Config& config, std::string_view section) {
  Config& c = const_cast<Config&>(config);  // only read through the field accessors
  std::string out = fmt::format("[{}]\n", section);
  for (const auto& p : params()) {
    if (std::string_view(p.section) != section) continue;
    void* f = p.field(c);
    std::string value;
    switch (p.type) {
      case ParamType::real: value = format_real(*static_cast<double*>(f)); break;
      case ParamType::integer:
        value = std::string_view(p.key) == "seed" ? fmt::format("{}", *static_cast<std::uint64_t*>(f))
                                                  : fmt::format("{}", *static_cast<std::int64_t*>(f));
        break;
      case ParamType::boolean: value = *static_cast<bool*>(f) ? "true" : "false"; break;
      case ParamType::text: value = quote(*static_cast<std::string*>(f)); break;
    }
    out += fmt::format("{} = {}  # [{}] {}\n", p.key, value, p.unit, p.doc);
  }
  return out;
}

std::string encounter_toml(const Encounter& e) {
  std::string out = "[[encounters]]\n";
  out += fmt::format("name = {}\n", quote(e.name));
  out += fmt::format("perturber_mass = {}  # [M] M2\n", format_real(e.perturber_mass));
  out += fmt::format("pericenter = {}  # [R] q\n", format_real(e.pericenter));
  out += fmt::format("pericenter_speed = {}  # [sqrt(GM/R)] V_q\n", format_real(e.pericenter_speed));
  if (e.failure_strain) out += fmt::format("failure_strain = {}  # [-] eps_S override\n", format_real(*e.failure_strain));
  return out;
}

std::string to_toml(const Config& config) {
  std::string out = "# tidalcrust resolved configuration (every key, defaults included)\n";
  for (auto section : section_order()) out += "\n" + section_toml(config, section);
  for (const auto& e : config.encounters) out += "\n" + encounter_toml(e);
  return out;
}

}  // namespace tidalcrust
