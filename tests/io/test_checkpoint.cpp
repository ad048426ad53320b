#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "support/bad_checkpoints.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"
#include "support/shared_checkpoint.hpp"
#include "io/checkpoint_file.hpp"
#include "model/config.hpp"
#include "base/errors.hpp"
#include "io/hdf5_handles.hpp"
#include "io/state_hash.hpp"
#include "support/synthetic_checkpoint.hpp"
#include "base/invariant.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

template <typename T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
template <typename T, std::size_t K>
bool same_bits(const std::array<T, K>& a, const std::array<T, K>& b) {
  return std::memcmp(a.data(), b.data(), sizeof(a)) == 0;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// The stage name and every record field's name and bytes, in visit order.
std::string record_bytes(const StageRecord& record) {
  std::string out = stage_name(record);
  auto append = [&out](const char* name, const auto& value, const char*, const char*) {
    using T = std::decay_t<decltype(value)>;
    out += name;
    if constexpr (std::is_same_v<T, std::string>) {
      out += value;
    } else if constexpr (std::is_same_v<T, std::optional<std::string>>) {
      out += value.value_or("");
    } else if constexpr (std::is_arithmetic_v<T>) {
      out.append(reinterpret_cast<const char*>(&value), sizeof value);
    } else if constexpr (Choice<T>) {
      out += choice_name(value);
    } else {
      out.append(reinterpret_cast<const char*>(value.data()), value.size() * sizeof(value[0]));
    }
  };
  std::visit([&](const auto& r) { visit_fields(r, append); }, record);
  return out;
}

void expect_identical(const Checkpoint& a, const Checkpoint& b) {
  EXPECT_EQ(record_bytes(a.stage.record), record_bytes(b.stage.record));
  EXPECT_EQ(a.stage.complete, b.stage.complete);
  EXPECT_TRUE(same_bits(a.stage.clock.start_time, b.stage.clock.start_time));
  EXPECT_EQ(a.stage.clock.start_step, b.stage.clock.start_step);
  EXPECT_TRUE(same_bits(a.stage.clock.dt, b.stage.clock.dt));
  EXPECT_EQ(a.stage.end_step, b.stage.end_step);
  EXPECT_EQ(a.stage.parent_hash, b.stage.parent_hash);
  EXPECT_EQ(a.stage.fingerprint, b.stage.fingerprint);
  EXPECT_EQ(a.stage.diagnostic, b.stage.diagnostic);
  EXPECT_EQ(a.config_toml, b.config_toml);

  EXPECT_TRUE(same_bits(a.body.mass, b.body.mass));
  EXPECT_EQ(a.body.species, b.body.species);
  EXPECT_EQ(a.body.springs, b.body.springs);
  EXPECT_EQ(a.body.spring_kind, b.body.spring_kind);
  EXPECT_EQ(a.body.hinges, b.body.hinges);
  EXPECT_EQ(a.body.faces, b.body.faces);
  EXPECT_TRUE(same_bits(a.body.softening, b.body.softening));

  EXPECT_TRUE(same_bits(a.state.time, b.state.time));
  EXPECT_EQ(a.state.step, b.state.step);
  EXPECT_TRUE(same_bits(a.state.position, b.state.position));
  EXPECT_TRUE(same_bits(a.state.velocity, b.state.velocity));
  EXPECT_TRUE(same_bits(a.state.springs.rest_length, b.state.springs.rest_length));
  EXPECT_TRUE(same_bits(a.state.springs.stiffness, b.state.springs.stiffness));
  EXPECT_EQ(a.state.springs.failed, b.state.springs.failed);
  EXPECT_TRUE(same_bits(a.state.hinges.rest_angle, b.state.hinges.rest_angle));
  EXPECT_TRUE(same_bits(a.body.hinge_stiffness, b.body.hinge_stiffness));
  EXPECT_EQ(a.state.perturber.present, b.state.perturber.present);
  EXPECT_TRUE(same_bits(a.state.perturber.mass, b.state.perturber.mass));
  EXPECT_TRUE(same_bits(a.state.perturber.position, b.state.perturber.position));
  EXPECT_TRUE(same_bits(a.state.perturber.velocity, b.state.perturber.velocity));

  ASSERT_EQ(a.observables.failures.size(), b.observables.failures.size());
  for (std::size_t i = 0; i < a.observables.failures.size(); ++i) {
    const auto &x = a.observables.failures[i], &y = b.observables.failures[i];
    EXPECT_TRUE(same_bits(x.time, y.time) && x.step == y.step && x.spring == y.spring &&
                same_bits(x.strain, y.strain) && same_bits(x.position, y.position) &&
                same_bits(x.released_energy, y.released_energy))
        << "failure row " << i;
  }
  ASSERT_EQ(a.observables.timeseries.size(), b.observables.timeseries.size());
  for (std::size_t i = 0; i < a.observables.timeseries.size(); ++i) {
    const auto &x = a.observables.timeseries[i], &y = b.observables.timeseries[i];
    EXPECT_TRUE(same_bits(x.time, y.time) && x.failed == y.failed && same_bits(x.kinetic_energy, y.kinetic_energy) &&
                same_bits(x.momentum, y.momentum) && same_bits(x.angular_momentum, y.angular_momentum) &&
                same_bits(x.perturber_offset, y.perturber_offset))
        << "timeseries row " << i;
    for (double TimeseriesSample::*term :
         {&TimeseriesSample::internal_kinetic_energy, &TimeseriesSample::spring_energy, &TimeseriesSample::hinge_energy,
          &TimeseriesSample::self_gravity_energy, &TimeseriesSample::perturber_energy,
          &TimeseriesSample::damping_dissipated, &TimeseriesSample::failure_released,
          &TimeseriesSample::hinge_residual_work})
      EXPECT_TRUE(same_bits(x.*term, y.*term)) << "timeseries row " << i;
  }
}


std::vector<std::string> tmp_files_in(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) names.push_back(entry.path().string());
  return names;
}

/// Runs in a death-test child: writes with RLIMIT_FSIZE = `limit` bytes; exit code 3 when the
/// write failed with InputError, 0 when it succeeded.
[[noreturn]] void write_with_file_size_limit(const fs::path& file, const Checkpoint& c, rlim_t limit) {
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit rl{limit, limit};
  setrlimit(RLIMIT_FSIZE, &rl);
  try {
    write_checkpoint(file, c);
  } catch (const InputError&) {
    std::_Exit(3);
  }
  std::_Exit(0);
}

}  // namespace

TEST(Checkpoint, RoundTripIsBitwiseIdentical) {
  const ScratchFolder scratch("roundtrip");
  const fs::path& dir = scratch.path;
  const Checkpoint original = synthetic_checkpoint();
  write_checkpoint(dir / "c.h5", original);
  const Checkpoint back = read_checkpoint(dir / "c.h5");
  expect_identical(original, back);
  EXPECT_EQ(state_hash(back.state), state_hash(original.state));
  EXPECT_TRUE(is_valid_checkpoint(dir / "c.h5"));
  EXPECT_TRUE(tmp_files_in(dir).empty());
}

// The tests' shared relaxed bodies (tests/support/shared_checkpoint.hpp): the first call computes
// and stores, a later one (another test process) reads the same bits without computing; without
// the variable every call computes.
TEST(Checkpoint, SharedTestCheckpointIsComputedOnceAndReadBackBitForBit) {
  const ScratchFolder scratch("shared_checkpoint");
  const char* before = std::getenv("TIDALCRUST_TEST_CACHE");
  const std::string saved = before ? before : "";
  int computed = 0;
  auto compute = [&] {
    ++computed;
    return synthetic_checkpoint();
  };
  ::setenv("TIDALCRUST_TEST_CACHE", (scratch.path / "cache").c_str(), 1);
  const Checkpoint first = shared_checkpoint("body", compute);
  const Checkpoint second = shared_checkpoint("body", compute);
  EXPECT_EQ(computed, 1);
  expect_identical(first, second);
  expect_identical(first, synthetic_checkpoint());
  ::unsetenv("TIDALCRUST_TEST_CACHE");
  shared_checkpoint("body", compute);
  EXPECT_EQ(computed, 2);
  if (before) ::setenv("TIDALCRUST_TEST_CACHE", saved.c_str(), 1);
}

TEST(Checkpoint, EveryEnergyBudgetColumnIsRequired) {
  // Format 4 files always have the budget's columns; one deleted (integrity record rebuilt, so
  // the layout check itself is exercised) is refused naming it.
  const ScratchFolder scratch("no_energy_columns");
  write_checkpoint(scratch.path / "full.h5", synthetic_checkpoint());
  for (const char* column : {"/checkpoint/timeseries/spring_energy", "/checkpoint/timeseries/hinge_residual_work",
                             "/checkpoint/failures/released_energy"}) {
    const fs::path old = edited_copy(scratch.path / "full.h5", scratch.path, "old.h5",
                                     [&](hid_t f) { H5Ldelete(f, column, H5P_DEFAULT); });
    try {
      read_checkpoint(old);
      ADD_FAILURE() << column << " deleted, file accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(column), std::string::npos) << e.what();
    }
  }
}

TEST(Checkpoint, RoundTripWithoutPerturberAndWithEmptyObservables) {
  const ScratchFolder scratch("roundtrip_empty");
  const fs::path& dir = scratch.path;
  Checkpoint original = synthetic_checkpoint();
  original.stage.record = BuildRecord{200, 0, 0.1};
  original.stage.complete = true;
  original.stage.fingerprint.clear();
  original.stage.parent_hash.clear();
  original.state.perturber = Perturber{};
  original.observables = Observables{};
  original.body.faces.clear();
  original.config_toml.clear();
  write_checkpoint(dir / "c.h5", original);
  const Checkpoint back = read_checkpoint(dir / "c.h5");
  expect_identical(original, back);
  EXPECT_FALSE(back.state.perturber.present);
  h5::File f = h5::open_file_readonly(dir / "c.h5");
  EXPECT_FALSE(h5::exists(f.get(), "/checkpoint/perturber"));
  EXPECT_EQ(h5::read_dataset<double>(f.get(), "/checkpoint/failures/position").dims,
            (std::vector<hsize_t>{0, 3}));
}

TEST(Checkpoint, EqualCheckpointsGiveIdenticalBytes) {
  const ScratchFolder scratch("identical");
  const fs::path& dir = scratch.path;
  const Checkpoint c = synthetic_checkpoint();
  write_checkpoint(dir / "a.h5", c);
  write_checkpoint(dir / "b.h5", c);
  const std::string a = read_file(dir / "a.h5");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, read_file(dir / "b.h5"));
  // Reading back and writing again reproduces the same bytes too.
  write_checkpoint(dir / "c.h5", read_checkpoint(dir / "a.h5"));
  EXPECT_EQ(a, read_file(dir / "c.h5"));
  // A different state gives a different file.
  Checkpoint d = c;
  d.state.position[4] = std::nextafter(d.state.position[4], 1.0);
  write_checkpoint(dir / "d.h5", d);
  EXPECT_NE(a, read_file(dir / "d.h5"));
}

TEST(Checkpoint, RecordWithManyFieldsUsesDenseAttributeStorageReproducibly) {
  // More than 8 attributes on one group switch HDF5 to dense (heap + B-tree) storage; the
  // encounter record has more than that.
  const ScratchFolder scratch("dense");
  const fs::path& dir = scratch.path;
  Checkpoint c = synthetic_checkpoint();
  c.stage.diagnostic = std::string(300, 'x');
  write_checkpoint(dir / "a.h5", c);
  {
    h5::File f = h5::open_file_readonly(dir / "a.h5");
    h5::Group record = h5::open_group(f.get(), "/checkpoint/record");
    EXPECT_GT(h5::attribute_names(record.get()).size(), 8u);
  }
  write_checkpoint(dir / "b.h5", c);
  EXPECT_EQ(read_file(dir / "a.h5"), read_file(dir / "b.h5"));
  expect_identical(c, read_checkpoint(dir / "a.h5"));
}

TEST(Checkpoint, ObjectsCarryNoTimestamps) {
  const ScratchFolder scratch("timestamps");
  const fs::path& dir = scratch.path;
  write_checkpoint(dir / "c.h5", synthetic_checkpoint());
  h5::File f = h5::open_file_readonly(dir / "c.h5");
  struct Visit {
    int objects = 0;
    std::vector<std::string> timed;
  } visit;
  auto op = [](hid_t, const char* name, const H5O_info_t* info, void* data) -> herr_t {
    auto* v = static_cast<Visit*>(data);
    ++v->objects;
    if (info->atime || info->mtime || info->ctime || info->btime) v->timed.push_back(name);
    return 0;
  };
  ASSERT_GE(H5Ovisit(f.get(), H5_INDEX_NAME, H5_ITER_INC, op, &visit), 0);
  EXPECT_GT(visit.objects, 40);
  EXPECT_TRUE(visit.timed.empty()) << visit.timed.front();
}

TEST(Checkpoint, FileFollowsTheH5mdLayout) {
  const ScratchFolder scratch("layout");
  const fs::path& dir = scratch.path;
  const Checkpoint c = synthetic_checkpoint();
  write_checkpoint(dir / "c.h5", c);
  h5::File f = h5::open_file_readonly(dir / "c.h5");
  const hid_t root = f.get();
  {
    h5::Group g = h5::open_group(root, "/h5md");
    EXPECT_EQ(h5::read_attribute_array<std::int32_t>(g.get(), "version"), (std::vector<std::int32_t>{1, 1}));
    h5::Group creator = h5::open_group(root, "/h5md/creator");
    EXPECT_EQ(h5::read_string_attribute(creator.get(), "name"), "tidalcrust");
    EXPECT_TRUE(h5::exists(root, "/h5md/author"));
  }
  {
    h5::Group box = h5::open_group(root, "/particles/body/box");
    EXPECT_EQ(h5::read_attribute<std::int32_t>(box.get(), "dimension"), 3);
    EXPECT_EQ(h5::read_string_array_attribute(box.get(), "boundary"),
              (std::vector<std::string>{"none", "none", "none"}));
  }
  EXPECT_EQ(h5::read_dataset<double>(root, "/particles/body/position/value").dims, (std::vector<hsize_t>{1, 5, 3}));
  EXPECT_EQ(h5::read_dataset<double>(root, "/particles/body/velocity/time").values, std::vector<double>{2.25});
  EXPECT_EQ(h5::read_dataset<std::int64_t>(root, "/particles/body/velocity/step").values,
            std::vector<std::int64_t>{1125});
  EXPECT_EQ(h5::read_dataset<std::int32_t>(root, "/connectivity/hinges").dims, (std::vector<hsize_t>{3, 4}));
  {
    h5::Group g = h5::open_group(root, "/checkpoint");
    EXPECT_EQ(h5::read_string_attribute(g.get(), "state_hash"), state_hash(c.state));
    EXPECT_EQ(h5::read_string_attribute(g.get(), "stage"), "encounter");
    EXPECT_EQ(h5::read_attribute<std::int64_t>(g.get(), "format_version"), checkpoint_format_version);
    EXPECT_EQ(h5::read_attribute<double>(g.get(), "dt"), 0.002);
    EXPECT_EQ(h5::read_attribute<double>(g.get(), "start_time"), 2.0);
    // Every record field: numbers, flags and texts as attributes, lists as datasets.
    h5::Group record = h5::open_group(root, "/checkpoint/record");
    std::size_t fields = 0;
    visit_fields(c.stage.as<EncounterRecord>(), [&](const char* name, const auto& value, const char*, const char*) {
      ++fields;
      using T = std::decay_t<decltype(value)>;
      if constexpr (std::is_same_v<T, std::vector<std::int64_t>>)
        EXPECT_EQ(h5::read_dataset<std::int64_t>(record.get(), name).values, value) << name;
      else
        EXPECT_GT(H5Aexists(record.get(), name), 0) << name;
    });
    EXPECT_EQ(fields, 31u);  // 18 + the energy budget's three accumulators + the local failure rule's three + shadow_distance + the griffith rule's two + after and the orbit's three angles
  }
  EXPECT_EQ(h5::read_string_dataset(root, "/parameters/config"), c.config_toml);
  {
    h5::Group p = h5::open_group(root, "/parameters/provenance");
    for (const char* key : {"version", "git_commit", "compiler", "build_flags"})
      EXPECT_FALSE(h5::read_string_attribute(p.get(), key).empty()) << key;
  }
  for (const char* d : {"/checkpoint/timeseries/momentum", "/checkpoint/timeseries/angular_momentum",
                        "/checkpoint/timeseries/perturber_offset"})
    EXPECT_EQ(h5::read_dataset<double>(root, d).dims, (std::vector<hsize_t>{2, 3})) << d;
  // Stored as little-endian IEEE float64 whatever the reader.
  h5::Dataset set(H5Dopen2(root, "/checkpoint/springs/rest_length", H5P_DEFAULT));
  h5::Type type(H5Dget_type(set.get()));
  EXPECT_GT(H5Tequal(type.get(), H5T_IEEE_F64LE), 0);
}

TEST(Checkpoint, XdmfSidecarReferencesExistingDatasets) {
  const ScratchFolder scratch("xdmf");
  const fs::path& dir = scratch.path;
  write_checkpoint(dir / "body.h5", synthetic_checkpoint());
  ASSERT_TRUE(fs::exists(dir / "body.xdmf"));
  const std::string xml = read_file(dir / "body.xdmf");
  for (const char* expected : {"<Xdmf Version=\"3.0\">", "TopologyType=\"Polyvertex\" NumberOfElements=\"5\"",
                               "TopologyType=\"Polyline\" NumberOfElements=\"10\" NodesPerElement=\"2\"",
                               "TopologyType=\"Triangle\" NumberOfElements=\"4\"", "Name=\"failed\"",
                               "Name=\"kind\"", "Name=\"species\"", "</Xdmf>"})
    EXPECT_NE(xml.find(expected), std::string::npos) << expected;
  // Every heavy-data reference is relative ("body.h5:/...") and names a dataset of the file.
  h5::File f = h5::open_file_readonly(dir / "body.h5");
  std::regex reference(R"(>([^<>:]+):(/[^<]+)</DataItem>)");
  int references = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), reference); it != std::sregex_iterator(); ++it) {
    ++references;
    EXPECT_EQ((*it)[1].str(), "body.h5");
    EXPECT_TRUE(h5::exists(f.get(), (*it)[2].str())) << (*it)[2].str();
  }
  EXPECT_GE(references, 11);
  // Equal checkpoints give equal sidecars too.
  write_checkpoint(dir / "again.h5", synthetic_checkpoint());
  std::string again = read_file(dir / "again.xdmf");
  EXPECT_EQ(std::regex_replace(again, std::regex("again\\.h5"), "body.h5"), xml);
}

TEST(Checkpoint, BadFilesAreRejectedWithMessagesNamingFileAndDataset) {
  const ScratchFolder scratch("bad");
  const fs::path& dir = scratch.path;
  write_checkpoint(dir / "valid.h5", synthetic_checkpoint());
  const auto bad = make_bad_checkpoints(dir / "valid.h5", dir);
  EXPECT_EQ(bad.size(), 12u);
  for (const auto& b : bad) {
    const std::string message = checkpoint_read_error(b.file);
    EXPECT_NE(message.find(b.file.string() + ": "), std::string::npos) << b.what << ": " << message;
    EXPECT_NE(message.find(b.expected_message), std::string::npos) << b.what << ": " << message;
    EXPECT_FALSE(is_valid_checkpoint(b.file)) << b.what;
  }
  EXPECT_TRUE(is_valid_checkpoint(dir / "valid.h5"));
}

TEST(Checkpoint, HashMismatchMessageGivesBothHashes) {
  const ScratchFolder scratch("hash");
  const fs::path& dir = scratch.path;
  const Checkpoint c = synthetic_checkpoint();
  write_checkpoint(dir / "valid.h5", c);
  Checkpoint changed = c;
  changed.state.position[4] = std::nextafter(changed.state.position[4], 2.0);
  // Replace the positions in a copy without touching the stored hash.
  auto file = edited_copy(dir / "valid.h5", dir, "tampered.h5", [&](hid_t f) {
    H5Ldelete(f, "/particles/body/position/value", H5P_DEFAULT);
    h5::write_dataset(f, "/particles/body/position/value", changed.state.position, {1, 5, 3});
  });
  EXPECT_EQ(checkpoint_read_error(file), file.string() + ": state_hash mismatch: stored " + state_hash(c.state) +
                                      ", computed " + state_hash(changed.state) + " (file modified or corrupt)");
}

TEST(Checkpoint, ReplacingAValidFileGoesThroughRenameNeverInPlace) {
  const ScratchFolder scratch("replace");
  const fs::path& dir = scratch.path;
  const Checkpoint first = synthetic_checkpoint();
  write_checkpoint(dir / "c.h5", first);
  const std::string first_bytes = read_file(dir / "c.h5");
  // A second name for the old inode: an in-place rewrite would change what it shows.
  fs::create_hard_link(dir / "c.h5", dir / "old_inode.h5");
  Checkpoint second = first;
  second.state.step += 1;
  second.state.time += second.stage.clock.dt;
  write_checkpoint(dir / "c.h5", second);
  EXPECT_EQ(read_file(dir / "old_inode.h5"), first_bytes);
  EXPECT_EQ(read_checkpoint(dir / "c.h5").state.step, second.state.step);
  EXPECT_TRUE(tmp_files_in(dir).empty());
}

TEST(Checkpoint, FailedWriteIntoMissingFolderLeavesNothing) {
  const ScratchFolder scratch("missing_folder");
  const fs::path& dir = scratch.path;
  const fs::path target = dir / "no" / "such" / "folder" / "c.h5";
  try {
    write_checkpoint(target, synthetic_checkpoint());
    ADD_FAILURE() << "write into a missing folder succeeded";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find(target.string()), std::string::npos) << err.what();
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Checkpoint, FailedWriteLeavesExistingFileUntouched) {
  const ScratchFolder scratch("failed_write");
  const fs::path& dir = scratch.path;
  const Checkpoint first = synthetic_checkpoint();
  write_checkpoint(dir / "c.h5", first);
  const std::string before = read_file(dir / "c.h5");
  const std::string sidecar_before = read_file(dir / "c.xdmf");
  Checkpoint second = first;
  second.state.step += 1;
  // The write runs in a child process whose file-size limit is far below a checkpoint's size:
  // every write(2) past it fails with EFBIG, as on a full disk.
  EXPECT_EXIT(write_with_file_size_limit(dir / "c.h5", second, 4096), ::testing::ExitedWithCode(3), "");
  EXPECT_EQ(read_file(dir / "c.h5"), before);
  EXPECT_EQ(read_file(dir / "c.xdmf"), sidecar_before);
  EXPECT_TRUE(tmp_files_in(dir).empty()) << tmp_files_in(dir).front();
  EXPECT_TRUE(is_valid_checkpoint(dir / "c.h5"));
  // Without write permission on the folder (not testable as root, who may write anyway).
  if (geteuid() != 0) {
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
    EXPECT_THROW(write_checkpoint(dir / "c.h5", second), InputError);
    fs::permissions(dir, fs::perms::owner_all);
    EXPECT_EQ(read_file(dir / "c.h5"), before);
    EXPECT_TRUE(tmp_files_in(dir).empty());
  }
}

TEST(Checkpoint, InconsistentCheckpointIsNotWritten) {
  const ScratchFolder scratch("inconsistent");
  const fs::path& dir = scratch.path;
  Checkpoint c = synthetic_checkpoint();
  c.state.springs.failed.pop_back();
  EXPECT_THROW(write_checkpoint(dir / "c.h5", c), InternalError);
  c = synthetic_checkpoint();
  c.body.faces[1][2] = 5;
  EXPECT_THROW(write_checkpoint(dir / "c.h5", c), InternalError);
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(Checkpoint, BuiltQuickBodyRoundTripsAndWritesReproducibly) {
  const ScratchFolder scratch("built_body");
  const fs::path& dir = scratch.path;
  const Config config = quick_config();
  Checkpoint c = quick_built();
  c.config_toml = to_toml(config);
  write_checkpoint(dir / "a.h5", c);
  write_checkpoint(dir / "b.h5", c);
  EXPECT_EQ(read_file(dir / "a.h5"), read_file(dir / "b.h5"));
  const Checkpoint back = read_checkpoint(dir / "a.h5");
  expect_identical(c, back);
  EXPECT_EQ(back.body.particle_count(), 1042u);
  EXPECT_EQ(parse_config(back.config_toml, "stored").interior.radius, config.interior.radius);
}

namespace {

/// The bytes of address space this process has mapped (/proc/self/statm, first field).
rlim_t mapped_bytes() {
  std::ifstream statm("/proc/self/statm");
  unsigned long pages = 0;
  statm >> pages;
  return static_cast<rlim_t>(pages) * static_cast<rlim_t>(::sysconf(_SC_PAGESIZE));
}

/// Runs in a death-test child: with only `headroom` bytes of address space beyond what is mapped
/// now (ulimit -v), writes `c` to `file` and reads it back; exit code 3 when either failed with
/// an InputError naming the file, 0 when both succeeded (never a crash, never another error).
[[noreturn]] void write_and_read_with_headroom(const fs::path& file, const Checkpoint& c, rlim_t headroom) {
  const rlim_t limit = mapped_bytes() + headroom;
  rlimit rl{limit, limit};
  setrlimit(RLIMIT_AS, &rl);
  try {
    write_checkpoint(file, c);
    read_checkpoint(file);
  } catch (const InputError& e) {
    std::_Exit(std::string(e.what()).find(file.string() + ": ") != std::string::npos ? 3 : 4);
  } catch (...) {
    std::_Exit(5);
  }
  std::_Exit(0);
}

/// Runs in a death-test child: reads `file` with `headroom` bytes of address space beyond what is
/// mapped now; exit code 3 when the InputError holds `expected`, 4 otherwise.
[[noreturn]] void read_with_headroom(const fs::path& file, rlim_t headroom, const std::string& expected) {
  const rlim_t limit = mapped_bytes() + headroom;
  rlimit rl{limit, limit};
  setrlimit(RLIMIT_AS, &rl);
  std::_Exit(checkpoint_read_error(file).find(expected) != std::string::npos ? 3 : 4);
}

/// The exit of write_and_read_with_headroom when it wrote and read (0) or was refused (3).
bool written_or_refused(int status) { return WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 3); }

/// A copy of `valid` named `name` in `folder` edited in place by `edit` (the integrity record as
/// it was: the reader's checks must refuse the edit before reading what it declares).
template <typename Edit>
fs::path hostile_copy(const fs::path& valid, const fs::path& folder, const std::string& name, Edit edit) {
  const fs::path file = folder / name;
  fs::copy_file(valid, file, fs::copy_options::overwrite_existing);
  edit_in_place(file, edit);
  return file;
}

/// Creates at `path` a chunked dataset declaring `count` elements of `type`, none written (so
/// the file stays small).
void declare_unwritten_dataset(hid_t f, const char* path, hid_t type, hsize_t count) {
  h5::Dataspace space(h5::check(H5Screate_simple(1, &count, nullptr), path));
  h5::PropList dcpl(h5::check(H5Pcreate(H5P_DATASET_CREATE), path));
  const hsize_t chunk = 1 << 16;
  h5::check(H5Pset_chunk(dcpl.get(), 1, &chunk), path);
  h5::Dataset set(h5::check(H5Dcreate2(f, path, type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT), path));
}

}  // namespace

TEST(Checkpoint, FilesThatDeclareMoreThanTheyHoldOrPointElsewhereAreRefusedBeforeReading) {
  // Issue 28: /integrity/path declared as 2^40 strings gave "internal error: std::bad_alloc"; a
  // 150 KB file declaring 400,000,000 doubles had inspect allocate 3.1 GB before refusing it.
  const ScratchFolder scratch("hostile");
  const fs::path& dir = scratch.path;
  write_checkpoint(dir / "valid.h5", synthetic_checkpoint());
  const fs::path valid = dir / "valid.h5";
  struct Case {
    fs::path file;
    std::string expected;
  };
  std::vector<Case> cases;
  cases.push_back({hostile_copy(valid, dir, "integrity_path.h5",
                                [](hid_t f) {
                                  H5Ldelete(f, "/integrity/path", H5P_DEFAULT);
                                  h5::Type type = h5::fixed_string_type(32);
                                  declare_unwritten_dataset(f, "/integrity/path", type.get(), hsize_t{1} << 40);
                                }),
                   "dataset /integrity/path declares 1099511627776 values of 32 bytes, more than the file's"});
  cases.push_back({hostile_copy(valid, dir, "huge_dataset.h5",
                                [](hid_t f) {
                                  declare_unwritten_dataset(f, "/checkpoint/huge", H5T_IEEE_F64LE, 400'000'000);
                                }),
                   "dataset /checkpoint/huge declares 400000000 values of 8 bytes"});
  cases.push_back({hostile_copy(valid, dir, "huge_mass.h5",
                                [](hid_t f) {
                                  H5Ldelete(f, "/particles/body/mass", H5P_DEFAULT);
                                  declare_unwritten_dataset(f, "/particles/body/mass", H5T_IEEE_F64LE, 400'000'000);
                                }),
                   "/particles/body/mass declares 400000000 values"});
  cases.push_back({hostile_copy(valid, dir, "external_link.h5",
                                [](hid_t f) {
                                  h5::check(H5Lcreate_external("valid.h5", "/checkpoint", f, "/checkpoint/elsewhere",
                                                               H5P_DEFAULT, H5P_DEFAULT),
                                            "external link");
                                }),
                   "link /checkpoint/elsewhere is an external link (to another file); refused"});
  cases.push_back({hostile_copy(valid, dir, "external_storage.h5",
                                [](hid_t f) {
                                  const hsize_t n = 4;
                                  h5::Dataspace space(h5::check(H5Screate_simple(1, &n, nullptr), "space"));
                                  h5::PropList dcpl(h5::check(H5Pcreate(H5P_DATASET_CREATE), "dcpl"));
                                  h5::check(H5Pset_external(dcpl.get(), "raw.bin", 0, n * 8), "external");
                                  h5::Dataset set(h5::check(H5Dcreate2(f, "/checkpoint/outside", H5T_IEEE_F64LE,
                                                                       space.get(), H5P_DEFAULT, dcpl.get(),
                                                                       H5P_DEFAULT),
                                                            "create"));
                                }),
                   "dataset /checkpoint/outside keeps its values in other files"});
  for (const Case& c : cases) {
    const std::string message = checkpoint_read_error(c.file);
    EXPECT_EQ(message.rfind(c.file.string() + ": ", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_LT(fs::file_size(c.file), 1u << 20) << c.file;  // small files, as in the issue
  }
  // The refusals come before the allocation: with 200 MB of address space the reader reports the
  // declaration, not a lack of memory.
  EXPECT_EXIT(read_with_headroom(dir / "huge_dataset.h5", rlim_t{200} << 20, "declares 400000000"),
              ::testing::ExitedWithCode(3), "");
}

TEST(Checkpoint, RunningOutOfMemoryWhileWritingOrReadingIsAnErrorNamingTheFile) {
  // Issue 28: with ulimit -v at 40-41 MB HDF5 crashed (SIGSEGV in H5AC_create, opening the
  // in-memory image) while writing a checkpoint; at 39 MB "internal error: std::bad_alloc". At
  // every headroom the write and the read either succeed or are an InputError naming the file,
  // and a failed write leaves the file that was there.
  const ScratchFolder scratch("memory");
  const fs::path file = scratch.path / "build.h5";
  const Checkpoint& body = quick_built();
  write_checkpoint(file, body);
  const std::string before = read_file(file);
  Checkpoint changed = body;
  changed.state.step += 1;
  for (rlim_t mb = 0; mb <= 64; mb += 4) {
    EXPECT_EXIT(write_and_read_with_headroom(file, changed, mb << 20), written_or_refused, "") << mb << " MB of headroom";
    const std::string now = read_file(file);
    if (now != before) {
      EXPECT_EQ(read_checkpoint(file).state.step, changed.state.step) << mb << " MB: a damaged file";
      write_checkpoint(file, body);
    }
    EXPECT_TRUE(tmp_files_in(scratch.path).empty()) << mb << " MB";
  }
}
