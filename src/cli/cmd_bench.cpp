// tidalcrust bench: time full integration steps (all forces) of the configured body, with the
// configured gravity kernel and the other one (fast and portable), and in the same run the
// textbook step at the same N, so the speed-up is measured under the same machine load. With
// [gravity] method = "tree" also the direct sum at the same N (full step and gravity alone) and
// the tree's force error against it; `--random N` times gravity alone on N random points in a
// sphere. Peak memory is the process's getrusage ru_maxrss.
#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cxxopts.hpp>
#include <string>
#include <vector>

#include "stages/build_stage.hpp"
#include "stages/time_step.hpp"
#include "cli/cli_options.hpp"
#include "cli/commands.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "forces/gravity.hpp"
#include "forces/tree_gravity.hpp"
#include "base/random.hpp"
#include "io/json.hpp"
#include "integrate/leapfrog.hpp"
#include "integrate/textbook_step.hpp"

namespace tidalcrust {
namespace {

constexpr const char* default_workflow = "workflows/paper-T.toml";

using Clock = std::chrono::steady_clock;

double milliseconds_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// Median over `repeats` of the mean milliseconds per call of `run(calls)`.
template <typename Run>
double median_ms_per_call(int repeats, std::int64_t calls, Run&& run) {
  std::vector<double> samples;
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    run(calls);
    samples.push_back(milliseconds_since(start) / static_cast<double>(calls));
  }
  return median(samples);
}

Json error_json(const ForceErrorStats& e) {
  return {{"median", e.median}, {"p99", e.p99}, {"max", e.max}, {"particles", e.particles}};
}

std::string error_text(const ForceErrorStats& e) {
  return fmt::format("median {:.2e}, p99 {:.2e}, max {:.2e} over {} particles", e.median, e.p99, e.max, e.particles);
}

/// Exact accelerations of every `stride`-th particle (plain sqrt and division, each row summed in
/// index order), for the error of a method at an N too large for a full direct sum.
std::vector<double> sampled_direct_rows(const std::vector<double>& mass, double softening, const double* x,
                                        std::size_t stride) {
  const std::size_t n = mass.size(), rows = (n + stride - 1) / stride;
  const double eps2 = softening * softening;
  std::vector<double> a(3 * rows, 0.0);
#pragma omp parallel for schedule(dynamic, 8)
  for (std::size_t r = 0; r < rows; ++r) {
    const std::size_t i = r * stride;
    double sum[3] = {0, 0, 0};
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i) continue;
      const double d[3] = {x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2]};
      const double f = mass[j] * plummer_inverse_cube(d[0] * d[0] + d[1] * d[1] + d[2] * d[2], eps2);
      for (int k = 0; k < 3; ++k) sum[k] += f * d[k];
    }
    for (int k = 0; k < 3; ++k) a[3 * r + k] = sum[k];
  }
  return a;
}

/// `tidalcrust bench --random N`: gravity alone on N points uniform in the unit sphere (equal
/// masses 1/N, softening 1e-3), tree against direct. The direct sum is timed on the first
/// `direct_subset` points and scaled by (N/subset)^2 when N is larger (O(N^2) exactly); the error
/// is measured on every stride-th particle against sampled_direct_rows when N > 65536.
int bench_random(std::int64_t count, const Config& config, int repeats, bool json_output) {
  const auto n = static_cast<std::size_t>(count);
  constexpr std::size_t direct_subset = 65536, error_rows = 4096;
  constexpr double softening = 1e-3;
  Random random(12345);
  std::vector<double> mass(n, 1.0 / static_cast<double>(n)), x;
  x.reserve(3 * n);
  while (x.size() < 3 * n) {
    const double p[3] = {random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)};
    if (p[0] * p[0] + p[1] * p[1] + p[2] * p[2] <= 1) x.insert(x.end(), p, p + 3);
  }
  TreeGravity tree(mass, softening, config.gravity.force_error, config.gravity.kernel);
  std::vector<double> a_tree(3 * n);
  tree.accelerations(x.data(), a_tree.data());  // warm-up
  const double tree_ms =
      median_ms_per_call(repeats, 1, [&](std::int64_t) { tree.accelerations(x.data(), a_tree.data()); });
  const double tree_peak_mb = peak_memory_mb();

  const std::size_t timed = std::min(n, direct_subset);
  const std::vector<double> subset_mass(mass.begin(), mass.begin() + static_cast<std::ptrdiff_t>(timed));
  DirectGravity direct(subset_mass, softening, config.gravity.kernel);
  std::vector<double> a_direct(3 * timed);
  const double subset_ms = median_ms_per_call(1, 1, [&](std::int64_t) { direct.accelerations(x.data(), a_direct.data()); });
  const double scale = static_cast<double>(n) / static_cast<double>(timed);
  const double direct_ms = subset_ms * scale * scale;

  ForceErrorStats error;
  if (timed == n) {
    error = relative_force_errors(a_tree, a_direct);
  } else {
    const std::size_t stride = (n + error_rows - 1) / error_rows;
    const std::vector<double> reference = sampled_direct_rows(mass, softening, x.data(), stride);
    std::vector<double> sampled;
    for (std::size_t i = 0; i < n; i += stride) sampled.insert(sampled.end(), &a_tree[3 * i], &a_tree[3 * i] + 3);
    error = relative_force_errors(sampled, reference);
  }
  const std::string direct_note =
      timed == n ? "one evaluation"
                 : fmt::format("timed on the first {} points, scaled by (N/{})^2", timed, timed);
  if (json_output) {
    const Json json = {{"random_points", n},
                       {"threads", omp_get_max_threads()},
                       {"force_error_target", config.gravity.force_error},
                       {"opening_angle", tree.opening_angle()},
                       {"gravity_kernel", gravity_kernel_label(config.gravity.kernel)},
                       {"tree_gravity_ms", tree_ms},
                       {"direct_gravity_ms", direct_ms},
                       {"direct_gravity_note", direct_note},
                       {"speedup", direct_ms / tree_ms},
                       {"force_error", error_json(error)},
                       {"peak_memory_mb_tree", tree_peak_mb},
                       {"peak_memory_mb", peak_memory_mb()}};
    fmt::print("{}", json_text(json));
  } else {
    fmt::print("random points in a sphere: {}  threads: {}  kernel: {}\n", n, omp_get_max_threads(),
               gravity_kernel_label(config.gravity.kernel));
    fmt::print("gravity alone: tree {:.1f} ms (theta {:.3f} for force_error {:g}), direct {:.1f} ms ({}), "
               "speedup {:.1f}\n",
               tree_ms, tree.opening_angle(), config.gravity.force_error, direct_ms, direct_note, direct_ms / tree_ms);
    fmt::print("tree force error against direct: {}\n", error_text(error));
    fmt::print("peak memory: {:.0f} MB after the tree, {:.0f} MB in all\n", tree_peak_mb, peak_memory_mb());
  }
  return exit_ok;
}

}  // namespace

int command_bench(int argc, char** argv) {
  cxxopts::Options options =
      command_options("bench", "All forces (springs, hinges, gravity, perturber) of the body built from --config "
                               "(default workflows/paper-T.toml, relative to the current folder).");
  add_common_options(options);
  options.add_options("bench")
      ("steps", "steps per timed repeat", cxxopts::value<std::int64_t>()->default_value("20"))
      ("repeats", "timed repeats (the median is reported)", cxxopts::value<int>()->default_value("5"))
      ("textbook-steps", "steps per repeat of the textbook step (0: skip it)",
       cxxopts::value<std::int64_t>()->default_value("3"))
      ("direct-steps", "with [gravity] method = \"tree\": steps of the direct-sum step timed at the same N",
       cxxopts::value<std::int64_t>()->default_value("2"))
      ("random", "time gravity alone on this many random points in a sphere (tree and direct) instead",
       cxxopts::value<std::int64_t>()->default_value("0"))
      ("json", "print one JSON object");
  const auto parsed = parse_arguments(options, argc, argv);
  if (parsed.count("help")) {
    fmt::print("{}\n", options.help());
    return exit_ok;
  }
  CommonOptions common = read_common_options(parsed);
  if (!common.config_file) common.config_file = default_workflow;
  const std::int64_t steps = parsed["steps"].as<std::int64_t>();
  const int repeats = parsed["repeats"].as<int>();
  const std::int64_t textbook_steps = parsed["textbook-steps"].as<std::int64_t>();
  if (steps < 1) throw InputError(fmt::format("--steps must be >= 1, got {}", steps));
  if (repeats < 1) throw InputError(fmt::format("--repeats must be >= 1, got {}", repeats));
  if (textbook_steps < 0) throw InputError(fmt::format("--textbook-steps must be >= 0, got {}", textbook_steps));
  const std::int64_t direct_steps = parsed["direct-steps"].as<std::int64_t>();
  const std::int64_t random_points = parsed["random"].as<std::int64_t>();
  if (direct_steps < 1) throw InputError(fmt::format("--direct-steps must be >= 1, got {}", direct_steps));
  if (random_points < 0 || random_points > 100'000'000)
    throw InputError(fmt::format("--random must be in [0, 100000000], got {}", random_points));
  Config config = resolve_config("", "", common);
  apply_thread_count(common.threads);
  if (random_points > 0) return bench_random(random_points, config, repeats, parsed.count("json") > 0);

  const auto build_start = Clock::now();
  Checkpoint body = build_stage(config);
  const double build_ms = milliseconds_since(build_start);
  if (config.choose_dt) {  // a [material] body without dt: the step `run` would choose (docs/material.md)
    settle_time_step(config, body, "bench");
    body.stage.clock.dt = config.integrator.dt;
  }
  State& state = body.state;
  // Every force path switched on: encounter damping and a perturber at the start distance.
  state.perturber.present = true;
  state.perturber.mass = config.encounters.empty() ? 0.5 : config.encounters.front().perturber_mass;
  state.perturber.position = {config.encounter.start_distance, 0.0, 0.0};
  state.perturber.velocity = {0.0, 1.0, 0.0};

  ForceField forces(body.body, force_options(config, config.encounter.damping));
  State run = state;
  Leapfrog leapfrog(forces, body.stage.clock);
  leapfrog.advance(run, 2);  // warm-up: caches, thread pool
  const double ms_per_step = median_ms_per_call(repeats, steps, [&](std::int64_t n) { leapfrog.advance(run, n); });

  // The same steps with the other gravity kernel, for the cost of the portable one.
  const GravityKernel kernel = config.gravity.kernel;
  const GravityKernel other = kernel == GravityKernel::fast ? GravityKernel::portable : GravityKernel::fast;
  ForceOptions other_options = force_options(config, config.encounter.damping);
  other_options.gravity_kernel = other;
  ForceField other_forces(body.body, other_options);
  State other_run = state;
  Leapfrog other_leapfrog(other_forces, body.stage.clock);
  other_leapfrog.advance(other_run, 2);
  const double other_ms =
      median_ms_per_call(repeats, steps, [&](std::int64_t n) { other_leapfrog.advance(other_run, n); });
  const double fast_ms = kernel == GravityKernel::fast ? ms_per_step : other_ms;
  const double portable_ms = kernel == GravityKernel::portable ? ms_per_step : other_ms;

  // The kernels one by one, for the breakdown.
  Accelerations scratch;
  std::vector<double> gravity(state.position.size());
  const double* x = state.position.data();
  const double* v = state.velocity.data();
  const double springs_ms = median_ms_per_call(repeats, steps, [&](std::int64_t n) {
    for (std::int64_t i = 0; i < n; ++i) forces.compute_spring_forces(x, v, state.springs);
  });
  const double hinges_ms = median_ms_per_call(repeats, steps, [&](std::int64_t n) {
    for (std::int64_t i = 0; i < n; ++i) forces.compute_hinge_forces(x, state.hinges);
  });
  const double gravity_ms = median_ms_per_call(repeats, steps, [&](std::int64_t n) {
    for (std::int64_t i = 0; i < n; ++i) forces.compute_gravity(x, gravity.data());
  });

  double textbook_ms = 0;
  if (textbook_steps > 0) {
    TextbookStep textbook(body.body, state, force_options(config, config.encounter.damping));
    textbook_ms = median_ms_per_call(std::min(repeats, 3), textbook_steps, [&](std::int64_t n) {
      for (std::int64_t i = 0; i < n; ++i) textbook.step(state.springs, state.hinges, body.stage.clock.dt);
    });
  }
  const int threads = omp_get_max_threads();
  const double speedup = textbook_ms > 0 ? textbook_ms / ms_per_step : 0.0;
  const double peak_mb = peak_memory_mb();  // before the direct comparison allocates its buffers

  // The tree against the direct sum at the same N, in the same run.
  const bool tree = config.gravity.method == GravityMethod::tree;
  double direct_ms_per_step = 0, direct_gravity_ms = 0;
  ForceErrorStats error;
  if (tree) {
    ForceOptions direct_options = force_options(config, config.encounter.damping);
    direct_options.gravity_method = GravityMethod::direct;
    ForceField direct_forces(body.body, direct_options);
    std::vector<double> direct_gravity(state.position.size());
    direct_gravity_ms = median_ms_per_call(1, 1, [&](std::int64_t) { direct_forces.compute_gravity(x, direct_gravity.data()); });
    error = relative_force_errors(gravity, direct_gravity);  // `gravity`: the tree's, at the same positions
    State direct_run = state;
    Leapfrog direct_leapfrog(direct_forces, body.stage.clock);
    direct_ms_per_step = median_ms_per_call(1, direct_steps, [&](std::int64_t n) { direct_leapfrog.advance(direct_run, n); });
  }

  if (parsed.count("json")) {
    Json json = {
        {"workflow", config.workflow.name},
        {"particles", body.body.particle_count()},
        {"springs", body.body.spring_count()},
        {"hinges", body.body.hinge_count()},
        {"threads", threads},
        {"steps", steps},
        {"repeats", repeats},
        {"ms_per_step", ms_per_step},
        {"gravity_kernel", gravity_kernel_label(kernel)},
        {"fast_ms_per_step", fast_ms},
        {"fast_kernel", gravity_kernel_label(GravityKernel::fast)},
        {"portable_ms_per_step", portable_ms},
        {"portable_over_fast", portable_ms / fast_ms},
        {"kernels_ms", {{"springs", springs_ms}, {"hinges", hinges_ms}, {"gravity", gravity_ms}}},
        {"textbook_ms_per_step", textbook_ms},
        {"textbook", "one thread, array of particle structs, pair loop over half the pairs; same forces "
                     "(springs, hinges, gravity, perturber) and same drift-kick-drift"},
        {"speedup", speedup},
        {"build_ms", build_ms},
        {"gravity_method", std::string(choice_name(config.gravity.method))},
        {"peak_memory_mb", peak_mb}};
    if (tree) {
      json["force_error_target"] = config.gravity.force_error;
      json["direct_ms_per_step"] = direct_ms_per_step;
      json["direct_kernels_ms"] = {{"gravity", direct_gravity_ms}};
      json["speedup_vs_direct"] = direct_ms_per_step / ms_per_step;
      json["gravity_speedup_vs_direct"] = direct_gravity_ms / gravity_ms;
      json["force_error"] = error_json(error);
      json["peak_memory_mb_with_direct"] = peak_memory_mb();
    }
    fmt::print("{}", json_text(json));
  } else {
    fmt::print("workflow: {}\n", config.workflow.name);
    fmt::print("particles: {}\nsprings: {}\nhinges: {}\nthreads: {}\n", body.body.particle_count(),
               body.body.spring_count(), body.body.hinge_count(), threads);
    fmt::print("ms_per_step: {:.3f}  (median of {} x {} steps; springs {:.3f}, hinges {:.3f}, gravity {:.3f})\n",
               ms_per_step, repeats, steps, springs_ms, hinges_ms, gravity_ms);
    fmt::print("gravity kernels: {} {:.3f} ms/step, portable {:.3f} ms/step (x{:.2f}; this run: {})\n",
               gravity_kernel_label(GravityKernel::fast), fast_ms, portable_ms, portable_ms / fast_ms,
               gravity_kernel_label(kernel));
    if (textbook_ms > 0) {
      fmt::print("textbook_ms_per_step: {:.3f}  (one thread, particle structs, half-pair loop; same forces)\n",
                 textbook_ms);
      fmt::print("speedup: {:.2f}\n", speedup);
    }
    fmt::print("gravity: {}{}\npeak_memory: {:.0f} MB\n", choice_name(config.gravity.method),
               tree ? fmt::format(" (force_error {:g})", config.gravity.force_error) : "", peak_mb);
    if (tree) {
      fmt::print("direct_ms_per_step: {:.3f}  ({} steps; gravity alone {:.3f})\n", direct_ms_per_step, direct_steps,
                 direct_gravity_ms);
      fmt::print("speedup_vs_direct: {:.2f} per step, {:.2f} gravity alone\n", direct_ms_per_step / ms_per_step,
                 direct_gravity_ms / gravity_ms);
      fmt::print("force error against direct: {}\n", error_text(error));
    }
  }
  return exit_ok;
}

}  // namespace tidalcrust
