#pragma once
// Atomic file replacement: write a temporary beside the file, fsync it, rename(2) it over the
// file, fsync the folder. A reader (or a crash) sees the old complete file or the new complete
// file, never half of one. Used for checkpoints, their XDMF sidecars, status.json and the
// analysis summary.
#include <filesystem>
#include <functional>
#include <string_view>

namespace tidalcrust {

/// Replaces `file` with what `write_to(temporary)` writes. The temporary is `file` + ".tmp-<pid>"
/// in the same folder (rename is atomic only within one file system). On any failure the
/// temporary is removed, `file` is left as it was, and the exception propagates: an exception of
/// `write_to` as it is, a failed fsync or rename as an InputError naming the file and the
/// strerror text.
void replace_file_atomically(const std::filesystem::path& file,
                             const std::function<void(const std::filesystem::path&)>& write_to);

/// replace_file_atomically with `text` as the whole content. A failed open or write is an
/// InputError naming the file and the strerror text.
void write_file_atomically(const std::filesystem::path& file, std::string_view text);

}  // namespace tidalcrust
