// Checkpoints of every format this program reads. The stored files of tests/reference/format-3/
// and format-4/ (README there: written by earlier commits, never regenerated) stand for users'
// old results: each is read, the encounter is begun from each relax.h5 and each mid-stage
// encounter resumed, each encounter.h5 analysed, to the values of
// tests/reference/stored-checkpoints.toml. They must keep passing with every later format. Then
// the upgrade's own rules: a newer or too old format is one line and exit 2, the integrity
// record is verified on the file as stored before any upgrade, a format-4 file written before the
// energy budget reads with NaN there, and an upgraded checkpoint is written in the current format.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

#include "io/checkpoint_file.hpp"
#include "io/content_hash.hpp"
#include "io/hdf5_handles.hpp"
#include "io/json.hpp"
#include "io/state_hash.hpp"
#include "support/bad_checkpoints.hpp"
#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/force_test_bodies.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// The formats of tests/reference/format-<N>/, each a relax.h5, an encounter.h5 and an
/// encounter.mid.h5 of one run.
constexpr std::int64_t stored_formats[] = {3, 4};

fs::path stored_file(std::int64_t format, const std::string& name) {
  return source_file(fmt::format("tests/reference/format-{}/{}.h5", format, name));
}

const toml::table& expected() {
  static const toml::table table = toml::parse_file(source_file("tests/reference/stored-checkpoints.toml").string());
  return table;
}

/// expected()[table][key], or [table][entry][key] ("stored", "encounter.mid", "step").
toml::node_view<const toml::node> value(std::string_view table, std::string_view key) { return expected()[table][key]; }
toml::node_view<const toml::node> value(std::string_view table, std::string_view entry, std::string_view key) {
  return expected()[table][entry][key];
}

double tolerance() { return expected()["relative_tolerance"].value_or(0.0); }

/// A stored value of type T (a missing one fails the comparison it is used in).
template <typename T>
T get(toml::node_view<const toml::node> v) {
  if constexpr (std::is_same_v<T, double>) return v.value_or(std::nan(""));
  else return v.value_or(T{});
}

/// |computed - stored| within the file's relative tolerance.
void expect_near(double computed, double stored, const std::string& what) {
  EXPECT_LE(std::abs(computed - stored), tolerance() * std::abs(stored)) << what << ": " << fmt::format("{:.17g}", computed);
}

/// A resumed encounter's end against [resumed]: its step, failures and final kinetic energy, and
/// its state_hash against the value named `hash` (the portable mode gives the same bits on every
/// x86-64 CPU: its sin, cos and atan2 come from SLEEF, docs/determinism.md).
void expect_resumed_end(const fs::path& file, const std::string& what, const char* hash) {
  const Checkpoint c = read_checkpoint(file);
  EXPECT_TRUE(c.stage.complete) << what;
  EXPECT_EQ(c.state.step, get<std::int64_t>(value("resumed", "step"))) << what;
  EXPECT_EQ(static_cast<std::int64_t>(c.observables.failures.size()), get<std::int64_t>(value("resumed", "failed")))
      << what;
  ASSERT_FALSE(c.observables.timeseries.empty()) << what;
  expect_near(c.observables.timeseries.back().kinetic_energy, get<double>(value("resumed", "kinetic_energy")),
              what + ": final kinetic_energy");
  EXPECT_EQ(state_hash(c.state), get<std::string>(value("resumed", hash))) << what;
}

}  // namespace

TEST(StoredCheckpoints, EachFileReadsWithItsStoredValues) {
  for (const std::int64_t format : stored_formats)
    for (const char* name : {"relax", "encounter", "encounter.mid"}) {
      const std::string what = fmt::format("format-{}/{}.h5", format, name);
      const Checkpoint c = read_checkpoint(stored_file(format, name));
      EXPECT_EQ(c.provenance.format_version, format) << what;
      EXPECT_EQ(c.stage.name(), get<std::string>(value("stored", name, "stage"))) << what;
      EXPECT_EQ(c.stage.complete, get<bool>(value("stored", name, "complete"))) << what;
      EXPECT_EQ(c.state.step, get<std::int64_t>(value("stored", name, "step"))) << what;
      EXPECT_EQ(state_hash(c.state), get<std::string>(value("stored", name, "state_hash"))) << what;
      // `run` wrote relax.h5 and encounter.h5 (with fingerprints), `encounter` the mid-stage file.
      EXPECT_EQ(c.stage.fingerprint.empty(), std::string_view(name) == "encounter.mid") << what;
      if (const auto failed = value("stored", name, "failed").value<std::int64_t>()) {
        EXPECT_EQ(static_cast<std::int64_t>(c.observables.failures.size()), *failed) << what;
      }
      if (!std::holds_alternative<EncounterRecord>(c.stage.record)) continue;
      const auto& record = c.stage.as<EncounterRecord>();
      EXPECT_EQ(kind_of(record.failure_rule), FailureRuleKind::local) << what;  // as stored: format 3 files already had the local rule
      // Before format 7 every encounter began from the relaxed body on the paper's orbit.
      EXPECT_FALSE(record.encounter.after) << what;
      EXPECT_TRUE(record.orbit.is_default()) << what;
      ASSERT_FALSE(c.observables.timeseries.empty()) << what;
      // Format 3 did not record the energy budget: NaN after the upgrade, never a made-up 0.
      const bool budget = format >= 4;
      EXPECT_EQ(std::isfinite(record.energy.damping_dissipated), budget) << what;
      EXPECT_EQ(std::isfinite(c.observables.timeseries.back().spring_energy), budget) << what;
      EXPECT_EQ(std::isfinite(c.observables.failures.front().released_energy), budget) << what;
    }
}

TEST(StoredCheckpoints, EncounterFromEachStoredRelaxEndsAtTheStoredValues) {
  for (const std::int64_t format : stored_formats) {
    const ScratchFolder scratch(fmt::format("stored_relax_{}", format));
    const fs::path relax = scratch.path / "relax.h5", out = scratch.path / "encounter.h5";
    fs::copy_file(stored_file(format, "relax"), relax);
    // Format 3 recorded no gravity kernel (its fast kernel was the portable code on this machine).
    const CliResult r = run_cli("encounter --quiet --gravity-kernel portable --encounter close --from " + quoted(relax) +
                                " --out " + quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_resumed_end(out, fmt::format("encounter from format-{}/relax.h5", format), "state_hash");
    EXPECT_EQ(read_file(relax), read_file(stored_file(format, "relax")));
  }
}

TEST(StoredCheckpoints, EachStoredMidStageEncounterResumesToTheStoredEnd) {
  for (const std::int64_t format : stored_formats) {
    const ScratchFolder scratch(fmt::format("stored_mid_{}", format));
    const fs::path mid = scratch.path / "encounter.mid.h5", out = scratch.path / "encounter.h5";
    fs::copy_file(stored_file(format, "encounter.mid"), mid);
    const CliResult r = run_cli("encounter --quiet --gravity-kernel portable --from " + quoted(mid) + " --out " + quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string what = fmt::format("format-{}/encounter.mid.h5 resumed", format);
    expect_resumed_end(out, what, "mid_state_hash");
    // A resumed stage keeps its record: a format-3 encounter goes on without an energy budget.
    EXPECT_EQ(std::isfinite(read_checkpoint(out).stage.as<EncounterRecord>().energy.damping_dissipated), format >= 4)
        << what;
  }
}

TEST(StoredCheckpoints, EachStoredEncounterAnalyses) {
  for (const std::int64_t format : stored_formats) {
    const ScratchFolder scratch(fmt::format("stored_analyze_{}", format));
    const fs::path encounter = scratch.path / "encounter.h5", out = scratch.path / "analysis";
    fs::copy_file(stored_file(format, "encounter"), encounter);
    const CliResult r = run_cli("analyze --from " + quoted(encounter) + " --out " + quoted(out));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json summary = Json::parse(read_file(out / "summary.json"));
    const std::string what = fmt::format("format-{}/encounter.h5", format);
    EXPECT_EQ(summary["state_hash"], get<std::string>(value("stored", "encounter", "state_hash"))) << what;
    for (const auto& [key, stored] : *expected()["analysis"]["failures"].as_table()) {
      const std::string name(key.str());
      const Json& computed = summary["failures"][name];
      if (stored.is_integer()) {
        EXPECT_EQ(computed.get<std::int64_t>(), stored.value_or(std::int64_t{-1})) << what << ": failures." << name;
      } else {
        expect_near(computed.get<double>(), stored.value_or(std::nan("")), what + ": failures." + name);
      }
    }
    for (const auto& [key, stored] : *expected()["analysis"]["energy"].as_table()) {
      const std::string name(key.str());
      const Json& computed = summary["energy"][name];
      if (format < 4) {
        EXPECT_TRUE(computed.is_null()) << what << ": energy." << name;  // not recorded
      } else {
        expect_near(computed.get<double>(), stored.value_or(std::nan("")), what + ": energy." + name);
      }
    }
    EXPECT_TRUE(fs::exists(out / "fracture_map.png")) << what;
  }
}

TEST(CheckpointFormats, NewerAndTooOldFormatsAreOneLineErrorsNamingTheVersions) {
  const ScratchFolder scratch("formats_refused");
  const std::string current = std::to_string(checkpoint_format_version);
  const std::pair<std::int64_t, std::string> cases[] = {
      {checkpoint_format_version + 1, fmt::format("written by a newer tidalcrust (format {}); this one reads up to {}",
                                                  checkpoint_format_version + 1, current)},
      {2, "written in format 2, too old: this tidalcrust reads formats 3 to " + current}};
  for (const auto& [version, message] : cases) {
    const fs::path file = edited_copy(stored_file(4, "relax"), scratch.path, fmt::format("v{}.h5", version),
                                      [v = version](hid_t f) { overwrite_attribute(f, "/checkpoint", "format_version", v); });
    const std::string bytes = read_file(file);
    const CliResult r = run_cli("encounter --quiet --encounter close --from " + quoted(file) + " --out " +
                                quoted(scratch.path / "e.h5"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(file.string() + ": " + message), std::string::npos) << r.err;
    EXPECT_EQ(read_file(file), bytes);
    EXPECT_FALSE(fs::exists(scratch.path / "e.h5"));
  }
}

// A format-4 encounter as written before the energy budget and the local rule's record fields
// (commits b423be2 to cf32658, the same version number): those objects are added in the copy
// read, NaN and the paper rule's values.
TEST(CheckpointFormats, Format4WrittenBeforeTheEnergyBudgetReadsWithNaNThere) {
  const ScratchFolder scratch("formats_early_4");
  const fs::path early = edited_copy(stored_file(4, "encounter"), scratch.path, "early.h5", [](hid_t f) {
    for (const char* column : {"internal_kinetic_energy", "spring_energy", "hinge_energy", "self_gravity_energy",
                               "perturber_energy", "damping_dissipated", "failure_released", "hinge_residual_work"})
      H5Ldelete(f, fmt::format("/checkpoint/timeseries/{}", column).c_str(), H5P_DEFAULT);
    H5Ldelete(f, "/checkpoint/failures/released_energy", H5P_DEFAULT);
    h5::Group record = h5::open_group(f, "/checkpoint/record");
    for (const char* name : {"failure_rule", "relaxation_steps", "exclusion_distance", "damping_dissipated",
                             "failure_released", "hinge_residual_work"})
      H5Adelete(record.get(), name);
  });
  const Checkpoint c = read_checkpoint(early);
  EXPECT_EQ(state_hash(c.state), get<std::string>(value("stored", "encounter", "state_hash")));
  const auto& record = c.stage.as<EncounterRecord>();
  // The upgrade fills in the paper rule, which has no parameters of its own.
  EXPECT_EQ(kind_of(record.failure_rule), FailureRuleKind::paper);
  EXPECT_TRUE(std::isnan(record.energy.failure_released));
  ASSERT_EQ(c.observables.timeseries.size(), read_checkpoint(stored_file(4, "encounter")).observables.timeseries.size());
  for (const auto& sample : c.observables.timeseries) EXPECT_TRUE(std::isnan(sample.hinge_energy));
  for (const auto& event : c.observables.failures) EXPECT_TRUE(std::isnan(event.released_energy));

  // The integrity record is verified on the file as stored, before the upgrade: an edit shows.
  edit_in_place(early, [](hid_t f) { overwrite_element(f, "/particles/body/mass", 3, 0.5); });
  EXPECT_NE(checkpoint_read_error(early).find("/particles/body/mass changed since the file was written"),
            std::string::npos)
      << checkpoint_read_error(early);
}

// Format-3 files written between the integrity check and format 4 carry a record: it is verified.
// Those without one are still held to their state_hash.
TEST(CheckpointFormats, Format3IsVerifiedByItsIntegrityRecordIfAnyAndItsStateHash) {
  const ScratchFolder scratch("formats_3_checks");
  const fs::path sealed = edited_copy(stored_file(3, "relax"), scratch.path, "sealed.h5", [](hid_t) {});
  EXPECT_EQ(state_hash(read_checkpoint(sealed).state), get<std::string>(value("stored", "relax", "state_hash")));
  edit_in_place(sealed, [](hid_t f) { overwrite_element(f, "/particles/body/mass", 3, 0.5); });
  EXPECT_NE(checkpoint_read_error(sealed).find("/particles/body/mass changed since the file was written"),
            std::string::npos)
      << checkpoint_read_error(sealed);

  const fs::path bare = scratch.path / "bare.h5";
  fs::copy_file(stored_file(3, "relax"), bare);
  edit_in_place(bare, [](hid_t f) { overwrite_element(f, "/particles/body/position/value", 7, 0.25); });
  EXPECT_NE(checkpoint_read_error(bare).find("state_hash mismatch"), std::string::npos) << checkpoint_read_error(bare);
}

TEST(CheckpointFormats, AnUpgradedCheckpointIsWrittenInTheCurrentFormat) {
  const ScratchFolder scratch("formats_rewrite");
  const Checkpoint old = read_checkpoint(stored_file(3, "encounter"));
  const fs::path file = scratch.path / "rewritten.h5";
  write_checkpoint(file, old);
  {
    h5::File f = h5::open_file_readonly(file);
    h5::Group g = h5::open_group(f.get(), "/checkpoint");
    EXPECT_EQ(h5::read_attribute<std::int64_t>(g.get(), "format_version"), checkpoint_format_version);
    EXPECT_FALSE(h5::exists(f.get(), "/observables"));
    EXPECT_TRUE(h5::exists(f.get(), "/checkpoint/failures/released_energy"));
    EXPECT_TRUE(h5::exists(f.get(), integrity_group));
  }
  const Checkpoint again = read_checkpoint(file);
  EXPECT_EQ(again.provenance.format_version, checkpoint_format_version);
  EXPECT_EQ(state_hash(again.state), state_hash(old.state));
  EXPECT_EQ(again.stage.fingerprint, old.stage.fingerprint);
  EXPECT_EQ(again.observables.failures.size(), old.observables.failures.size());
}

// Format 8 (a crust that varies, docs/crust.md): each spring's strength factor is stored and read
// back bit for bit; a format-7 file, and every older one, reads as a uniform crust (factor 1 for
// every spring).
TEST(CheckpointFormats, StrengthFactorsRoundTripAndFormat7ReadsAsAUniformCrust) {
  const ScratchFolder scratch("formats_strength");
  Config config = small_body_config();
  config.crust.strength_harmonics = "s11 = -0.3, c20 = 0.1";
  config.crust.weak_lines = "pole_lon = 30, pole_lat = 20, radius = 60, half_width = 5, factor = 0.45";
  const Checkpoint built = build_stage(config);
  const fs::path file = scratch.path / "built.h5";
  write_checkpoint(file, built);
  const Checkpoint back = read_checkpoint(file);
  ASSERT_EQ(back.body.strength_factor.size(), built.body.spring_count());
  for (std::size_t n = 0; n < built.body.spring_count(); ++n)
    ASSERT_EQ(std::bit_cast<std::uint64_t>(back.body.strength_factor[n]),
              std::bit_cast<std::uint64_t>(built.body.strength_factor[n]))
        << n;
  EXPECT_LT(*std::min_element(back.body.strength_factor.begin(), back.body.strength_factor.end()), 0.45 * 0.8);

  const fs::path seven = edited_copy(file, scratch.path, "seven.h5", [](hid_t f) {
    h5::check(H5Ldelete(f, "/checkpoint/springs/strength_factor", H5P_DEFAULT), "delete strength_factor");
    overwrite_attribute(f, "/checkpoint", "format_version", std::int64_t{7});
  });
  const Checkpoint old = read_checkpoint(seven);
  EXPECT_EQ(old.provenance.format_version, 7);
  EXPECT_EQ(state_hash(old.state), state_hash(built.state));
  ASSERT_EQ(old.body.strength_factor.size(), built.body.spring_count());
  for (const double f : old.body.strength_factor) ASSERT_EQ(f, 1.0);
  for (const std::int64_t format : stored_formats) {
    const Checkpoint stored = read_checkpoint(stored_file(format, "relax"));
    ASSERT_EQ(stored.body.strength_factor.size(), stored.body.spring_count()) << format;
    for (const double f : stored.body.strength_factor) ASSERT_EQ(f, 1.0) << format;
  }
  // A factor that is not > 0 is refused naming the dataset.
  const fs::path zero = edited_copy(file, scratch.path, "zero.h5", [](hid_t f) {
    overwrite_element(f, "/checkpoint/springs/strength_factor", 3, 0.0);
  });
  EXPECT_NE(checkpoint_read_error(zero).find("/checkpoint/springs/strength_factor row 3: factor 0 is not finite and > 0"),
            std::string::npos)
      << checkpoint_read_error(zero);
}
