#include "stage_fingerprint.hpp"

#include <fmt/format.h>

#include <sstream>

namespace tidalcrust {

std::string build_fingerprint(const Config& config) {
  return fmt::format("seed = {}\nsoftening_fraction = {}\n", config.workflow.seed,
                     config.integrator.softening_fraction) +
         section_toml(config, "interior") + section_toml(config, "shell") + section_toml(config, "cross");
}

std::string stretch_fingerprint(const Config& config) {
  return build_fingerprint(config) + section_toml(config, "stretch");
}

std::string relax_fingerprint(const Config& config) {
  return stretch_fingerprint(config) + section_toml(config, "relax") +
         fmt::format("dt = {}\n", config.integrator.dt);
}

std::string encounter_fingerprint(const Config& config, const EncounterSpec& spec) {
  // The relaxed body's own dt is part of relax_fingerprint; the encounter may run at another.
  return stretch_fingerprint(config) + section_toml(config, "relax") + section_toml(config, "encounter") +
         encounter_toml(spec) + fmt::format("encounter_dt = {}\n", config.integrator.dt);
}

std::string first_difference(const std::string& old_text, const std::string& new_text) {
  std::istringstream a(old_text), b(new_text);
  std::string la, lb, section;
  while (true) {
    bool ga = static_cast<bool>(std::getline(a, la)), gb = static_cast<bool>(std::getline(b, lb));
    if (!ga && !gb) return "";
    if (ga && !la.empty() && la[0] == '[') section = la;
    if (la != lb) {
      auto strip = [](const std::string& s) { return s.substr(0, s.find("  #")); };
      return fmt::format("{} '{}' -> '{}'", section, strip(la), strip(lb));
    }
  }
}

}  // namespace tidalcrust
