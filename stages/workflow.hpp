#pragma once
// The restart-driven workflow behind `tidalcrust run`: one body chain (build, stretch, relax)
// shared by all encounters, and one more per other body seed the encounters name (body_seed: the
// members of an ensemble that varies the body); each encounter and its analysis in a folder of its
// own. Rerunning after an interruption continues from the newest valid checkpoint; finished stages
// whose fingerprint (model/stage_fingerprint.hpp) and parent match are reused; a changed value
// reruns exactly the stages it affects. Output layout: checkpoints/README.md.
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
  /// The workflow file, named first in the errors of a stage's configuration (StageRunOptions::config_source).
  std::filesystem::path config_file;
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

/// BODY_DIR/encounters-checked: the state_hash of the relaxed body in `body_dir` (root/body or
/// root/body-seed<N>) against which `run` last checked the encounter folders of that body for ones
/// branched from another body (and removed those); a run on the same relaxed body does not check
/// them again.
std::filesystem::path superseded_check_file(const std::filesystem::path& body_dir);

/// Refuses an output folder whose body/build.h5 (`build_file`) holds another body than `config`
/// builds: InputError naming the file and the first difference. Nothing when the file is absent.
void check_same_body(const std::filesystem::path& build_file, const Config& config);

/// The configuration as the body chain's StageKind::prepare steps leave it (the relax's time
/// step, chosen from the stretched body when integrator.dt is not given), from the body
/// checkpoints `run` wrote in the body folder of `encounter` (body_folder: root/body without one):
/// what that encounter of run_workflow was computed with, so that `report` judges it as run does.
/// Its workflow.seed is the body's (body_config_of). Stops at the first body checkpoint that is
/// missing (nothing run yet); InputError naming one that cannot be read.
Config body_chain_config(const Config& config, const std::filesystem::path& root,
                         const Encounter* encounter = nullptr);

/// Runs (or resumes) the workflow of `config`, which must be validated. InputError before
/// anything is written if root holds checkpoints of another body; SimulationError on a blow-up
/// (with a diagnostic checkpoint beside the stage's file).
WorkflowResult run_workflow(const Config& config, const WorkflowOptions& options);

}  // namespace tidalcrust
