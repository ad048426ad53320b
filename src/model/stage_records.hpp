#pragma once
// What a stage records besides the body and state: its time axis (the one home of dt), its
// results, and the schedule a resumed stage must follow exactly. One typed record per stage;
// `visit_fields` lists each record's fields ONCE (name, value, unit, meaning) and drives the
// checkpoint writer and reader (io/checkpoint_file.cpp), `inspect` and the layout in
// docs/checkpoint-layout.md (the pattern of GROMACS doCheckpointData and REBOUND's binary field
// list). Units: G = M = R = 1 (t_grav, R, sqrt(GM/R)); "1" marks a pure number.
#include <concepts>
#include <cstdint>
#include <initializer_list>
#include <iterator>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "model/encounter.hpp"
#include "model/failure_rule.hpp"

namespace tidalcrust {

/// The time axis of a stage. Time is a function of the step count, never accumulated by
/// t += dt, so a resumed run and a straight run agree bit for bit:
///   time_at(step) = start_time + (step - start_step) * dt.
/// The time step dt lives here and nowhere else; the integrator takes it from the clock.
struct StepClock {
  double start_time = 0;         ///< t_grav at start_step
  std::int64_t start_step = 0;   ///< global step at which the stage started
  double dt = 0;                 ///< time step, t_grav
  double time_at(std::int64_t step) const { return start_time + static_cast<double>(step - start_step) * dt; }
  bool operator==(const StepClock&) const = default;
};

/// Stage 1 (build): how the random interior came out.
struct BuildRecord {
  std::int64_t interior_nodes = 0;   ///< nodes placed (the target is interior.count)
  std::int64_t interior_trials = 0;  ///< trial points of the random sequential addition
  double min_spacing = 0;            ///< smallest distance between two particles, R
  bool operator==(const BuildRecord&) const = default;
};

/// Stage 2 (stretch and strengthen, paper section 2.3).
struct StretchRecord {
  double stretch_factor = 1;                ///< common rest-length factor f (1: stretching off)
  double stretch_factor_unstrengthened = 0; ///< f before strengthening
  double residual_surface_acceleration = 0; ///< mean radial acceleration of the surface after, G M/R^2
  double residual_virial_acceleration = 0;  ///< virial balance residual after, G M/R^2
  std::int64_t iterations = 0;              ///< force evaluations used
  double strengthening_max = 0;             ///< largest stiffness multiplier of the core springs
  double uniform_pressure = 0;              ///< P of the even compression the multipliers are scaled to, e_g
  double strengthening_radius = 0;          ///< radius inside which springs are strengthened, R
  double dt_max = 0;                        ///< stability bound of eq. 13 on the stretched body, t_grav
  bool operator==(const StretchRecord&) const = default;
};

/// Stage 3 (damped relaxation, paper section 2.8) and its stability probe.
struct RelaxRecord {
  double damping = 0;                ///< gamma of the relaxation, 1/t_grav (eq. 14, reduced mass)
  std::int64_t creep_end_step = 0;   ///< last step of the creep phase (global step)
  bool relaxed = false;              ///< relaxation done (the probe may still be pending)
  double max_shell_strain = 0;       ///< largest |strain| of a shell spring when relaxed
  double max_shell_tension = 0;      ///< largest tensile strain of a shell spring when relaxed
  double internal_kinetic_energy = 0;///< kinetic energy about the centre of mass, G M^2/R
  double mean_shell_radius = 0;      ///< mean shell node distance from the centre of mass, R
  std::int64_t probe_runs = 0;       ///< stability probes run (0: no probe results)
  double probe_failure_strain = 0;   ///< eps_S of the main probe
  std::int64_t probe_failures = 0;   ///< failures of the main probe
  double probe_max_shell_strain = 0; ///< largest tensile shell strain during the main probe
  std::vector<double> probe_other_strains;          ///< [k] further eps_S checked (T1's, overrides)
  std::vector<std::int64_t> probe_other_failures;   ///< [k] failures at each of them
  bool operator==(const RelaxRecord&) const = default;
};

/// The energy that the forces without a potential and the failures moved in or out of the motion
/// since the stage began, accumulated every step (docs/energy-budget.md), G M^2/R. With them the
/// total kinetic + potential + damping_dissipated + failure_released - hinge_residual_work is
/// conserved up to the leapfrog's O(dt^2) error.
struct EnergyLedger {
  double damping_dissipated = 0;   ///< work done against the spring damping (>= 0 up to O(dt^2))
  double failure_released = 0;     ///< elastic energy removed by failures: (1 - F_Sk) k (L - L0)^2/2 each
  double hinge_residual_work = 0;  ///< work of the hinge forces beyond minus the change of the hinge energy
  bool operator==(const EnergyLedger&) const = default;
};

/// Stage 4 (encounter, paper sections 2.6, 2.9): the perturber, the failure rule and schedules
/// fixed when the encounter begins, and what the run measured.
struct EncounterRecord {
  Encounter encounter;                ///< name, M2, q, V_q, after (failure_strain, orientation: see below)
  OrbitOrientation orbit;             ///< the orbit's orientation used (orbit_orientation of the encounter), deg
  double failure_strain = 0;          ///< eps_S used
  double failed_stiffness_factor = 0; ///< F_Sk used
  double damping = 0;                 ///< gamma, 1/t_grav
  FailureRule failure_rule;           ///< the rule with its schedule in steps (model/failure_rule.hpp)
  std::int64_t sample_interval = 1;   ///< steps between timeseries samples
  double start_distance = 0;          ///< perturber distance at the start, R
  double end_distance = 0;            ///< perturber distance at the end, R
  double pericenter_time = 0;         ///< analytic time of pericenter, t_grav
  std::int64_t pericenter_step = 0;   ///< step nearest the analytic pericenter
  std::vector<std::int64_t> snapshot_steps;  ///< [k] ascending global steps of the snapshot files
  double min_distance = 0;            ///< closest approach measured so far, R
  double speed_at_min = 0;            ///< relative speed there, sqrt(GM/R)
  double time_of_min = 0;             ///< t_grav
  std::int64_t step_of_min = 0;
  EnergyLedger energy;                ///< accumulated every step since the encounter began
  bool operator==(const EncounterRecord&) const = default;
};

/// Lists every field of a record (const or not) as visit(name, value, unit, meaning). Names are
/// the HDF5 names under /checkpoint/record; the order is the stored order.
template <typename Record, typename Visit>
  requires std::same_as<std::remove_const_t<Record>, BuildRecord>
void visit_fields(Record& r, Visit&& visit) {
  visit("interior_nodes", r.interior_nodes, "1", "interior nodes placed");
  visit("interior_trials", r.interior_trials, "1", "trial points of the random sequential addition");
  visit("min_spacing", r.min_spacing, "R", "smallest distance between two particles");
}

template <typename Record, typename Visit>
  requires std::same_as<std::remove_const_t<Record>, StretchRecord>
void visit_fields(Record& r, Visit&& visit) {
  visit("stretch_factor", r.stretch_factor, "1", "common rest-length factor f");
  visit("stretch_factor_unstrengthened", r.stretch_factor_unstrengthened, "1", "f before strengthening");
  visit("residual_surface_acceleration", r.residual_surface_acceleration, "G M/R^2",
        "mean radial surface acceleration after stretching");
  visit("residual_virial_acceleration", r.residual_virial_acceleration, "G M/R^2", "virial balance residual");
  visit("iterations", r.iterations, "1", "force evaluations");
  visit("strengthening_max", r.strengthening_max, "1", "largest core stiffness multiplier");
  visit("uniform_pressure", r.uniform_pressure, "e_g", "pressure of the even compression");
  visit("strengthening_radius", r.strengthening_radius, "R", "springs inside are strengthened");
  visit("dt_max", r.dt_max, "t_grav", "stability bound of eq. 13");
}

template <typename Record, typename Visit>
  requires std::same_as<std::remove_const_t<Record>, RelaxRecord>
void visit_fields(Record& r, Visit&& visit) {
  visit("damping", r.damping, "1/t_grav", "gamma of the relaxation");
  visit("creep_end_step", r.creep_end_step, "step", "last step of the creep phase");
  visit("relaxed", r.relaxed, "1", "relaxation done");
  visit("max_shell_strain", r.max_shell_strain, "1", "largest |shell strain| when relaxed");
  visit("max_shell_tension", r.max_shell_tension, "1", "largest tensile shell strain when relaxed");
  visit("internal_kinetic_energy", r.internal_kinetic_energy, "G M^2/R", "kinetic energy about the centre of mass");
  visit("mean_shell_radius", r.mean_shell_radius, "R", "mean shell radius");
  visit("probe_runs", r.probe_runs, "1", "stability probes run");
  visit("probe_failure_strain", r.probe_failure_strain, "1", "eps_S of the main probe");
  visit("probe_failures", r.probe_failures, "1", "failures in the main probe");
  visit("probe_max_shell_strain", r.probe_max_shell_strain, "1", "largest tensile shell strain in the probe");
  visit("probe_other_strains", r.probe_other_strains, "1", "further eps_S probed");
  visit("probe_other_failures", r.probe_other_failures, "1", "failures at each further eps_S");
}

template <typename Record, typename Visit>
  requires std::same_as<std::remove_const_t<Record>, EncounterRecord>
void visit_fields(Record& r, Visit&& visit) {
  visit("name", r.encounter.name, "", "encounter name");
  visit("perturber_mass", r.encounter.perturber_mass, "M", "M2");
  visit("pericenter", r.encounter.pericenter, "R", "q");
  visit("pericenter_speed", r.encounter.pericenter_speed, "sqrt(GM/R)", "V_q");
  visit("after", r.encounter.after, "", "the encounter this one began from (\"\": the relaxed body)");
  visit("inclination", r.orbit.inclination, "deg", "i of the orbit in the body's frame");
  visit("ascending_node", r.orbit.ascending_node, "deg", "Omega of the orbit");
  visit("argument_of_pericenter", r.orbit.argument_of_pericenter, "deg", "omega of the orbit");
  visit("failure_strain", r.failure_strain, "1", "eps_S");
  visit("failed_stiffness_factor", r.failed_stiffness_factor, "1", "F_Sk");
  visit("damping", r.damping, "1/t_grav", "gamma");
  visit_failure_rule(r.failure_rule, visit);  // fail_interval, failure_rule, relaxation_steps, exclusion_distance, shadow_distance,
                                              // flaw_length, growth_strain_factor
  visit("sample_interval", r.sample_interval, "steps", "between timeseries samples");
  visit("start_distance", r.start_distance, "R", "perturber distance at the start");
  visit("end_distance", r.end_distance, "R", "perturber distance at the end");
  visit("pericenter_time", r.pericenter_time, "t_grav", "analytic time of pericenter");
  visit("pericenter_step", r.pericenter_step, "step", "step nearest the analytic pericenter");
  visit("snapshot_steps", r.snapshot_steps, "step", "steps of the snapshot files");
  visit("min_distance", r.min_distance, "R", "closest approach measured");
  visit("speed_at_min", r.speed_at_min, "sqrt(GM/R)", "relative speed at the closest approach");
  visit("time_of_min", r.time_of_min, "t_grav", "time of the closest approach");
  visit("step_of_min", r.step_of_min, "step", "step of the closest approach");
  visit("damping_dissipated", r.energy.damping_dissipated, "G M^2/R", "work done against spring damping so far");
  visit("failure_released", r.energy.failure_released, "G M^2/R", "elastic energy removed by failures so far");
  visit("hinge_residual_work", r.energy.hinge_residual_work, "G M^2/R",
        "hinge work not accounted for by the hinge energy so far");
}

/// The record of whichever stage wrote a checkpoint; the alternative IS the stage.
using StageRecord = std::variant<BuildRecord, StretchRecord, RelaxRecord, EncounterRecord>;

/// The stages in pipeline order: the alternatives of StageRecord, named by stage_names. What each
/// one does and how it is run is its row in stages/stage_kinds.cpp.
enum class StageId : std::uint8_t { build, stretch, relax, encounter };

/// "build", "stretch", "relax" or "encounter", in pipeline order (the variant's order).
inline constexpr const char* stage_names[] = {"build", "stretch", "relax", "encounter"};
inline constexpr std::size_t stage_count = std::size(stage_names);
static_assert(stage_count == std::variant_size_v<StageRecord>, "one name and one StageId per stage record");
static_assert(static_cast<std::size_t>(StageId::encounter) + 1 == stage_count, "StageId lists every stage");

/// The stage name of a record.
inline const char* stage_name(const StageRecord& record) { return stage_names[record.index()]; }
inline const char* stage_name(StageId id) { return stage_names[static_cast<std::size_t>(id)]; }
/// The stage of a record.
inline StageId stage_id(const StageRecord& record) { return static_cast<StageId>(record.index()); }

/// A set of stages: the stages whose results a configuration key changes (model/config.cpp),
/// the stages a stage may begin from (stages/stage_kinds.cpp).
class StageSet {
 public:
  constexpr StageSet() = default;
  constexpr StageSet(std::initializer_list<StageId> stages) {
    for (StageId s : stages) bits_ |= bit(s);
  }
  constexpr bool contains(StageId s) const { return (bits_ & bit(s)) != 0; }
  constexpr bool empty() const { return bits_ == 0; }
  constexpr StageSet operator|(StageSet other) const { return from_bits(bits_ | other.bits_); }
  constexpr bool operator==(const StageSet&) const = default;

 private:
  static constexpr std::uint32_t bit(StageId s) { return std::uint32_t{1} << static_cast<unsigned>(s); }
  static constexpr StageSet from_bits(std::uint32_t bits) {
    StageSet s;
    s.bits_ = bits;
    return s;
  }
  std::uint32_t bits_ = 0;
};

/// The names of the stages in `stages`, in pipeline order, joined by `separator` ("" if none).
std::string stage_list(StageSet stages, const char* separator = ", ");

/// The encounter a record runs (the `encounter` member of a per-encounter stage's record), or null.
inline const Encounter* record_encounter(const StageRecord& record) {
  return std::visit(
      [](const auto& r) -> const Encounter* {
        if constexpr (requires { r.encounter; }) return &r.encounter;
        else return nullptr;
      },
      record);
}

/// An empty record of the named stage; false if `name` is not a stage.
bool make_stage_record(const std::string& name, StageRecord& record);

}  // namespace tidalcrust
