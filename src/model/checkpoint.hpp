#pragma once
// One checkpoint = the full content needed to continue a run bit for bit: body, state, stage
// bookkeeping, resolved configuration and the observables gathered so far. The file format is
// io/checkpoint_file.hpp.
#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "base/errors.hpp"
#include "model/body.hpp"
#include "model/stage_records.hpp"
#include "model/state.hpp"
#include "base/invariant.hpp"

namespace tidalcrust {

/// One shell spring failure (paper section 2.6).
struct FailureEvent {
  double time = 0;                      ///< t_grav
  std::int64_t step = 0;
  std::int32_t spring = 0;              ///< index into Body::springs
  double strain = 0;                    ///< (L - L0)/L0 when it failed
  std::array<double, 3> position{};     ///< spring midpoint, R, same frame as State
  /// Elastic energy the failure removed, (1 - F_Sk) k (L - L0)^2/2 at the strain it failed at, G M^2/R.
  double released_energy = 0;
};

/// A sample of the conserved quantities (body + perturber, about the origin), of where the
/// perturber is, and of the energy budget (docs/energy-budget.md; G M^2/R, NaN where not
/// measured: the relax stage).
struct TimeseriesSample {
  static constexpr double not_measured = std::numeric_limits<double>::quiet_NaN();
  double time = 0;
  std::int64_t failed = 0;              ///< failed springs so far
  double kinetic_energy = 0;            ///< body particles and perturber
  std::array<double, 3> momentum{};
  std::array<double, 3> angular_momentum{};
  /// Perturber position minus the body's centre of mass (orbital_frame.hpp), R; the simulated
  /// track including the body's recoil. Zero when there is no perturber.
  std::array<double, 3> perturber_offset{};
  double internal_kinetic_energy = not_measured;  ///< body particles about the body's centre of mass
  double spring_energy = not_measured;       ///< elastic energy of the springs
  double hinge_energy = not_measured;        ///< bending energy E_h of the hinges
  double self_gravity_energy = not_measured; ///< the body's gravitational self-energy
  double perturber_energy = not_measured;    ///< gravitational energy of the body in the perturber's field
  double damping_dissipated = not_measured;  ///< EnergyLedger, since the stage began
  double failure_released = not_measured;    ///< EnergyLedger, since the stage began
  double hinge_residual_work = not_measured; ///< EnergyLedger, since the stage began
  /// The conserved total K + U + damping_dissipated + failure_released - hinge_residual_work.
  double conserved_energy() const {
    return kinetic_energy + spring_energy + hinge_energy + self_gravity_energy + perturber_energy +
           damping_dissipated + failure_released - hinge_residual_work;
  }
};

struct Observables {
  std::vector<FailureEvent> failures;
  std::vector<TimeseriesSample> timeseries;
};

/// Which stage wrote the checkpoint and everything its next step depends on besides the state.
struct StageInfo {
  StageRecord record;          ///< which stage (the variant's alternative) and what it recorded
  bool complete = true;        ///< false for a mid-stage (periodic, SIGINT or diagnostic) checkpoint
  StepClock clock;             ///< time axis: clock.start_step is where the stage began, clock.dt its time step
  std::int64_t end_step = 0;   ///< global step at which the stage ends
  std::string parent_hash;     ///< state_hash of the checkpoint the stage started from ("" for build)
  std::string fingerprint;     ///< what the result depends on (model/stage_fingerprint.hpp); "" in files written by
                               ///< a single-stage command before it recorded one
  std::string diagnostic;      ///< on a diagnostic checkpoint, what went wrong; else ""
  /// The gravity kernel that computed the state (forces/gravity.hpp: "fast/avx512", "fast/generic"
  /// or "portable"); "" for a build checkpoint (no forces) and files written before it was
  /// recorded. A new stage starts with its parent's; a stage that steps on under another kernel
  /// is refused unless allowed (stages/gravity_kernel_check.hpp).
  std::string gravity_kernel;
  /// One line per allowed change of kernel in this stage's history ("step 1200: fast/avx512 ->
  /// portable (--allow-kernel-change)"), oldest first; "" when the kernel never changed.
  std::string gravity_kernel_changes;

  const char* name() const { return stage_name(record); }
  /// The record as stage R; InternalError (TIDALCRUST_ASSERT) if the checkpoint is of another
  /// stage (callers check the stage first and report bad input themselves).
  template <typename R>
  R& as() {
    auto* r = std::get_if<R>(&record);
    TIDALCRUST_ASSERT(r != nullptr, std::string("stage record requested of the wrong stage: ") + name());
    return *r;
  }
  template <typename R>
  const R& as() const {
    const auto* r = std::get_if<R>(&record);
    TIDALCRUST_ASSERT(r != nullptr, std::string("stage record requested of the wrong stage: ") + name());
    return *r;
  }
};

/// Which program wrote a checkpoint (/parameters/provenance). Filled by read_checkpoint;
/// write_checkpoint always stores the running program's own build information instead.
struct Provenance {
  std::string version;      ///< tidalcrust version
  std::string git_commit;   ///< commit it was built from
  std::string compiler;     ///< compiler name and version
  std::string build_flags;  ///< compiler flags of the build
  /// The file's /checkpoint@format_version as stored (an older one is upgraded on reading);
  /// 0 for a checkpoint made in memory.
  std::int64_t format_version = 0;
};

struct Checkpoint {
  StageInfo stage;
  Provenance provenance;    ///< of the file read; empty for a checkpoint made in memory
  std::string config_toml;  ///< resolved configuration (to_toml)
  Body body;
  State state;
  Observables observables;
};

/// The name of stage R ("encounter" for EncounterRecord).
template <typename R>
const char* stage_name_of() {
  return stage_name(StageRecord(std::in_place_type<R>));
}

/// The record of stage R; InputError naming `file` if the checkpoint is of another stage.
template <typename R>
const R& stage_record(const Checkpoint& checkpoint, std::string_view file) {
  if (const auto* r = std::get_if<R>(&checkpoint.stage.record)) return *r;
  const std::string wanted = stage_name_of<R>();
  throw InputError(std::string(file) + ": stage is '" + checkpoint.stage.name() + "', expected " +
                   (wanted == "encounter" ? "an '" : "a '") + wanted + "' checkpoint");
}

}  // namespace tidalcrust
