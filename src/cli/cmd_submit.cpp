// `tidalcrust submit WORKFLOW.toml --slurm`: the workflow as Slurm jobs. One job computes the
// shared body chain (`run --body-only`); one job array, which starts only after that job
// succeeded (afterok), runs one encounter per task (`run --only NAME`, the names read by task
// index from a file). Requeue-safe: a task that Slurm stops (preemption, `scontrol requeue`,
// SIGTERM 60 s before its time limit) writes its mid-stage checkpoint and exits 130; run again,
// it resumes from it with the same bits. docs/cluster.md describes the use on a cluster.
#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "io/atomic_file.hpp"
#include "io/xxh3_hasher.hpp"
#include "stages/encounter_stage.hpp"
#include "stages/workflow.hpp"

extern char** environ;

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

/// Seconds before its time limit at which Slurm sends a task SIGTERM (`--signal=B:TERM@60`):
/// the encounter stops at the next step and writes its mid-stage checkpoint well within it.
constexpr int stop_lead_seconds = 60;

/// What the scripts need, every path absolute (the jobs run elsewhere, from another folder).
struct Submission {
  fs::path executable;  ///< this tidalcrust
  fs::path workflow;
  fs::path out;         ///< the workflow's output folder (run --out)
  std::string name;     ///< workflow.name
  std::vector<std::string> encounters;
  std::optional<std::string> partition, time, account;
  int cpus_per_task = 1;
  std::optional<int> max_running;
  fs::path folder() const { return out / "slurm"; }
  fs::path logs() const { return folder() / "logs"; }
  /// The names file is named by its content, so that a later submission with other encounters
  /// never changes the list that queued tasks of an earlier one read by index.
  fs::path names_file() const {
    Xxh3Hasher hasher;
    for (const auto& e : encounters) hasher.text(e + '\n');
    return folder() / fmt::format("encounters-{}.txt", hasher.hex().substr(0, 12));
  }
};

/// `text` in single quotes for bash ('\'' for a quote inside).
std::string shell_quoted(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

/// Seconds of a Slurm time limit (minutes, minutes:seconds, hours:minutes:seconds, days-hours,
/// days-hours:minutes, days-hours:minutes:seconds; -1 for infinite or unlimited); InputError
/// naming --time otherwise.
long time_limit_seconds(const std::string& text) {
  if (text == "infinite" || text == "unlimited" || text == "INFINITE" || text == "UNLIMITED") return -1;
  static const std::regex format(R"(^(?:(\d{1,5})-(\d{1,2})(?::(\d{1,2})(?::(\d{1,2}))?)?|(\d{1,7})(?::(\d{1,2})(?::(\d{1,2}))?)?)$)");
  std::smatch m;
  if (!std::regex_match(text, m, format))
    throw InputError(fmt::format(
        "--time '{}' is not a Slurm time limit (MM, MM:SS, HH:MM:SS, D-HH, D-HH:MM, D-HH:MM:SS or unlimited)", text));
  const auto number = [&](int i) { return m[i].matched ? std::stol(m[i].str()) : 0L; };
  long seconds = 0;
  if (m[1].matched)
    seconds = number(1) * 86400 + number(2) * 3600 + number(3) * 60 + number(4);
  else if (m[7].matched)  // H:M:S
    seconds = number(5) * 3600 + number(6) * 60 + number(7);
  else  // M or M:S
    seconds = number(5) * 60 + number(6);
  if (seconds < 2 * stop_lead_seconds)
    throw InputError(fmt::format("--time '{}' is shorter than {} s: a task is told to stop {} s before its limit",
                                 text, 2 * stop_lead_seconds, stop_lead_seconds));
  return seconds;
}

/// The #SBATCH lines both jobs share.
std::string common_directives(const Submission& s) {
  std::string lines = fmt::format("#SBATCH --cpus-per-task={}\n", s.cpus_per_task);
  if (s.partition) lines += fmt::format("#SBATCH --partition={}\n", *s.partition);
  if (s.time) lines += fmt::format("#SBATCH --time={}\n", *s.time);
  if (s.account) lines += fmt::format("#SBATCH --account={}\n", *s.account);
  lines += fmt::format(
      "#SBATCH --requeue\n"
      "#SBATCH --open-mode=append\n"
      "#SBATCH --signal=B:TERM@{}\n",
      stop_lead_seconds);
  return lines;
}

/// `exec tidalcrust run ...`: exec, so that the signals Slurm sends to the batch step reach
/// tidalcrust itself, which stops at a step boundary and writes its checkpoint.
std::string run_line(const Submission& s, const std::string& selection) {
  return fmt::format("exec {} run {} --out {} {} --threads {}\n", shell_quoted(s.executable.string()),
                     shell_quoted(s.workflow.string()), shell_quoted(s.out.string()), selection, s.cpus_per_task);
}

std::string body_script(const Submission& s) {
  return fmt::format(
      "#!/bin/bash\n"
      "# tidalcrust submit: the body chain (build, stretch, relax) of workflow {0}, shared by its encounters.\n"
      "#SBATCH --job-name={0}-body\n"
      "{1}"
      "#SBATCH --output={2}/body-%j.log\n"
      "echo \"tidalcrust body chain: job $SLURM_JOB_ID on $(hostname), restart ${{SLURM_RESTART_COUNT:-0}}, $(date -u +%FT%TZ)\"\n"
      "{3}",
      s.name, common_directives(s), s.logs().string(), run_line(s, "--body-only"));
}

std::string array_script(const Submission& s) {
  const std::string throttle = s.max_running ? fmt::format("%{}", *s.max_running) : "";
  return fmt::format(
      "#!/bin/bash\n"
      "# tidalcrust submit: the {0} encounter{9} of workflow {1}, one per task, named in line\n"
      "# (task index + 1) of {2}.\n"
      "#SBATCH --job-name={1}-encounters\n"
      "#SBATCH --array=0-{3}{4}\n"
      "{5}"
      "#SBATCH --output={6}/encounter-%a.log\n"
      "name=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" {7})\n"
      "if [ -z \"$name\" ]; then echo \"no encounter in line $((SLURM_ARRAY_TASK_ID + 1)) of {2}\" >&2; exit 2; fi\n"
      "echo \"tidalcrust encounter $name: task $SLURM_ARRAY_TASK_ID of job $SLURM_ARRAY_JOB_ID on $(hostname), restart ${{SLURM_RESTART_COUNT:-0}}, $(date -u +%FT%TZ)\"\n"
      "{8}",
      s.encounters.size(), s.name, s.names_file().string(), s.encounters.size() - 1, throttle, common_directives(s),
      s.logs().string(), shell_quoted(s.names_file().string()), run_line(s, "--only \"$name\""),
      s.encounters.size() == 1 ? "" : "s");
}

std::optional<fs::path> find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return std::nullopt;
  std::string dirs = path;
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(end > start ? dirs.substr(start, end - start) : ".") / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = end + 1;
  }
  return std::nullopt;
}

struct Captured {
  int exit_code = -1;
  std::string out, err;
};

std::string read_all(int fd) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buffer, static_cast<size_t>(n));
  }
  ::close(fd);
  return text;
}

/// Runs `argv` (no shell) and captures its output (both small: sbatch prints one line).
Captured run_program(const std::vector<std::string>& argv) {
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0 || ::pipe2(err_pipe, O_CLOEXEC) != 0)
    throw InputError(fmt::format("{}: cannot make a pipe: {}", argv[0], std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  Captured result;
  result.out = read_all(out_pipe[0]);
  result.err = read_all(err_pipe[0]);
  if (spawned != 0) throw InputError(fmt::format("{}: cannot start it: {}", argv[0], std::strerror(spawned)));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string first_line(const std::string& text) {
  const size_t start = text.find_first_not_of(" \n");
  if (start == std::string::npos) return "no message";
  return text.substr(start, text.find('\n', start) - start);
}

/// `sbatch --parsable [extra] SCRIPT`; returns the job id (the part before any ";cluster").
std::string sbatch(const fs::path& program, const std::vector<std::string>& extra, const fs::path& script,
                   const std::string& already_submitted) {
  std::vector<std::string> argv = {program.string(), "--parsable"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  argv.push_back(script.string());
  const Captured result = run_program(argv);
  const std::string id = first_line(result.out).substr(0, first_line(result.out).find(';'));
  if (result.exit_code != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw InputError(fmt::format("sbatch {} failed (exit {}): {}{}", script.string(), result.exit_code,
                                 first_line(result.err + result.out), already_submitted));
  return id;
}

}  // namespace

int command_submit(int argc, char** argv) {
  cxxopts::Options options = command_options("submit");
  options.positional_help("WORKFLOW.toml --slurm");
  options.add_options()("workflow", "workflow TOML file", cxxopts::value<std::string>())(
      "slurm", "submit to Slurm with sbatch (the one batch system supported)")(
      "out", "output root (default checkpoints/<workflow name>); on a file system all nodes share",
      cxxopts::value<std::string>())("partition", "Slurm partition", cxxopts::value<std::string>())(
      "time", "time limit of each job (MM, HH:MM:SS, D-HH:MM, ...; at least 2 minutes)", cxxopts::value<std::string>())(
      "cpus-per-task", "CPUs (and threads) of each job", cxxopts::value<int>()->default_value("1"))(
      "max-running", "at most this many encounter tasks at once (%K)", cxxopts::value<int>())(
      "account", "Slurm account to charge", cxxopts::value<std::string>())(
      "dry-run", "print the scripts and sbatch command lines; write and submit nothing")("h,help", "show this help");
  options.parse_positional({"workflow"});
  auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) return fmt::print("{}\n", options.help()), exit_ok;
  if (!parsed.count("workflow")) throw InputError("missing WORKFLOW.toml (see --help)");
  if (!parsed.count("slurm")) throw InputError("name the batch system: --slurm (the only one supported)");

  // Everything is checked before anything is written or submitted.
  Submission s;
  s.cpus_per_task = parsed["cpus-per-task"].as<int>();
  if (s.cpus_per_task < 1 || s.cpus_per_task > max_threads)
    throw InputError(fmt::format("--cpus-per-task must be in 1..{}, got {}", max_threads, s.cpus_per_task));
  if (parsed.count("max-running")) {
    s.max_running = parsed["max-running"].as<int>();
    if (*s.max_running < 1) throw InputError(fmt::format("--max-running must be at least 1, got {}", *s.max_running));
  }
  if (parsed.count("time")) {
    s.time = parsed["time"].as<std::string>();
    time_limit_seconds(*s.time);
  }
  for (const char* key : {"partition", "account"}) {
    if (!parsed.count(key)) continue;
    const std::string value = parsed[key].as<std::string>();
    if (value.empty() || value.find_first_of(" \t\n'\"\\$`") != std::string::npos)
      throw InputError(fmt::format("--{} '{}' is not a Slurm name", key, value));
    (std::string_view(key) == "partition" ? s.partition : s.account) = value;
  }
  const bool dry_run = parsed.count("dry-run") > 0;
  std::optional<fs::path> sbatch_program = find_on_path("sbatch");
  if (!dry_run && !sbatch_program)
    throw InputError("sbatch is not on PATH (load Slurm's client, e.g. `module load slurm`; --dry-run shows the jobs)");

  const fs::path workflow = parsed["workflow"].as<std::string>();
  const Config config = load_config(workflow);
  if (config.encounters.empty()) throw InputError(fmt::format("{}: the workflow has no encounter", workflow.string()));
  for (const auto& spec : config.encounters) {
    check_encounter(config, spec, workflow.string());
    if (spec.name.find_first_of(" \t\n") != std::string::npos)
      throw InputError(fmt::format("{}: encounter name '{}' has white space", workflow.string(), spec.name));
    s.encounters.push_back(spec.name);
  }
  s.name = config.workflow.name;
  s.workflow = fs::absolute(workflow).lexically_normal();
  s.out = fs::absolute(parsed.count("out") ? fs::path(parsed["out"].as<std::string>())
                                           : fs::path("checkpoints") / config.workflow.name)
              .lexically_normal();
  // A folder of another body would fail the body job and leave the array waiting forever.
  check_same_body(s.out / "body" / "build.h5", config);
  std::error_code ec;
  s.executable = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw InputError(fmt::format("cannot tell this program's path (/proc/self/exe: {})", ec.message()));

  std::string names;
  for (const auto& e : s.encounters) names += e + '\n';
  const fs::path body_file = s.folder() / "body.sbatch", array_file = s.folder() / "encounters.sbatch";
  const std::string array_dependency = "--dependency=afterok:";
  if (dry_run) {
    fmt::print("# tidalcrust submit --dry-run: nothing written, nothing submitted.\n");
    fmt::print("# ==> {} <==\n{}", s.names_file().string(), names);
    fmt::print("# ==> {} <==\n{}", body_file.string(), body_script(s));
    fmt::print("# ==> {} <==\n{}", array_file.string(), array_script(s));
    fmt::print("# the sbatch command lines:\nbody_job=$(sbatch --parsable {})\nsbatch --parsable {}${{body_job%%;*}} {}\n",
               shell_quoted(body_file.string()), array_dependency, shell_quoted(array_file.string()));
    return exit_ok;
  }

  fs::create_directories(s.logs(), ec);
  if (ec) throw InputError(fmt::format("{}: cannot create the folder: {}", s.logs().string(), ec.message()));
  write_file_atomically(s.names_file(), names);
  write_file_atomically(body_file, body_script(s));
  write_file_atomically(array_file, array_script(s));
  const std::string body_job = sbatch(*sbatch_program, {}, body_file, "");
  const std::string array_job =
      sbatch(*sbatch_program, {array_dependency + body_job}, array_file,
             fmt::format(" (the body job {} was submitted: scancel {})", body_job, body_job));
  fmt::print("body chain: job {} (log {}/body-{}.log)\n", body_job, s.logs().string(), body_job);
  fmt::print("encounters: job array {} of {} tasks{} after job {} succeeds (logs {}/encounter-<task>.log; names {})\n",
             array_job, s.encounters.size(),
             s.max_running ? fmt::format(", at most {} at once,", *s.max_running) : std::string(","), body_job,
             s.logs().string(), s.names_file().string());
  fmt::print("watch: squeue -j {},{}; a task's log shows its progress; a failed or time-limited task continues from "
             "its checkpoint after `scontrol requeue {}_<task>` or the same submit command\n",
             body_job, array_job, array_job);
  return exit_ok;
}

}  // namespace tidalcrust
