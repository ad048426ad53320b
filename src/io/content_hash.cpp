// The integrity check of checkpoint files (content_hash.hpp): a generic walk over every object
// of an HDF5 file, digesting each with XXH3-128, and the /integrity record that stores them.
#include "io/content_hash.hpp"

#include <fmt/format.h>

#include <cstdint>
#include <exception>
#include <map>

#include "io/hdf5_handles.hpp"
#include "io/xxh3_hasher.hpp"

namespace tidalcrust {

namespace {

/// The datatype as a reader interprets it, described in the library's own terms (not in
/// HDF5's encoded message, whose version may differ between library releases): class and size,
/// and per class byte order, sign, bit layout, string padding and character set. Composite
/// types (compound, array, enum, ...) fall back to H5Tencode.
void hash_type(Xxh3Hasher& h, hid_t type, const std::string& what) {
  const H5T_class_t type_class = H5Tget_class(type);
  h.i64(type_class);
  h.i64(static_cast<std::int64_t>(H5Tget_size(type)));
  switch (type_class) {
    case H5T_INTEGER:
    case H5T_BITFIELD:
      h.i64(H5Tget_order(type));
      h.i64(type_class == H5T_INTEGER ? H5Tget_sign(type) : 0);
      h.i64(static_cast<std::int64_t>(H5Tget_precision(type)));
      h.i64(H5Tget_offset(type));
      return;
    case H5T_FLOAT: {
      std::size_t field[5] = {0, 0, 0, 0, 0};
      H5Tget_fields(type, &field[0], &field[1], &field[2], &field[3], &field[4]);
      h.i64(H5Tget_order(type));
      h.i64(static_cast<std::int64_t>(H5Tget_precision(type)));
      h.i64(H5Tget_offset(type));
      for (std::size_t f : field) h.i64(static_cast<std::int64_t>(f));
      h.i64(static_cast<std::int64_t>(H5Tget_ebias(type)));
      h.i64(H5Tget_norm(type));
      return;
    }
    case H5T_STRING:
      h.i64(H5Tis_variable_str(type));
      h.i64(H5Tget_strpad(type));
      h.i64(H5Tget_cset(type));
      return;
    case H5T_REFERENCE:
      h.i64(H5Tequal(type, H5T_STD_REF_OBJ));
      return;
    default: {
      std::size_t size = 0;
      if (H5Tencode(type, nullptr, &size) < 0) throw h5::Error("cannot describe the datatype of " + what);
      std::string encoded(size, '\0');
      if (H5Tencode(type, encoded.data(), &size) < 0) throw h5::Error("cannot describe the datatype of " + what);
      h.text(encoded);
    }
  }
}

/// Hashes the datatype, the shape and the values of a dataset or attribute: `read(memory_type,
/// buffer)` reads all values. Fixed-size values are read in their stored type (no conversion:
/// the bytes as stored); variable-length strings by their characters.
template <typename Read>
void hash_values(Xxh3Hasher& h, hid_t type, hid_t space, const std::string& what, std::vector<char>& buffer,
                 Read read) {
  hash_type(h, type, what);
  h.i64(H5Sget_simple_extent_type(space));
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank < 0) throw h5::Error("cannot read the shape of " + what);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space, dims.data(), nullptr) < 0)
    throw h5::Error("cannot read the shape of " + what);
  h.i64(rank);
  for (hsize_t d : dims) h.i64(static_cast<std::int64_t>(d));
  const hssize_t count = H5Sget_simple_extent_npoints(space);
  if (count < 0) throw h5::Error("cannot read the shape of " + what);
  if (count == 0) return;
  if (H5Tget_class(type) == H5T_STRING && H5Tis_variable_str(type) > 0) {
    for (const std::string& s : h5::read_strings(type, static_cast<std::size_t>(count), what, read)) h.text(s);
    return;
  }
  // Variable-length data read in its stored type would give memory addresses, not values.
  const H5T_class_t type_class = H5Tget_class(type);
  const bool composite = type_class == H5T_COMPOUND || type_class == H5T_ARRAY;
  if (type_class == H5T_VLEN || (composite && (H5Tdetect_class(type, H5T_VLEN) > 0 || H5Tdetect_class(type, H5T_STRING) > 0)))
    throw h5::Error(what + ": variable-length data (or strings inside a compound type) cannot be digested");
  const std::size_t bytes = H5Tget_size(type) * static_cast<std::size_t>(count);
  buffer.resize(bytes);
  h5::Type memory(h5::check(H5Tcopy(type), "H5Tcopy"));
  h5::check(read(memory.get(), buffer.data()), "cannot read " + what + " (corrupt data)");
  h.i64(static_cast<std::int64_t>(bytes));
  h.bytes(buffer.data(), bytes);
}

struct Walk {
  std::vector<ObjectDigest> rows;
  std::vector<char> buffer;  // reused for every read
  std::string error;         // what stopped the walk inside an HDF5 callback
};

/// One row per attribute of `object` (at `path`), by name in increasing order.
void digest_attributes(hid_t object, const std::string& path, Walk& walk) {
  struct Context {
    const std::string& path;
    Walk& walk;
  } context{path, walk};
  auto visit = [](hid_t loc, const char* name, const H5A_info_t*, void* data) -> herr_t {
    auto& c = *static_cast<Context*>(data);
    try {
      const std::string row = (c.path == "/" ? std::string("/") : c.path) + "@" + name;
      const std::string what = "attribute " + row;
      h5::Attribute attr(h5::check(H5Aopen(loc, name, H5P_DEFAULT), "cannot open " + what));
      h5::Type type(h5::check(H5Aget_type(attr.get()), "cannot read the type of " + what));
      h5::Dataspace space(h5::check(H5Aget_space(attr.get()), "cannot read the shape of " + what));
      Xxh3Hasher h;
      h.text("attribute");
      h.text(row);
      h5::check_fits_in_file(attr.get(), type.get(), space.get(), what);
      hash_values(h, type.get(), space.get(), what, c.walk.buffer,
                  [&](hid_t memory, void* buffer) { return H5Aread(attr.get(), memory, buffer); });
      c.walk.rows.push_back({row, h.hex()});
      return 0;
    } catch (const std::exception& e) {
      c.walk.error = e.what();
      return -1;
    }
  };
  hsize_t index = 0;
  if (H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, &index, visit, &context) < 0)
    throw h5::Error(!walk.error.empty() ? walk.error : "cannot list the attributes of " + path + " (corrupt)");
}

/// The row of the object a hard link `path` leads to, then its attributes' rows.
void digest_object(hid_t object, const std::string& path, Walk& walk) {
  Xxh3Hasher h;
  switch (H5Iget_type(object)) {
    case H5I_GROUP:
      h.text("group");
      h.text(path);
      break;
    case H5I_DATASET: {
      const std::string what = "dataset " + path;
      h5::Type type(h5::check(H5Dget_type(object), "cannot read the type of " + what));
      h5::Dataspace space(h5::check(H5Dget_space(object), "cannot read the shape of " + what));
      h5::check_dataset_readable(object, type.get(), space.get(), what);
      h.text("dataset");
      h.text(path);
      hash_values(h, type.get(), space.get(), what, walk.buffer, [&](hid_t memory, void* buffer) {
        return H5Dread(object, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
      });
      break;
    }
    case H5I_DATATYPE:
      h.text("datatype");
      h.text(path);
      hash_type(h, object, "datatype " + path);
      break;
    default:
      throw h5::Error("object " + path + " is of an unknown kind (corrupt)");
  }
  walk.rows.push_back({path, h.hex()});
  digest_attributes(object, path, walk);
}

/// One link of the walk: hard links by their object, soft and external links by their target.
void digest_link(hid_t group, const char* name, const std::string& path, H5L_type_t link_type, std::size_t size,
                 Walk& walk) {
  if (link_type == H5L_TYPE_EXTERNAL) throw h5::Error("link " + path + " is an external link (to another file); refused");
  if (link_type == H5L_TYPE_HARD) {
    h5::Object object(h5::check(H5Oopen(group, name, H5P_DEFAULT), "cannot open " + path + " (corrupt)"));
    digest_object(object.get(), path, walk);
    return;
  }
  std::string target(size, '\0');
  if (size > 0 && H5Lget_val(group, name, target.data(), size, H5P_DEFAULT) < 0)
    throw h5::Error("cannot read the link " + path + " (corrupt)");
  Xxh3Hasher h;
  h.text("link");
  h.text(path);
  h.i64(link_type);
  h.text(target);
  walk.rows.push_back({path, h.hex()});
}

bool in_integrity_group(const std::string& path) {
  const std::string group = integrity_group;
  return path == group || (path.size() > group.size() && path.compare(0, group.size(), group) == 0 &&
                           path[group.size()] == '/');
}

}  // namespace

std::vector<ObjectDigest> object_digests(hid_t file) {
  Walk walk;
  h5::Group root(h5::check(H5Gopen2(file, "/", H5P_DEFAULT), "cannot open the root group (corrupt)"));
  digest_object(root.get(), "/", walk);
  auto visit = [](hid_t group, const char* name, const H5L_info_t* info, void* data) -> herr_t {
    auto& w = *static_cast<Walk*>(data);
    try {
      const std::string path = std::string("/") + name;
      if (in_integrity_group(path)) return 0;
      digest_link(group, name, path, info->type, info->type == H5L_TYPE_HARD ? 0 : info->u.val_size, w);
      return 0;
    } catch (const std::exception& e) {
      w.error = e.what();
      return -1;
    }
  };
  if (H5Lvisit(root.get(), H5_INDEX_NAME, H5_ITER_INC, visit, &walk) < 0)
    throw h5::Error(!walk.error.empty() ? walk.error : "cannot walk the file's groups (corrupt): " + h5::error_stack_text());
  return std::move(walk.rows);
}

std::string content_hash(const std::vector<ObjectDigest>& rows) {
  Xxh3Hasher h;
  h.i64(static_cast<std::int64_t>(rows.size()));
  for (const auto& row : rows) {
    h.text(row.path);
    h.text(row.digest);
  }
  return h.hex();
}

void write_integrity_record(hid_t file, const std::vector<ObjectDigest>& rows) {
  if (h5::exists(file, integrity_group))
    h5::check(H5Ldelete(file, integrity_group, H5P_DEFAULT), fmt::format("cannot replace {}", integrity_group));
  h5::Group group = h5::create_group(file, integrity_group);
  h5::write_string_attribute(group.get(), "content_hash", content_hash(rows));
  h5::write_string_attribute(group.get(), "algorithm",
                             "XXH3-128 per object (path, datatype, shape, stored bytes) and over the (path, digest) "
                             "rows; see docs/checkpoint-layout.md");
  std::vector<std::string> paths, digests;
  for (const auto& row : rows) {
    paths.push_back(row.path);
    digests.push_back(row.digest);
  }
  h5::write_string_array_dataset(group.get(), "path", paths);
  h5::write_string_array_dataset(group.get(), "digest", digests);
}

void verify_integrity(hid_t file) {
  const std::string record = integrity_group;
  if (!h5::exists(file, record))
    throw h5::Error("group " + record +
                    " (the content hashes) is missing: written by a tidalcrust without the integrity check, or damaged");
  std::vector<ObjectDigest> stored;
  std::string stored_hash;
  {
    h5::Group group = h5::open_group(file, record);
    stored_hash = h5::read_string_attribute(group.get(), "content_hash");
    const auto paths = h5::read_string_array_dataset(group.get(), "path");
    const auto digests = h5::read_string_array_dataset(group.get(), "digest");
    if (paths.size() != digests.size())
      throw h5::Error(fmt::format("the integrity record {} is damaged ({} paths, {} digests)", record, paths.size(),
                                  digests.size()));
    for (std::size_t i = 0; i < paths.size(); ++i) stored.push_back({paths[i], digests[i]});
  }
  if (content_hash(stored) != stored_hash)
    throw h5::Error(fmt::format("the integrity record {} is damaged (its rows do not give {}@content_hash)", record,
                                record));
  const std::vector<ObjectDigest> computed = object_digests(file);
  if (computed == stored) return;
  std::map<std::string, const std::string*> written;
  for (const auto& row : stored) written.emplace(row.path, &row.digest);
  std::map<std::string, bool> present;
  for (const auto& row : computed) {
    present.emplace(row.path, true);
    const auto found = written.find(row.path);
    if (found == written.end())
      throw h5::Error(row.path + " was added since the file was written (content hash mismatch)");
    if (*found->second != row.digest)
      throw h5::Error(row.path + " changed since the file was written (content hash mismatch)");
  }
  for (const auto& row : stored)
    if (!present.count(row.path))
      throw h5::Error(row.path + " was removed since the file was written (content hash mismatch)");
  throw h5::Error("the objects of the file are in another order than when it was written (content hash mismatch)");
}

}  // namespace tidalcrust
