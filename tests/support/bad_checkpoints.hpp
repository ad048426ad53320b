#pragma once
// Damaged copies of a valid checkpoint that read_checkpoint must reject (make_bad_checkpoints),
// and in-place edits of a checkpoint as an HDF5 tool makes them (edit_in_place, overwrite_*).
#include <filesystem>
#include <string>
#include <vector>

#include "base/errors.hpp"
#include "io/checkpoint_file.hpp"
#include "io/content_hash.hpp"
#include "io/hdf5_handles.hpp"
#include "support/files.hpp"

namespace tidalcrust::test_support {

struct BadCheckpoint {
  std::string what;              ///< the kind of damage
  std::filesystem::path file;
  std::string expected_message;  ///< substring of the InputError message (dataset or cause)
};

/// The message of the InputError read_checkpoint(file) throws, "(no InputError)" if it reads.
inline std::string checkpoint_read_error(const std::filesystem::path& file) {
  try {
    read_checkpoint(file);
  } catch (const InputError& err) {
    return err.what();
  }
  return "(no InputError)";
}

/// Opens `file` read-write in place and lets `edit` change it, as a user editing a checkpoint
/// with an HDF5 tool would; the integrity record is left as it was (the edit shows).
template <typename Edit>
void edit_in_place(const std::filesystem::path& file, Edit edit) {
  h5::silence_errors();
  h5::File f(h5::check(H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), "open for editing"));
  edit(f.get());
  f.close("close after editing");
}

/// Overwrites element `index` (row-major over all dimensions) of the dataset `path` of an open
/// file in place with `value`.
template <typename T>
void overwrite_element(hid_t f, const char* path, hsize_t index, T value) {
  h5::Dataset set(h5::check(H5Dopen2(f, path, H5P_DEFAULT), path));
  h5::Dataspace space(h5::check(H5Dget_space(set.get()), path));
  std::vector<hsize_t> coordinates(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space.get())));
  std::vector<hsize_t> dims(coordinates.size());
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  for (std::size_t d = coordinates.size(); d-- > 0;) {
    coordinates[d] = index % dims[d];
    index /= dims[d];
  }
  h5::check(H5Sselect_elements(space.get(), H5S_SELECT_SET, 1, coordinates.data()), path);
  const hsize_t one = 1;
  h5::Dataspace memory(h5::check(H5Screate_simple(1, &one, nullptr), path));
  h5::check(H5Dwrite(set.get(), h5::type_of<T>().memory, memory.get(), space.get(), H5P_DEFAULT, &value), path);
}

/// Replaces the scalar numeric attribute `name` of the group `path` with `value` (deleted and
/// written again, as h5py's `attrs[name] = value` does).
template <typename T>
void overwrite_attribute(hid_t f, const char* path, const char* name, T value) {
  h5::Group group = h5::open_group(f, path);
  h5::check(H5Adelete(group.get(), name), std::string("delete ") + name);
  h5::write_attribute<T>(group.get(), name, value);
}

/// Opens a copy of `valid` named `name` in `folder` read-write, lets `edit` change it and then
/// re-seals it (a fresh integrity record of the edited content), so that the checks behind the
/// integrity check (shapes, names, indices, state_hash) are what refuses it.
template <typename Edit>
std::filesystem::path edited_copy(const std::filesystem::path& valid, const std::filesystem::path& folder,
                                  const std::string& name, Edit edit) {
  auto file = folder / name;
  std::filesystem::copy_file(valid, file, std::filesystem::copy_options::overwrite_existing);
  edit_in_place(file, [&](hid_t f) {
    edit(f);
    write_integrity_record(f, object_digests(f));
  });
  return file;
}

/// Makes every damaged variant of the valid checkpoint `valid` inside `folder`: one per failure
/// mode, each with the text its error message must contain (besides the file name).
inline std::vector<BadCheckpoint> make_bad_checkpoints(const std::filesystem::path& valid,
                                                       const std::filesystem::path& folder) {
  std::vector<BadCheckpoint> bad;
  const std::string bytes = read_file(valid);

  bad.push_back({"missing file", folder / "missing.h5", "no such checkpoint file"});

  write_file(folder / "empty.h5", "");
  bad.push_back({"empty file", folder / "empty.h5", "not an HDF5 file or truncated"});

  write_file(folder / "truncated.h5", bytes.substr(0, bytes.size() / 2));
  bad.push_back({"truncated file", folder / "truncated.h5", "not an HDF5 file or truncated"});

  write_file(folder / "text.h5", "this is not HDF5\n");
  bad.push_back({"text file", folder / "text.h5", "not an HDF5 file or truncated"});

  haddr_t position_offset;
  {
    h5::File f = h5::open_file_readonly(valid);
    position_offset = h5::dataset_offset(f.get(), "/particles/body/position/value");
  }
  std::string flipped = bytes;
  flipped.at(position_offset + 8 * 4 + 3) ^= 0x10;  // inside position value 4 (particle 1, y)
  write_file(folder / "flipped.h5", flipped);
  bad.push_back({"flipped byte in positions", folder / "flipped.h5",
                 "/particles/body/position/value changed since the file was written (content hash mismatch)"});

  bad.push_back({"missing dataset",
                 edited_copy(valid, folder, "missing_dataset.h5",
                             [](hid_t f) { H5Ldelete(f, "/checkpoint/springs/failed", H5P_DEFAULT); }),
                 "/checkpoint/springs/failed"});

  bad.push_back({"wrong format_version", edited_copy(valid, folder, "version.h5", [](hid_t f) {
                   h5::Group g = h5::open_group(f, "/checkpoint");
                   H5Adelete(g.get(), "format_version");
                   h5::write_attribute<std::int64_t>(g.get(), "format_version", 99);
                 }),
                 "written by a newer tidalcrust (format 99); this one reads up to " +
                     std::to_string(checkpoint_format_version)});

  bad.push_back({"wrong stage", edited_copy(valid, folder, "stage.h5", [](hid_t f) {
                   h5::Group g = h5::open_group(f, "/checkpoint");
                   H5Adelete(g.get(), "stage");
                   h5::write_string_attribute(g.get(), "stage", "analyse");
                 }),
                 "/checkpoint@stage is 'analyse'"});

  bad.push_back({"wrong shape", edited_copy(valid, folder, "shape.h5", [](hid_t f) {
                   H5Ldelete(f, "/particles/body/mass", H5P_DEFAULT);
                   std::vector<double> mass = {0.5, 0.5};
                   h5::write_dataset(f, "/particles/body/mass", mass, {2});
                 }),
                 "/particles/body/mass has shape [2]"});

  bad.push_back({"wrong type", edited_copy(valid, folder, "type.h5", [](hid_t f) {
                   H5Ldelete(f, "/checkpoint/hinges/rest_angle", H5P_DEFAULT);
                   std::vector<std::int32_t> angles = {0, 0, 0};
                   h5::write_dataset(f, "/checkpoint/hinges/rest_angle", angles, {3});
                 }),
                 "/checkpoint/hinges/rest_angle"});

  bad.push_back({"index out of range", edited_copy(valid, folder, "index.h5", [](hid_t f) {
                   auto springs = h5::read_dataset<std::int32_t>(f, "/connectivity/springs");
                   springs.values[5] = 99;
                   H5Ldelete(f, "/connectivity/springs", H5P_DEFAULT);
                   h5::write_dataset(f, "/connectivity/springs", springs.values, springs.dims);
                 }),
                 "/connectivity/springs row 2: particle index 99"});

  bad.push_back({"zero time step", edited_copy(valid, folder, "dt.h5",
                                               [](hid_t f) { overwrite_attribute<double>(f, "/checkpoint", "dt", 0.0); }),
                 "/checkpoint@dt is 0, expected a finite number > 0"});
  return bad;
}

}  // namespace tidalcrust::test_support
