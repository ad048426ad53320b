#pragma once
// Atomic file replacement: write a temporary beside the file, fsync it, rename(2) it over the
// file, fsync the folder. A reader (or a crash) sees the old complete file or the new complete
// file, never half of one. Used for checkpoints, their XDMF sidecars, status.json, figures and
// the analysis summary: every file the program writes.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace tidalcrust {

/// The temporary of `file` for this process: `file` + ".tmp-<pid>.<host>", in the same folder
/// (rename is atomic only within one file system).
std::filesystem::path temporary_path(const std::filesystem::path& file);

/// Replaces `file` with what `write_to(fd, temporary)` writes to the open temporary `fd`
/// (temporary_path; closed and fsynced here). The temporary is created new (O_CREAT|O_EXCL|
/// O_NOFOLLOW): a symbolic link or any other file planted under its name is never written
/// through (InputError naming it; a leftover regular file of an earlier process with this pid
/// is replaced). Before the first write of `file` in this process, the temporaries of `file`
/// left by processes of this host that no longer run (killed mid-write) are removed
/// (remove_stale_temporaries; stages/run_stage.cpp removes those of a stage's files when it
/// takes the stage's lock). On any failure the temporary is removed, `file` is left as it
/// was, and the exception propagates: an exception of `write_to` as it is, a failed create,
/// fsync or rename as an InputError naming the file and the strerror text.
void replace_file_atomically(const std::filesystem::path& file,
                             const std::function<void(int fd, const std::filesystem::path&)>& write_to);

/// replace_file_atomically with `text` as the whole content. A failed write is an InputError
/// naming the file and the strerror text.
void write_file_atomically(const std::filesystem::path& file, std::string_view text);

/// Removes the temporaries (`<name>.tmp-<pid>[.<host>]`) in `folder` whose name begins with
/// `prefix` and whose writer is known to be gone: a process of this host (or of no recorded host)
/// that no longer runs, killed mid-write. Those of live processes and of other hosts stay.
/// `prefix` "relax." covers relax.h5, relax.mid.h5, relax.xdmf ...; "" the whole folder; the
/// temporaries of one file are those of prefix `<file name>.tmp-`. Returns how many were
/// removed; errors (a missing folder) are ignored.
int remove_stale_temporaries(const std::filesystem::path& folder, std::string_view prefix);

}  // namespace tidalcrust
