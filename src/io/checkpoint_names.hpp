#pragma once
// The files kept beside a stage's checkpoint OUT.h5: its mid-stage checkpoint OUT.mid.h5 (periodic
// and SIGINT, the one to resume from), its diagnostic checkpoint OUT.diagnostic.h5 (a blow-up), and
// an encounter's snapshots OUT.snap-<step>.h5 (global step, decimal) for the snapshot row of the
// hemisphere figure (Figure 6).
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include "model/config.hpp"

namespace tidalcrust {

/// The folder of the body chain `encounter` branches from in the output root `root`: root/body
/// for the workflow's own body (no encounter, or one without another body_seed), root/body-seed<N>
/// for the body of seed N (body_seed_of; docs/ensembles.md, "Members on bodies of their own").
std::filesystem::path body_folder(const std::filesystem::path& root, const Config& config,
                                  const Encounter* encounter = nullptr);

/// A file beside `out`: out.h5 -> out.<suffix>.h5 ("mid", "diagnostic").
std::filesystem::path sibling_checkpoint(const std::filesystem::path& out, const std::string& suffix);

/// Removes a checkpoint and its .xdmf sidecar if they exist (a finished stage's mid file).
void remove_checkpoint_files(const std::filesystem::path& file);

/// Removes what an earlier run of a stage left beside its checkpoint `file` once that run is
/// superseded (another fingerprint or parent): `file`, its diagnostic checkpoint and, unless
/// `keep_resume_files` (the stage resumes from its matching mid-stage checkpoint, whose
/// snapshots belong to it), its mid-stage checkpoint and its snapshots; each with its .xdmf.
/// Files in `keep` (e.g. the input of a single-stage command) stay. Missing files are no error.
void remove_stage_outputs(const std::filesystem::path& file, bool keep_resume_files,
                          const std::vector<std::filesystem::path>& keep = {});

inline constexpr std::string_view snapshot_infix = ".snap-";

/// The snapshot file of `checkpoint_file` at global step `step`.
std::filesystem::path snapshot_path(const std::filesystem::path& checkpoint_file, std::int64_t step);

struct SnapshotFile {
  std::int64_t step = 0;
  std::filesystem::path file;
};

/// Snapshot files beside `checkpoint_file`, ascending step (none if the folder is missing).
std::vector<SnapshotFile> find_snapshots(const std::filesystem::path& checkpoint_file);

/// Up to `max_panels` indices into ascending `times` for a row of snapshots: evenly spread
/// over the list, always with the first, the last and (for max_panels >= 3) the one nearest
/// `pericenter_time`.
std::vector<std::size_t> choose_snapshot_panels(const std::vector<double>& times, double pericenter_time,
                                                std::size_t max_panels);

}  // namespace tidalcrust
