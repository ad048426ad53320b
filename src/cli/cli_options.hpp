#pragma once
// Options shared by the stage commands: --config, --set, --threads, --dt-factor, and the gravity
// kernel's --gravity-kernel and --allow-kernel-change (also on `run`).
#include <cxxopts.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "model/config.hpp"

namespace tidalcrust {

/// --gravity-kernel K (sets [gravity] kernel, also when resuming) and --allow-kernel-change (a
/// stage may step on from a checkpoint computed by another kernel: stages/gravity_kernel_check.hpp).
struct KernelOptions {
  std::optional<std::string> gravity_kernel;
  bool allow_change = false;
  /// Sets config.gravity.kernel when --gravity-kernel was given; InputError for an unknown name.
  void apply(Config& config) const;
};

void add_kernel_options(cxxopts::Options& options);
KernelOptions read_kernel_options(const cxxopts::ParseResult& parsed);

struct CommonOptions {
  std::optional<std::filesystem::path> config_file;  ///< --config replaces the stored config
  std::vector<std::string> overrides;                ///< --set section.key=value
  int threads = 0;                                   ///< 0: OpenMP default
  double dt_factor = 1.0;                            ///< scales integrator.dt
  KernelOptions kernel;                              ///< --gravity-kernel, --allow-kernel-change
};

void add_common_options(cxxopts::Options& options);
CommonOptions read_common_options(const cxxopts::ParseResult& parsed);

/// The workflow of `run` and `report`: WORKFLOW.toml (positional "workflow") with each --set
/// applied and validated, --dt-factor checked, and the output root (--out, default
/// checkpoints/<workflow name>). InputError when WORKFLOW.toml is missing or any value is bad.
struct WorkflowArguments {
  std::filesystem::path file;
  Config config;
  std::vector<std::string> overrides;  ///< the --set assignments, as given
  double dt_factor = 1.0;
  std::filesystem::path root;
};
WorkflowArguments read_workflow_arguments(const cxxopts::ParseResult& parsed);

/// cxxopts 3.1 only accepts long options of two or more letters; the CLI has --q (encounter).
/// Rewrites "--x" to "-x" and "--x=V" to "-x" "V" for single-letter options (up to a "--").
std::vector<std::string> spell_single_letter_long_options(int argc, char** argv);

/// Parses argv, turning cxxopts errors (unknown option, missing value) and stray arguments
/// into InputError.
/// Single-letter options are accepted as --x (see spell_single_letter_long_options).
cxxopts::ParseResult parse_arguments(cxxopts::Options& options, int argc, char** argv);

/// The longest --out accepted (bytes): the files below it must stay within PATH_MAX (4096).
inline constexpr std::size_t max_output_path_bytes = 3000;

/// InputError naming `option` unless `text` can name an output folder or file: not empty, no
/// control characters, at most max_output_path_bytes and each part at most max_path_name_bytes
/// (model/config.hpp). Relative parts ("..") and any other characters are the user's choice of
/// place. parse_arguments applies it to every --out.
void check_output_path(const std::string& text, const std::string& option);

/// The configuration of the positional "workflow" file of `parsed` (a TOML workflow) with each
/// --set applied and every range checked, as `run` and `validate` read it. InputError when the
/// file is not given, unreadable or bad.
Config workflow_config(const cxxopts::ParseResult& parsed);

/// The configuration a stage runs with: `stored` (TOML text from the input checkpoint),
/// replaced by --config when given, then each --set applied, then --dt-factor and --gravity-kernel.
Config resolve_config(const std::string& stored_toml, const std::string& stored_origin,
                      const CommonOptions& common);

/// Largest --threads accepted: results never depend on the count, more threads than cores only
/// wait on each other, and an OpenMP runtime asked for tens of thousands crashes.
inline constexpr int max_threads = 256;

/// `threads` if it is in [0, max_threads] (0: the OpenMP default); InputError naming --threads
/// otherwise.
int checked_thread_count(int threads);

/// Sets the OpenMP thread count (0 leaves the default). Results never depend on it.
void apply_thread_count(int threads);

/// Peak resident memory so far, MB (getrusage ru_maxrss, which Linux gives in KiB): of this
/// process, or with `include_children` the larger of it and the largest finished child process
/// (`run --jobs` runs its encounters in children).
double peak_memory_mb(bool include_children = false);

}  // namespace tidalcrust
