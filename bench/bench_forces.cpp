// Micro-benchmarks of each force kernel, of the energies and of a full step on the paper-T body.
// Run: build/tidalcrust_microbench (from the source folder), --benchmark_filter=Gravity etc.
#include <benchmark/benchmark.h>

#include "bench_body.hpp"
#include "forces/force_field.hpp"
#include "integrate/leapfrog.hpp"
#include "integrate/textbook_step.hpp"

using namespace tidalcrust;
using tidalcrust::bench::paper_t_body;

namespace {

void set_counters(benchmark::State& run, std::size_t items) {
  run.SetItemsProcessed(static_cast<std::int64_t>(run.iterations() * items));
}

}  // namespace

static void BM_Springs(benchmark::State& run) {
  const Checkpoint& c = paper_t_body();
  ForceField forces(c.body, bench::damped());
  for (auto _ : run) {
    forces.compute_spring_forces(c.state.position.data(), c.state.velocity.data(), c.state.springs);
    benchmark::DoNotOptimize(forces.spring_forces().data());
  }
  set_counters(run, c.body.spring_count());
}
BENCHMARK(BM_Springs)->Unit(benchmark::kMicrosecond)->UseRealTime();

static void BM_Hinges(benchmark::State& run) {
  const Checkpoint& c = paper_t_body();
  ForceField forces(c.body, bench::damped());
  for (auto _ : run) {
    benchmark::DoNotOptimize(forces.compute_hinge_forces(c.state.position.data(), c.state.hinges));
  }
  set_counters(run, c.body.hinge_count());
}
BENCHMARK(BM_Hinges)->Unit(benchmark::kMicrosecond)->UseRealTime();

static void BM_Gravity(benchmark::State& run) {
  const Checkpoint& c = paper_t_body();
  DirectGravity gravity(c.body.mass, c.body.softening);
  std::vector<double> a(c.state.position.size());
  for (auto _ : run) {
    gravity.accelerations(c.state.position.data(), a.data());
    benchmark::DoNotOptimize(a.data());
  }
  const std::size_t n = c.body.particle_count();
  set_counters(run, n * (n - 1) / 2);  // pairs
}
BENCHMARK(BM_Gravity)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_Energies(benchmark::State& run) {
  // One thread, O(N^2) for self-gravity: the price of one energy-budget sample.
  const Checkpoint& c = paper_t_body();
  ForceField forces(c.body);
  for (auto _ : run) benchmark::DoNotOptimize(forces.energies(c.state).potential());
  set_counters(run, c.body.particle_count());
}
BENCHMARK(BM_Energies)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_FullStep(benchmark::State& run) {
  const Checkpoint& c = paper_t_body();
  ForceField forces(c.body, bench::damped());
  State state = c.state;
  Leapfrog leapfrog(forces, c.stage.clock);
  for (auto _ : run) leapfrog.step(state);
  set_counters(run, c.body.particle_count());
}
BENCHMARK(BM_FullStep)->Unit(benchmark::kMillisecond)->UseRealTime();

static void BM_TextbookStep(benchmark::State& run) {
  const Checkpoint& c = paper_t_body();
  TextbookStep textbook(c.body, c.state, bench::damped());
  for (auto _ : run) textbook.step(c.state.springs, c.state.hinges, c.stage.clock.dt);
  set_counters(run, c.body.particle_count());
}
BENCHMARK(BM_TextbookStep)->Unit(benchmark::kMillisecond)->UseRealTime();
