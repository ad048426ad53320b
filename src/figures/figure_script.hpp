#pragma once
// The figures are drawn by the Python package (python/tidalcrust/figures.py, matplotlib and
// cartopy) from the data files the C++ side writes (summary.json, cracks.json, figure_data.json,
// report/, validate/): this runs it as a child process, `PYTHON -m tidalcrust.figures KIND
// FOLDER`. The numbers never depend on it: every caller writes its data files first.
#include <filesystem>
#include <string>
#include <vector>

namespace tidalcrust {

/// The interpreter that draws the figures: $TIDALCRUST_PYTHON if set and not empty (a path, or a
/// bare name looked up on PATH), else /usr/bin/python3 (Debian's, which has python3-matplotlib
/// and python3-cartopy).
std::filesystem::path figure_python();

/// The folder holding the package `tidalcrust` that the child imports: the installed one
/// (<prefix>/<python site>/tidalcrust beside <prefix>/bin/tidalcrust after `make install`) if
/// this executable is installed, else the source tree's python/ (the build's compile definition).
std::filesystem::path figure_package_dir();

/// Runs `figure_python() -m tidalcrust.figures kind args...` with figure_package_dir() first on
/// PYTHONPATH and MPLBACKEND=Agg, and waits for it. InputError (exit 2), one line, when the
/// interpreter cannot be started ("...: no such interpreter (set TIDALCRUST_PYTHON)") or the script
/// fails (its exit status and the last line it wrote on stderr, e.g. a missing module). Files
/// already written are left as they are.
void draw_figures(const std::string& kind, const std::vector<std::string>& args);

}  // namespace tidalcrust
