#include "model/stage_fingerprint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <initializer_list>
#include <sstream>
#include <string_view>

namespace tidalcrust {
namespace {

enum class Keys { only, all_but };

/// The "section.key = value" lines of one section of the resolved configuration, restricted to
/// (or excluding) the given keys.
std::string keys_of(const Config& config, std::string_view section, Keys mode,
                    std::initializer_list<std::string_view> keys) {
  std::string out;
  for (const auto& [key, value] : section_values(config, section)) {
    const bool listed = std::find(keys.begin(), keys.end(), key) != keys.end();
    if (listed == (mode == Keys::only)) out += fmt::format("{}.{} = {}\n", section, key, value);
  }
  return out;
}

/// What the force law reads beyond the stored springs (the optional cross-spring law, eq. 26;
/// the self-gravity method: tree gravity gives other bits than the direct sum, so it is another
/// stage; written only for the tree, so every fingerprint of a direct run stays as it was).
std::string force_law(const Config& config) {
  std::string text = keys_of(config, "cross", Keys::only, {"nonlinear", "strain_scale", "min_force_factor"});
  if (config.gravity.method != GravityMethod::direct)
    text += keys_of(config, "gravity", Keys::only, {"method", "force_error"});
  return text;
}

/// What the force law and the failure rule read during a time-stepping stage.
std::string dynamics(const Config& config) {
  return force_law(config) + keys_of(config, "shell", Keys::only, {"failure_strain", "failed_stiffness_factor"});
}

/// [material], [resolution], [core] (issue 12): only the keys given, so a body without them keeps
/// its fingerprint.
std::string material_keys(const Config& config) {
  return keys_of(config, "material", Keys::all_but, {}) + keys_of(config, "resolution", Keys::all_but, {}) +
         keys_of(config, "core", Keys::all_but, {});
}

}  // namespace

// Each later stage also records its parent's state_hash, so a fingerprint only needs what the
// stage itself reads. Checkpoint intervals change no result and are left out.

std::string build_fingerprint(const Config& config) {
  return fmt::format("workflow.seed = {}\nintegrator.softening_fraction = {}\n", config.workflow.seed,
                     config.integrator.softening_fraction) +
         keys_of(config, "interior", Keys::all_but, {}) +
         keys_of(config, "shell", Keys::all_but, {"failure_strain", "failed_stiffness_factor"}) +
         keys_of(config, "cross", Keys::only, {"distance", "spring_constant", "min_per_shell_node"}) +
         // Only when not the paper's, so that a body without it keeps its fingerprint.
         (config.cross.coupling != CrossCoupling::paper ? keys_of(config, "cross", Keys::only, {"coupling"})
                                                        : std::string()) +
         material_keys(config);
}

std::string stretch_fingerprint(const Config& config) {
  return keys_of(config, "stretch", Keys::all_but, {}) + force_law(config) +
         keys_of(config, "core", Keys::all_but, {});  // the layered hydrostatic pressure
}

std::string relax_fingerprint(const Config& config) {
  // The stability probe uses the encounter failure interval and every eps_S an encounter asks for.
  std::string text = keys_of(config, "relax", Keys::all_but, {"checkpoint_interval"}) + dynamics(config) +
                     keys_of(config, "encounter", Keys::only,
                             {"fail_interval", "sample_interval", "failure_rule", "exclusion_radius",
                              "relaxation_crossings"}) +
                     fmt::format("integrator.dt = {}\n", config.integrator.dt);
  for (const auto& e : config.encounters)
    if (e.failure_strain) text += fmt::format("encounters.{}.failure_strain = {}\n", e.name, *e.failure_strain);
  return text;
}

std::string encounter_fingerprint(const Config& config, const Encounter& spec) {
  return keys_of(config, "encounter", Keys::all_but, {"checkpoint_interval"}) + dynamics(config) +
         encounter_toml(spec) + fmt::format("integrator.dt = {}\n", config.integrator.dt);
}

std::string first_difference(const std::string& old_text, const std::string& new_text) {
  std::istringstream a(old_text), b(new_text);
  std::string la, lb;
  while (true) {
    const bool ga = static_cast<bool>(std::getline(a, la)), gb = static_cast<bool>(std::getline(b, lb));
    if (!ga && !gb) return "";
    if (la != lb) return fmt::format("'{}' -> '{}'", ga ? la : "", gb ? lb : "");
  }
}

}  // namespace tidalcrust
