// tidalcrust bench: time full integration steps (all forces) of the configured body, with the
// configured gravity kernel and the other one (fast and portable), and in the same run the
// textbook step at the same N, so the speed-up is measured under the same machine load.
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

}  // namespace

int command_bench(int argc, char** argv) {
  cxxopts::Options options("tidalcrust bench",
                           "Time full integration steps (springs, hinges, gravity, perturber) of the body built "
                           "from --config (default workflows/paper-T.toml, relative to the current folder), and the "
                           "textbook step at the same N in the same run.");
  add_common_options(options);
  options.add_options("bench")
      ("steps", "steps per timed repeat", cxxopts::value<std::int64_t>()->default_value("20"))
      ("repeats", "timed repeats (the median is reported)", cxxopts::value<int>()->default_value("5"))
      ("textbook-steps", "steps per repeat of the textbook step (0: skip it)",
       cxxopts::value<std::int64_t>()->default_value("3"))
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
  Config config = resolve_config("", "", common);
  apply_thread_count(common.threads);

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
  const GravityKernel kernel = gravity_kernel_of(config);
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

  if (parsed.count("json")) {
    const Json json = {
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
        {"build_ms", build_ms}};
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
  }
  return exit_ok;
}

}  // namespace tidalcrust
