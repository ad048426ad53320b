// Encounter histories (issue 25 item 4, docs/encounter-history.md): an encounter that comes
// `after` another begins from that one's final state, with its failures carried over and the
// perturber on a new orbit (here turned by the orbit's orientation keys); `run` runs the chain,
// resumes it bit for bit after a kill in the second pass, and removes a second pass whose first
// one is gone.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/json.hpp"
#include "io/state_hash.hpp"
#include "physics/orbital_frame.hpp"
#include "stages/encounter_stage.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// The small body, a first pass A in the paper's orbit and a second pass B after it with its
/// pericenter elsewhere (i = 60, Omega = 30, omega = 200 deg: subsatellite point at longitude
/// -139.7, latitude -17.2), a weak crust so that both passes crack it, every step sampled.
fs::path history_workflow(const fs::path& dir, const std::string& relax_damping = "") {
  const auto file = dir / "history.toml";
  std::ofstream(file) << small_body_toml("history", "failure_strain = 0.002\n") << "stability_probe = false\n"
                      << relax_damping << R"([encounter]
failure_rule = "paper"
checkpoint_interval = 40
sample_interval = 1
[[encounters]]
name = "A"
perturber_mass = 0.5
pericenter = 1.5
[[encounters]]
name = "B"
after = "A"
perturber_mass = 0.5
pericenter = 1.5
inclination = 60
ascending_node = 30
argument_of_pericenter = 200
)";
  return file;
}

Json read_json(const fs::path& file) {
  std::ifstream in(file);
  return Json::parse(in);
}

std::set<std::int32_t> failed_shell_springs(const Checkpoint& c) {
  std::set<std::int32_t> out;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s)
    if (c.state.springs.failed[s] && c.body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell))
      out.insert(static_cast<std::int32_t>(s));
  return out;
}

}  // namespace

TEST(EncounterHistory, TheSecondPassBeginsFromTheFirstsFinalStateWithItsFailuresAndItsOwnOrbit) {
  const ScratchFolder scratch("history_chain");
  const auto workflow = history_workflow(scratch.path);
  const auto run = run_cli("run " + quoted(workflow) + " --quiet --out " + quoted(scratch.path / "out"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const Checkpoint a = read_checkpoint(scratch.path / "out" / "A" / "encounter.h5");
  const Checkpoint b = read_checkpoint(scratch.path / "out" / "B" / "encounter.h5");
  EXPECT_EQ(b.stage.parent_hash, state_hash(a.state));
  EXPECT_EQ(b.stage.clock.start_step, a.state.step);
  const auto& record = b.stage.as<EncounterRecord>();
  EXPECT_EQ(record.encounter.after, "A");
  EXPECT_EQ(record.orbit, (OrbitOrientation{60, 30, 200}));
  EXPECT_FALSE(a.stage.as<EncounterRecord>().encounter.after);

  // Failures carried over: every spring A broke is still broken; B's log names only new ones.
  const std::set<std::int32_t> before = failed_shell_springs(a), after = failed_shell_springs(b);
  ASSERT_GT(before.size(), 20u);
  ASSERT_GT(b.observables.failures.size(), 20u);
  for (const std::int32_t s : before) EXPECT_TRUE(after.contains(s)) << s;
  for (const FailureEvent& e : b.observables.failures) EXPECT_FALSE(before.contains(e.spring)) << e.spring;
  EXPECT_EQ(after.size(), before.size() + b.observables.failures.size());

  // The perturber passed the pericenter where the orbit's elements put it (sampled every step; the
  // body's own shape bends the path by far less than the tolerance).
  const Vec3 expected = subsatellite_direction_of(record.orbit);
  const TimeseriesSample* closest = nullptr;
  for (const auto& sample : b.observables.timeseries) {
    const Vec3 offset(sample.perturber_offset[0], sample.perturber_offset[1], sample.perturber_offset[2]);
    if (!closest || offset.norm() < Vec3(closest->perturber_offset[0], closest->perturber_offset[1],
                                         closest->perturber_offset[2]).norm())
      closest = &sample;
  }
  ASSERT_NE(closest, nullptr);
  const Vec3 at_pericenter(closest->perturber_offset[0], closest->perturber_offset[1], closest->perturber_offset[2]);
  EXPECT_LT(std::acos(std::clamp(at_pericenter.normalized().dot(expected), -1.0, 1.0)) * 180 / 3.14159265358979, 1.0);
  EXPECT_NEAR(at_pericenter.norm(), 1.5, 0.01);

  // summary.json: B's statistics are its own failures, the earlier ones counted apart; cracks.json
  // draws them apart, with B's subsatellite point.
  const Json summary = read_json(scratch.path / "out" / "B" / "analysis" / "summary.json");
  EXPECT_EQ(summary["failures"]["count"], b.observables.failures.size());
  EXPECT_EQ(summary["history"]["after"], "A");
  EXPECT_EQ(summary["history"]["earlier_failed"], before.size());
  EXPECT_EQ(summary["history"]["all_failures"]["count"], after.size());
  EXPECT_NEAR(summary["encounter"]["orbit"]["subsatellite_latitude_deg"].get<double>(), latitude_deg(expected), 1e-9);
  EXPECT_TRUE(read_json(scratch.path / "out" / "A" / "analysis" / "summary.json")["history"].is_null());
  const Json cracks = read_json(scratch.path / "out" / "B" / "analysis" / "cracks.json");
  EXPECT_EQ(cracks["earlier"]["springs"].size(), before.size());
  EXPECT_NEAR(cracks["subsatellite"][0].get<double>(), longitude_deg(expected), 1e-9);
  for (const char* figure : {"fracture_map.png", "orbit.png", "hemisphere.png"})
    EXPECT_TRUE(fs::exists(scratch.path / "out" / "B" / "analysis" / figure)) << figure;

  // `run --only B` on a new folder runs A first: the same bits.
  const auto only = run_cli("run " + quoted(workflow) + " --quiet --only B --out " + quoted(scratch.path / "only"));
  ASSERT_EQ(only.exit_code, 0) << only.err;
  EXPECT_EQ(state_hash(read_checkpoint(scratch.path / "only" / "B" / "encounter.h5").state), state_hash(b.state));

  // A rerun reuses both; `report` has both finished, B after A, and draws its phase diagram from A alone.
  const auto again = run_cli("run " + quoted(workflow) + " --out " + quoted(scratch.path / "out"));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_NE(again.out.find("encounter B: up to date"), std::string::npos) << again.out;
  const auto report = run_cli("report " + quoted(workflow) + " --out " + quoted(scratch.path / "out"));
  ASSERT_EQ(report.exit_code, 0) << report.err;
  const Json table = read_json(scratch.path / "out" / "report" / "sweep.json");
  ASSERT_EQ(table["encounters"].size(), 2u);
  EXPECT_EQ(table["counts"]["finished"], 2);
  EXPECT_EQ(table["encounters"][1]["after"], "A");
  EXPECT_EQ(table["encounters"][1]["failures"], b.observables.failures.size());
  EXPECT_TRUE(table["encounters"][0]["after"].is_null());
}

TEST(EncounterHistory, AChainKilledInItsSecondPassResumesBitIdentically) {
  const ScratchFolder scratch("history_kill");
  const auto workflow = history_workflow(scratch.path);
  const auto straight = run_cli("run " + quoted(workflow) + " --quiet --out " + quoted(scratch.path / "straight"));
  ASSERT_EQ(straight.exit_code, 0) << straight.err;
  const std::string expected = state_hash(read_checkpoint(scratch.path / "straight" / "B" / "encounter.h5").state);

  // A first, then the whole chain killed (SIGKILL, io/test_points.hpp) 100 steps into B, past two
  // of its mid-stage checkpoints; the rerun resumes B from its mid-stage checkpoint.
  const fs::path out = scratch.path / "killed";
  ASSERT_EQ(run_cli("run " + quoted(workflow) + " --quiet --only A --out " + quoted(out)).exit_code, 0);
  const auto killed = run_cli("run " + quoted(workflow) + " --out " + quoted(out), "TIDALCRUST_TEST_KILL_AT=step:100");
  EXPECT_NE(killed.exit_code, 0);
  ASSERT_TRUE(fs::exists(out / "B" / "encounter.mid.h5"));
  ASSERT_FALSE(fs::exists(out / "B" / "encounter.h5"));
  const auto resumed = run_cli("run " + quoted(workflow) + " --out " + quoted(out));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("encounter A: up to date"), std::string::npos) << resumed.out;
  EXPECT_NE(resumed.out.find("resum"), std::string::npos) << resumed.out;
  EXPECT_EQ(state_hash(read_checkpoint(out / "B" / "encounter.h5").state), expected);
}

TEST(EncounterHistory, ASecondPassWhoseFirstPassBranchedFromAnotherBodyIsRemoved) {
  const ScratchFolder scratch("history_superseded");
  const fs::path out = scratch.path / "out";
  ASSERT_EQ(run_cli("run " + quoted(history_workflow(scratch.path)) + " --quiet --out " + quoted(out)).exit_code, 0);
  ASSERT_TRUE(fs::exists(out / "B" / "encounter.h5"));
  // Another relaxation, and A alone: A is recomputed, and B (which began from the old A) removed.
  const auto workflow = history_workflow(scratch.path, "damping = 40.0\n");
  const auto rerun = run_cli("run " + quoted(workflow) + " --only A --out " + quoted(out));
  ASSERT_EQ(rerun.exit_code, 0) << rerun.err;
  EXPECT_FALSE(fs::exists(out / "B" / "encounter.h5"));
  EXPECT_FALSE(fs::exists(out / "B" / "analysis"));
  EXPECT_NE(rerun.out.find("B: removed the encounter, which began from another state of A"), std::string::npos)
      << rerun.out;
}

TEST(EncounterHistory, AnEncounterAfterAnotherNeedsItsFinalEncounterCheckpoint) {
  Config config = quick_config();
  Encounter spec = config.encounters.at(0);
  spec.after = "T0";
  try {
    begin_encounter(quick_relaxed(false), config, spec);
    ADD_FAILURE() << "began from a relaxed body";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("comes after 'T0' and starts from its final 'encounter' checkpoint, got a "
                                         "'relax' checkpoint"),
              std::string::npos)
        << e.what();
  }
}
