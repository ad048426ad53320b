#pragma once
// The restart-driven workflow behind `tidalcrust run`: one body chain (build, stretch, relax)
// shared by all encounters, each encounter and its analysis in a folder of its own. Rerunning
// after an interruption continues from the newest valid checkpoint; finished stages whose
// fingerprint (model/stage_fingerprint.hpp) and parent match are reused; a changed value reruns
// exactly the stages it affects. Output layout: checkpoints/README.md.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

struct WorkflowOptions {
  std::filesystem::path root;       ///< output folder (body/, one folder per encounter, status.json)
  double dt_factor = 1.0;           ///< encounters run at dt * dt_factor into root/dt<factor>/ when != 1
  std::vector<Encounter> encounters;///< the encounters to run (all of the workflow, or --only)
  bool quiet = false;               ///< no progress lines
  /// Step on from checkpoints computed by another gravity kernel (recorded in the checkpoint);
  /// without it that is refused (stages/gravity_kernel_check.hpp).
  bool allow_kernel_change = false;
};

/// One finished encounter of a workflow.
struct WorkflowEncounter {
  std::string name;
  std::filesystem::path checkpoint;  ///< its encounter.h5
  std::filesystem::path analysis;    ///< its analysis folder
  std::string summary;               ///< one line of fracture statistics (analysis_stage.hpp)
  std::string warning;               ///< failures still rising at the end (failure_trend_line), or ""
};

struct WorkflowResult {
  bool interrupted = false;          ///< stopped by SIGINT/SIGTERM; mid-stage checkpoints written
  std::optional<RelaxRecord> relaxed;///< the relaxed body's record (stability probe), when reached
  std::vector<WorkflowEncounter> encounters;
};

/// root/body/encounters-checked: the state_hash of the relaxed body against which `run` last
/// checked every encounter folder of `root` for ones branched from another body (and removed
/// those); a run on the same relaxed body does not check them again.
std::filesystem::path superseded_check_file(const std::filesystem::path& root);

/// Refuses an output folder whose body/build.h5 (`build_file`) holds another body than `config`
/// builds: InputError naming the file and the first difference. Nothing when the file is absent.
void check_same_body(const std::filesystem::path& build_file, const Config& config);

/// The configuration as the body chain's StageKind::prepare steps leave it (the relax's time
/// step, chosen from the stretched body when integrator.dt is not given), from the body
/// checkpoints `run` wrote in root/body: what the encounters of run_workflow were computed with,
/// so that `report` judges them as run does. Stops at the first body checkpoint that is missing
/// (nothing run yet); InputError naming one that cannot be read.
Config body_chain_config(const Config& config, const std::filesystem::path& root);

/// Runs (or resumes) the workflow of `config`, which must be validated. InputError before
/// anything is written if root holds checkpoints of another body; SimulationError on a blow-up
/// (with a diagnostic checkpoint beside the stage's file).
WorkflowResult run_workflow(const Config& config, const WorkflowOptions& options);

}  // namespace tidalcrust
