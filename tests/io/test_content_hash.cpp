// The integrity check of checkpoint files (io/content_hash.hpp): every dataset, attribute and
// link of a checkpoint is covered, so a file changed after writing (an edit with an HDF5 tool,
// a zeroed page, an added or removed object) is refused with the object's name, and an
// unmodified file reads back unchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"
#include "io/content_hash.hpp"
#include "io/hdf5_handles.hpp"
#include "support/bad_checkpoints.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"
#include "support/synthetic_checkpoint.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {


/// The one-line message for `object` of `file` changed, added or removed after writing.
std::string changed_message(const fs::path& file, const std::string& object, const char* how = "changed") {
  return file.string() + ": " + object + " " + how + " since the file was written (content hash mismatch)";
}

}  // namespace

TEST(ContentHash, RecordListsEveryObjectAndAnUnmodifiedFileReadsBack) {
  const ScratchFolder scratch("content_roundtrip");
  const fs::path file = scratch.path / "c.h5";
  const Checkpoint c = synthetic_checkpoint();
  write_checkpoint(file, c);
  EXPECT_EQ(checkpoint_read_error(file), "(no InputError)");

  h5::File f = h5::open_file_readonly(file);
  const std::vector<ObjectDigest> rows = object_digests(f.get());
  h5::Group record = h5::open_group(f.get(), integrity_group);
  const auto paths = h5::read_string_array_dataset(record.get(), "path");
  const auto digests = h5::read_string_array_dataset(record.get(), "digest");
  ASSERT_EQ(paths.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(paths[i], rows[i].path);
    EXPECT_EQ(digests[i], rows[i].digest) << rows[i].path;
    EXPECT_EQ(rows[i].digest.size(), 32u);
    EXPECT_EQ(rows[i].path.rfind(integrity_group, 0), std::string::npos) << "the walk must skip its own record";
  }
  EXPECT_EQ(h5::read_string_attribute(record.get(), "content_hash"), content_hash(rows));
  // Groups, datasets (both hard links of the shared step), attributes of every level.
  for (const char* expected : {"/", "/h5md@version", "/particles/body/mass", "/particles/body/velocity/step",
                               "/particles/body/position/step", "/connectivity/springs", "/checkpoint@softening",
                               "/checkpoint@state_hash", "/checkpoint/record@damping", "/checkpoint/record/snapshot_steps",
                               "/parameters/config", "/parameters/provenance@git_commit",
                               "/checkpoint/timeseries/kinetic_energy", "/checkpoint/perturber"}) {
    bool found = false;
    for (const auto& row : rows) found = found || row.path == expected;
    EXPECT_TRUE(found) << expected;
  }
  // Equal checkpoints still give byte-identical files.
  write_checkpoint(scratch.path / "again.h5", read_checkpoint(file));
  EXPECT_EQ(read_file(scratch.path / "again.h5"), read_file(file));
}

// Issue 10 item 2: one interior mass edited in place kept its state_hash and was accepted.
TEST(ContentHash, EditedDatasetsAndAttributesAreNamed) {
  const ScratchFolder scratch("content_edits");
  const fs::path valid = scratch.path / "stretch.h5";
  const Checkpoint& stretched = quick_stretched();
  write_checkpoint(valid, stretched);
  const double mass = stretched.body.mass[0];
  ASSERT_EQ(stretched.body.species[0], 0) << "particle 0 is an interior node";
  const auto spring = stretched.body.springs[7];
  const auto kind = static_cast<std::uint8_t>((stretched.body.spring_kind[0] + 1) % 3);
  const double factor = stretched.stage.as<StretchRecord>().stretch_factor;
  struct Edit {
    std::string object;
    std::function<void(hid_t)> edit;
  } edits[] = {
      {"/particles/body/mass", [&](hid_t f) { overwrite_element(f, "/particles/body/mass", 0, std::nextafter(mass, 2.0)); }},
      {"/connectivity/springs",
       [&](hid_t f) { overwrite_element<std::int32_t>(f, "/connectivity/springs", 15, spring[1] == 1 ? 2 : 1); }},
      {"/checkpoint/springs/kind", [&](hid_t f) { overwrite_element(f, "/checkpoint/springs/kind", 0, kind); }},
      {"/checkpoint/hinges/stiffness", [&](hid_t f) { overwrite_element(f, "/checkpoint/hinges/stiffness", 3, 1.0); }},
      {"/checkpoint@softening", [&](hid_t f) { overwrite_attribute(f, "/checkpoint", "softening", 0.5); }},
      {"/checkpoint/record@stretch_factor",
       [&](hid_t f) { overwrite_attribute(f, "/checkpoint/record", "stretch_factor", factor * 2); }},
      {"/checkpoint@dt", [&](hid_t f) { overwrite_attribute(f, "/checkpoint", "dt", 0.001); }},
  };
  for (const auto& e : edits) {
    const fs::path file = scratch.path / "edited.h5";
    fs::copy_file(valid, file, fs::copy_options::overwrite_existing);
    edit_in_place(file, e.edit);
    EXPECT_EQ(checkpoint_read_error(file), changed_message(file, e.object));
  }
}

TEST(ContentHash, AddedOrRemovedObjectsAreRefused) {
  const ScratchFolder scratch("content_add_remove");
  const fs::path valid = scratch.path / "valid.h5";
  write_checkpoint(valid, synthetic_checkpoint());
  struct Edit {
    std::string object, how;
    std::function<void(hid_t)> edit;
  } edits[] = {
      {"/extra", "was added", [](hid_t f) { h5::write_dataset<double>(f, "/extra", std::vector<double>{1.0}, {1}); }},
      {"/newgroup", "was added", [](hid_t f) { h5::create_group(f, "/newgroup"); }},
      {"/checkpoint@note", "was added",
       [](hid_t f) { h5::write_string_attribute(h5::open_group(f, "/checkpoint").get(), "note", "edited"); }},
      {"/particles/body/mass@comment", "was added",
       [](hid_t f) {
         h5::Object mass(H5Oopen(f, "/particles/body/mass", H5P_DEFAULT));
         h5::write_string_attribute(mass.get(), "comment", "edited");
       }},
      {"/checkpoint@diagnostic", "was removed",
       [](hid_t f) { H5Adelete(h5::open_group(f, "/checkpoint").get(), "diagnostic"); }},
      {"/checkpoint/timeseries/failed", "was removed",
       [](hid_t f) { H5Ldelete(f, "/checkpoint/timeseries/failed", H5P_DEFAULT); }},
      {"/particles/body/velocity/step", "was removed",
       [](hid_t f) { H5Ldelete(f, "/particles/body/velocity/step", H5P_DEFAULT); }},
  };
  for (const auto& e : edits) {
    const fs::path file = scratch.path / "edited.h5";
    fs::copy_file(valid, file, fs::copy_options::overwrite_existing);
    edit_in_place(file, e.edit);
    EXPECT_EQ(checkpoint_read_error(file), changed_message(file, e.object, e.how.c_str()));
  }
  EXPECT_EQ(checkpoint_read_error(valid), "(no InputError)");
}

TEST(ContentHash, MissingOrDamagedRecordIsRefused) {
  const ScratchFolder scratch("content_record");
  const fs::path valid = scratch.path / "valid.h5";
  write_checkpoint(valid, synthetic_checkpoint());
  const fs::path file = scratch.path / "edited.h5";

  fs::copy_file(valid, file, fs::copy_options::overwrite_existing);
  edit_in_place(file, [](hid_t f) { H5Ldelete(f, integrity_group, H5P_DEFAULT); });
  EXPECT_EQ(checkpoint_read_error(file), file.string() + ": group /integrity (the content hashes) is missing: written by a "
                                              "tidalcrust without the integrity check, or damaged");

  // A stored digest changed (to that of an edit the editor wanted to hide) no longer matches
  // the record's own hash.
  fs::copy_file(valid, file, fs::copy_options::overwrite_existing);
  edit_in_place(file, [](hid_t f) {
    h5::Group g = h5::open_group(f, integrity_group);
    auto digests = h5::read_string_array_dataset(g.get(), "digest");
    digests[3][0] = digests[3][0] == '0' ? '1' : '0';
    H5Ldelete(g.get(), "digest", H5P_DEFAULT);
    h5::write_string_array_dataset(g.get(), "digest", digests);
  });
  EXPECT_EQ(checkpoint_read_error(file), file.string() + ": the integrity record /integrity is damaged (its rows do not give "
                                              "/integrity@content_hash)");
}

// Issue 10 item 2: zeroing one 4 KiB page passed `inspect` in 38 of 103 positions with changed
// content. Now every page either is refused or reads back as exactly the written checkpoint
// (written again, it gives the same bytes: nothing the file holds differs).
TEST(ContentHash, ZeroingAnyPageIsRefusedOrReadsTheSameContent) {
  const ScratchFolder scratch("content_pages");
  const fs::path valid = scratch.path / "relax.h5";
  write_checkpoint(valid, quick_relaxed(false));
  const std::string bytes = read_file(valid);
  constexpr std::size_t page = 4096;
  const std::size_t pages = (bytes.size() + page - 1) / page;
  std::size_t refused = 0;
  const fs::path file = scratch.path / "zeroed.h5", again = scratch.path / "again.h5";
  for (std::size_t p = 0; p < pages; ++p) {
    std::string zeroed = bytes;
    const std::size_t end = std::min(bytes.size(), (p + 1) * page);
    std::fill(zeroed.begin() + static_cast<std::ptrdiff_t>(p * page), zeroed.begin() + static_cast<std::ptrdiff_t>(end), '\0');
    if (zeroed == bytes) continue;  // a page of zeros already
    write_file(file, zeroed);
    try {
      const Checkpoint c = read_checkpoint(file);
      write_checkpoint(again, c);
      EXPECT_EQ(read_file(again) == bytes, true) << "page " << p << " zeroed: read a different content";
    } catch (const InputError& e) {
      ++refused;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind(file.string() + ": ", 0), 0u) << e.what();
    }
  }
  std::printf("zeroed pages: %zu of %zu refused, the rest read the written content unchanged\n", refused, pages);
  EXPECT_GT(refused, pages / 2);
}
