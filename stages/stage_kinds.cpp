#include "stages/stage_kinds.hpp"

#include <fmt/format.h>

#include <array>

#include "physics/shell_failure.hpp"
#include "stages/build_stage.hpp"
#include "stages/encounter_stage.hpp"
#include "stages/relax_stage.hpp"
#include "stages/stretch_stage.hpp"
#include "stages/time_step.hpp"

namespace tidalcrust {
namespace {

using enum StageId;

constexpr std::array<StageKind, stage_count> kinds = {{
    {.id = build,
     .summary = "Build the body of a workflow (random interior, shell, springs).",
     .parents = {},
     .per_encounter = false,
     .begin = [](const Checkpoint*, const Config& config, const Encounter*) { return build_stage(config); },
     .run = nullptr,
     .checkpoint_interval_key = nullptr,
     .prepare = nullptr,
     .doing = [](const Config&) -> std::string { return "building the body"; },
     .written =
         [](const Checkpoint& c) {
           return fmt::format("{} particles, {} springs, {} hinges", c.body.particle_count(), c.body.spring_count(),
                              c.body.hinge_count());
         }},
    {.id = stretch,
     .summary = "Stretch and strengthen a built body (paper section 2.3).",
     .parents = {build},
     .per_encounter = false,
     .begin = [](const Checkpoint* built, const Config& config, const Encounter*) {
       return stretch_stage(*built, config);
     },
     .run = nullptr,
     .checkpoint_interval_key = nullptr,
     .prepare = nullptr,
     .doing =
         [](const Config& config) -> std::string {
           return config.stretch.hydrostatic_support == HydrostaticSupport::compress
                      ? "stretching (interior compressed to its pressure)"
                      : "stretching and strengthening";
         },
     .written =
         [](const Checkpoint& c) {
           const auto& record = c.stage.as<StretchRecord>();
           return fmt::format("factor {}, residual surface acceleration {:.3g}", record.stretch_factor,
                              record.residual_surface_acceleration);
         }},
    {.id = relax,
     .summary = "Damped relaxation and stability probe (paper section 2.8).",
     .parents = {stretch},
     .per_encounter = false,
     .begin = [](const Checkpoint* stretched, const Config& config, const Encounter*) {
       return begin_relax(*stretched, config);
     },
     .run = [](Checkpoint& c, const Config& config, const StepLoopOptions& options,
               const std::filesystem::path&) { return run_relax(c, config, options); },
     .checkpoint_interval_key = "relax.checkpoint_interval",
     // dt checked against (or, for a [material] body without one, chosen from) the stretched
     // body's stability bound; the encounters run with it too.
     // The failure rule's physical lengths are checked against this body's lattice once, here.
     .prepare = [](Config& config, const Checkpoint& stretched, const std::string& parent_file) {
       const std::string dt_note = settle_time_step(config, stretched, parent_file);
       const std::string lengths = unresolved_rule_lengths(config, stretched.body, stretched.state);
       return dt_note.empty() || lengths.empty() ? dt_note + lengths : dt_note + "\n" + lengths;
     },
     .doing = nullptr,
     .written = nullptr},
    {.id = encounter,
     .summary = "Tidal encounter with crust failure (paper sections 2.6, 2.9).",
     .parents = {relax, encounter},
     .per_encounter = true,
     .begin = [](const Checkpoint* relaxed, const Config& config, const Encounter* spec) {
       return begin_encounter(*relaxed, config, *spec);
     },
     .run = [](Checkpoint& c, const Config& config, const StepLoopOptions& options,
               const std::filesystem::path& file) { return run_encounter(c, config, options, file); },
     .checkpoint_interval_key = "encounter.checkpoint_interval",
     .prepare = nullptr,
     .doing = nullptr,
     .written = nullptr},
}};

constexpr bool in_pipeline_order() {
  for (std::size_t i = 0; i < kinds.size(); ++i)
    if (static_cast<std::size_t>(kinds[i].id) != i) return false;
  return true;
}
static_assert(in_pipeline_order(), "one row per stage, in the order of StageRecord");

}  // namespace

std::int64_t StageKind::checkpoint_interval(const Config& config) const {
  if (!checkpoint_interval_key) return 0;
  const std::string_view key = checkpoint_interval_key;
  const auto dot = key.find('.');
  return integer_key_value(config, key.substr(0, dot), key.substr(dot + 1));
}

std::span<const StageKind> stage_kinds() { return kinds; }

const StageKind& stage_kind(StageId id) { return kinds[static_cast<std::size_t>(id)]; }

}  // namespace tidalcrust
