#pragma once
// The integrity check of checkpoint files: an XXH3-128 digest of every object of the file
// (each group, dataset, link and attribute) and one digest over all of them, stored in the
// group /integrity when the file is written and verified on every read. It walks the file
// generically, so groups, datasets and attributes added to the layout are covered without any
// change here. docs/checkpoint-layout.md, "What is checked on reading".
#include <hdf5.h>

#include <string>
#include <vector>

namespace tidalcrust {

/// The group holding the stored digests; the walk skips it (and only it).
inline constexpr const char* integrity_group = "/integrity";

/// The digest of one object: `path` names a group or dataset ("/particles/body/mass") or an
/// attribute ("/checkpoint@softening"; the root's are "/@name"); `digest` is 32 hex digits.
struct ObjectDigest {
  std::string path;
  std::string digest;
  bool operator==(const ObjectDigest&) const = default;
};

/// Walks the open file `file` in a fixed order (links by name, increasing, depth first; each
/// object's attributes by name) and digests every object except /integrity and its contents:
/// for a group its path; for a dataset (and an attribute) its path, its encoded datatype
/// (class, size, byte order, sign, string padding...), its shape and its raw data as stored
/// (variable-length strings by their characters); for a soft or external link its target.
/// A dataset reached through two hard links is digested under both paths.
/// Throws h5::Error naming the object when it cannot be read (corrupt file) or holds a
/// variable-length type other than strings (not digestible).
std::vector<ObjectDigest> object_digests(hid_t file);

/// XXH3-128 (32 hex digits) of the rows in order: each path and digest, length-prefixed.
std::string content_hash(const std::vector<ObjectDigest>& rows);

/// Stores `rows` in `file`: /integrity@content_hash (content_hash(rows)), /integrity@algorithm,
/// and the datasets /integrity/path and /integrity/digest [n] (strings). Replaces an existing
/// /integrity. Throws h5::Error.
void write_integrity_record(hid_t file, const std::vector<ObjectDigest>& rows);

/// Recomputes the digests of `file` and compares them with its /integrity record. Throws
/// h5::Error with a one-line message naming the first object that changed, was added or was
/// removed since the file was written ("/particles/body/mass changed since the file was written
/// (content hash mismatch)"), or saying that the record itself is missing or damaged.
void verify_integrity(hid_t file);

}  // namespace tidalcrust
