#include "cli/cli_options.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "base/errors.hpp"

namespace tidalcrust {

void add_common_options(cxxopts::Options& options) {
  options.add_options("common")
      ("config", "the workflow TOML (build), or a TOML file that replaces the stored configuration", cxxopts::value<std::string>())
      ("set", "override one value: section.key=value (repeatable)", cxxopts::value<std::vector<std::string>>())
      ("threads", "number of threads (results do not depend on it)", cxxopts::value<int>()->default_value("0"))
      ("dt-factor", "scale the time step by this factor", cxxopts::value<double>()->default_value("1.0"))
      ("h,help", "show this help");
  add_kernel_options(options);
}

void add_kernel_options(cxxopts::Options& options) {
  options.add_options("gravity kernel")
      ("gravity-kernel",
       fmt::format("one of: {} (sets gravity.kernel; portable: the same bits on every x86-64 CPU)",
                   choice_names<GravityKernel>()),
       cxxopts::value<std::string>())
      ("allow-kernel-change", "continue a checkpoint computed by another gravity kernel (recorded in the checkpoint)");
}

KernelOptions read_kernel_options(const cxxopts::ParseResult& parsed) {
  KernelOptions kernel;
  if (parsed.count("gravity-kernel")) kernel.gravity_kernel = parsed["gravity-kernel"].as<std::string>();
  kernel.allow_change = parsed.count("allow-kernel-change") > 0;
  return kernel;
}

void KernelOptions::apply(Config& config) const {
  if (!gravity_kernel) return;
  config.gravity.kernel = parse_choice<GravityKernel>(*gravity_kernel, "--gravity-kernel: gravity.kernel");
}

CommonOptions read_common_options(const cxxopts::ParseResult& parsed) {
  CommonOptions common;
  if (parsed.count("config")) common.config_file = parsed["config"].as<std::string>();
  if (parsed.count("set")) common.overrides = parsed["set"].as<std::vector<std::string>>();
  common.threads = parsed["threads"].as<int>();
  common.dt_factor = parsed["dt-factor"].as<double>();
  common.threads = checked_thread_count(common.threads);
  common.kernel = read_kernel_options(parsed);
  if (!std::isfinite(common.dt_factor) || common.dt_factor <= 0)
    throw InputError(fmt::format("--dt-factor must be a number > 0, got {}", common.dt_factor));
  return common;
}

std::vector<std::string> spell_single_letter_long_options(int argc, char** argv) {
  std::vector<std::string> args(argv, argv + argc);
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "--") break;
    const bool single_letter = arg.size() >= 3 && arg.compare(0, 2, "--") == 0 &&
                               std::isalnum(static_cast<unsigned char>(arg[2])) && (arg.size() == 3 || arg[3] == '=');
    if (!single_letter) continue;
    std::string value = arg.size() > 3 ? arg.substr(4) : "";
    const bool has_value = arg.size() > 3;
    args[i] = std::string("-") + arg[2];
    if (has_value) args.insert(args.begin() + static_cast<std::ptrdiff_t>(++i), value);
  }
  return args;
}

cxxopts::ParseResult parse_arguments(cxxopts::Options& options, int argc, char** argv) {
  const std::vector<std::string> args = spell_single_letter_long_options(argc, argv);
  std::vector<const char*> pointers;
  for (const auto& arg : args) pointers.push_back(arg.c_str());
  cxxopts::ParseResult parsed;
  try {
    parsed = options.parse(static_cast<int>(pointers.size()), pointers.data());
  } catch (const cxxopts::exceptions::incorrect_argument_type& err) {
    // cxxopts names the value only ("Argument 'two' failed to parse"): name the option too.
    const std::string what = err.what();
    const bool fancy = what.find("\u2018") != std::string::npos;  // cxxopts quotes with 'x' on some systems
    const std::string left = fancy ? "\u2018" : "'", right = fancy ? "\u2019" : "'";
    const auto open = what.find(left), close = what.rfind(right);
    const std::string value = open != std::string::npos && close != std::string::npos && close > open
                                  ? what.substr(open + left.size(), close - open - left.size())
                                  : std::string();
    for (std::size_t i = 1; i < args.size() && !value.empty(); ++i) {
      const auto eq = args[i].find('=');
      const bool inline_value = args[i].starts_with("-") && eq != std::string::npos && args[i].substr(eq + 1) == value;
      if (inline_value || (args[i] == value && args[i - 1].starts_with("-")))
        throw InputError(fmt::format("{}: '{}' is not a valid value for {} (see --help)", options.program(), value,
                                     inline_value ? args[i].substr(0, eq) : args[i - 1]));
    }
    throw InputError(fmt::format("{}: {} (see --help)", options.program(), what));
  } catch (const cxxopts::exceptions::exception& err) {
    throw InputError(fmt::format("{}: {} (see --help)", options.program(), err.what()));
  }
  // A stray word is a mistake (a forgotten --from, a misspelt option), never silently ignored.
  if (!parsed.unmatched().empty())
    throw InputError(fmt::format("{}: unexpected argument '{}' (see --help)", options.program(),
                                 parsed.unmatched().front()));
  if (parsed.count("out")) check_output_path(parsed["out"].as<std::string>(), "--out");
  return parsed;
}

void check_output_path(const std::string& text, const std::string& option) {
  if (text.empty()) throw InputError(fmt::format("{} is empty", option));
  for (unsigned char ch : text)
    if (ch < 0x20 || ch == 0x7f)
      throw InputError(fmt::format("{}: the path holds the control character 0x{:02x}", option, ch));
  if (text.size() > max_output_path_bytes)
    throw InputError(fmt::format("{}: the path is {} bytes long (at most {})", option, text.size(), max_output_path_bytes));
  for (const auto& part : std::filesystem::path(text))
    if (part.native().size() > max_path_name_bytes)
      throw InputError(fmt::format("{}: the part '{}...' of {} is {} bytes long (at most {})", option,
                                   part.native().substr(0, 40), text, part.native().size(), max_path_name_bytes));
}

Config workflow_config(const cxxopts::ParseResult& parsed) {
  if (!parsed.count("workflow")) throw InputError("missing WORKFLOW.toml (see --help)");
  Config config = load_config(std::filesystem::path(parsed["workflow"].as<std::string>()));
  if (parsed.count("set"))
    for (const auto& assignment : parsed["set"].as<std::vector<std::string>>()) apply_override(config, assignment);
  validate(config, "--set");
  return config;
}

Config resolve_config(const std::string& stored_toml, const std::string& stored_origin,
                      const CommonOptions& common) {
  Config config = common.config_file ? load_config(*common.config_file)
                                     : parse_config(stored_toml, stored_origin);
  for (const auto& assignment : common.overrides) apply_override(config, assignment);
  if (common.dt_factor != 1.0) scale_time_step(config, common.dt_factor);
  validate(config, "--set/--dt-factor");
  common.kernel.apply(config);
  return config;
}

WorkflowArguments read_workflow_arguments(const cxxopts::ParseResult& parsed) {
  WorkflowArguments w;
  w.config = workflow_config(parsed);
  w.file = parsed["workflow"].as<std::string>();
  if (parsed.count("set")) w.overrides = parsed["set"].as<std::vector<std::string>>();
  w.dt_factor = parsed["dt-factor"].as<double>();
  if (!std::isfinite(w.dt_factor) || w.dt_factor <= 0)
    throw InputError(fmt::format("--dt-factor must be a number > 0, got {}", w.dt_factor));
  w.root = parsed.count("out") ? std::filesystem::path(parsed["out"].as<std::string>())
                               : std::filesystem::path("checkpoints") / w.config.workflow.name;
  return w;
}

int checked_thread_count(int threads) {
  if (threads < 0 || threads > max_threads)
    throw InputError(fmt::format("--threads must be between 0 (the OpenMP default) and {}, got {}", max_threads,
                                 threads));
  return threads;
}

void apply_thread_count(int threads) {
  if (threads > 0) omp_set_num_threads(threads);
}

double peak_memory_mb(bool include_children) {
  rusage self{}, children{};
  getrusage(RUSAGE_SELF, &self);
  long peak = self.ru_maxrss;
  if (include_children && getrusage(RUSAGE_CHILDREN, &children) == 0) peak = std::max(peak, children.ru_maxrss);
  return static_cast<double>(peak) / 1024.0;
}

}  // namespace tidalcrust
