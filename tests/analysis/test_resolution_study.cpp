// The table of `compare --resolution` (analysis/resolution_study): shell levels from N_S, rows
// sorted coarsest first with their own fracture statistics, the relative changes, and the checks
// that make the input one encounter at several resolutions.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "analysis/resolution_study.hpp"
#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"
#include "io/state_hash.hpp"
#include "support/files.hpp"
#include "support/synthetic_encounter.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// Fails every `every`-th shell spring of `c` on the subsatellite half (y > 0).
void fail_springs(Checkpoint& c, std::size_t every) {
  for (std::size_t s = 0; s < c.body.spring_count(); s += every)
    if (c.body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::shell) &&
        vec3_at(c.state.position, c.body.springs[s][0]).y() > 0)
      c.state.springs.failed[s] = 1;
}

std::string error_of(const std::vector<std::string>& files) {
  try {
    build_resolution_study(files);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(ResolutionStudy, ShellLevelFromTheIcosphereNodeCount) {
  EXPECT_EQ(shell_level_of(12), 0);
  EXPECT_EQ(shell_level_of(42), 1);
  EXPECT_EQ(shell_level_of(642), 3);
  EXPECT_EQ(shell_level_of(2562), 4);
  EXPECT_EQ(shell_level_of(10242), 5);
  EXPECT_EQ(shell_level_of(40962), 6);
  EXPECT_EQ(shell_level_of(0), -1);
  EXPECT_EQ(shell_level_of(643), -1);
}

TEST(ResolutionStudy, RelativeChangeIsUndefinedFromZero) {
  EXPECT_DOUBLE_EQ(relative_change_percent(0.11, 0.1), 10.0);
  EXPECT_DOUBLE_EQ(relative_change_percent(0.05, 0.1), -50.0);
  EXPECT_TRUE(std::isnan(relative_change_percent(0.1, 0.0)));
  EXPECT_TRUE(std::isnan(relative_change_percent(0.1, std::nan(""))));
}

TEST(ResolutionStudy, RowsCoarsestFirstWithTheirOwnStatistics) {
  const ScratchFolder scratch("resolution_study");
  Checkpoint fine = synthetic_encounter(2), coarse = synthetic_encounter(1);
  fail_springs(fine, 3);
  fail_springs(coarse, 2);
  fine.stage.clock.dt = 0.001;
  const std::string fine_file = (scratch.path / "fine.h5").string(), coarse_file = (scratch.path / "coarse.h5").string();
  write_checkpoint(fine_file, fine);
  write_checkpoint(coarse_file, coarse);

  const ResolutionStudy study = build_resolution_study({fine_file, coarse_file});
  ASSERT_EQ(study.rows.size(), 2u);
  EXPECT_EQ(study.encounter.name, "T5");
  EXPECT_EQ(study.rows[0].file, coarse_file);
  EXPECT_EQ(study.rows[1].file, fine_file);
  EXPECT_EQ(study.rows[0].shell_level, 1);
  EXPECT_EQ(study.rows[1].shell_level, 2);
  EXPECT_EQ(study.rows[1].shell_nodes, 162u);
  EXPECT_EQ(study.rows[1].particles, 163u);
  EXPECT_EQ(study.rows[1].dt, 0.001);
  EXPECT_EQ(study.rows[1].state_hash, state_hash(fine.state));
  const FractureSummary fine_summary = analyze_fractures(fine.body, fine.state);
  const FractureSummary coarse_summary = analyze_fractures(coarse.body, coarse.state);
  EXPECT_EQ(failure_summary_json(study.rows[1].fractures), failure_summary_json(fine_summary));
  EXPECT_EQ(failure_summary_json(study.rows[0].fractures), failure_summary_json(coarse_summary));
  EXPECT_TRUE(std::isnan(study.rows[0].area_fraction_change_percent));
  EXPECT_DOUBLE_EQ(study.rows[1].area_fraction_change_percent,
                   100 * (fine_summary.failed_area_fraction / coarse_summary.failed_area_fraction - 1));
  EXPECT_DOUBLE_EQ(study.rows[1].hemisphere_fraction_change_percent,
                   100 * (fine_summary.hemisphere_fraction / coarse_summary.hemisphere_fraction - 1));
  EXPECT_DOUBLE_EQ(study.rows[1].crack_length_change_percent,
                   100 * (fine_summary.total_crack_length / coarse_summary.total_crack_length - 1));
  EXPECT_TRUE(std::isnan(study.rows[0].crack_length_change_percent));

  const Json json = resolution_study_json(study);
  EXPECT_EQ(json["rows"][0]["shell_level"], 1);
  EXPECT_TRUE(json["rows"][0]["change_percent"]["failed_area_fraction"].is_null());
  EXPECT_EQ(json["rows"][1]["failures"], failure_summary_json(fine_summary));
  EXPECT_EQ(json["encounter"]["pericenter"], 1.84);
  const std::string csv = resolution_study_csv(study);
  EXPECT_EQ(csv.substr(0, csv.find(',')), "file");
  EXPECT_NE(csv.find("\n" + coarse_file + ",1,42,43,0.002,"), std::string::npos) << csv;
}

TEST(ResolutionStudy, RefusesOtherEncountersStagesUnfinishedAndASingleFile) {
  const ScratchFolder scratch("resolution_study_errors");
  const auto file = [&](const char* name) { return (scratch.path / name).string(); };
  const Checkpoint a = synthetic_encounter(1);
  write_checkpoint(file("a.h5"), a);
  Checkpoint other = synthetic_encounter(2);
  std::get<EncounterRecord>(other.stage.record).encounter.pericenter = 2.0;
  write_checkpoint(file("other_q.h5"), other);
  Checkpoint strain = synthetic_encounter(2);
  std::get<EncounterRecord>(strain.stage.record).failure_strain = 0.001;
  write_checkpoint(file("other_eps.h5"), strain);
  Checkpoint unfinished = synthetic_encounter(2);
  unfinished.stage.complete = false;
  write_checkpoint(file("mid.h5"), unfinished);
  Checkpoint relaxed = synthetic_encounter(2);
  relaxed.stage.record = RelaxRecord{};
  write_checkpoint(file("relax.h5"), relaxed);

  EXPECT_EQ(error_of({file("a.h5")}).find(file("a.h5") + ": compare --resolution needs at least two"), 0u);
  std::string e = error_of({file("a.h5"), file("other_q.h5")});
  EXPECT_EQ(e.find(file("other_q.h5") + ": another encounter than " + file("a.h5")), 0u) << e;
  EXPECT_NE(e.find("q = 2 R"), std::string::npos) << e;
  e = error_of({file("a.h5"), file("other_eps.h5")});
  EXPECT_EQ(e.find(file("other_eps.h5") + ": another encounter"), 0u) << e;
  e = error_of({file("a.h5"), file("mid.h5")});
  EXPECT_EQ(e.find(file("mid.h5") + ": not a finished encounter"), 0u) << e;
  e = error_of({file("relax.h5"), file("a.h5")});
  EXPECT_EQ(e.find(file("relax.h5") + ": stage is 'relax', expected an 'encounter' checkpoint"), 0u) << e;
  for (const std::string& message : {error_of({}), error_of({file("a.h5"), file("missing.h5")})})
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}
