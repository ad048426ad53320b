#pragma once
// Small RAII handles over the HDF5 C API and typed read/write helpers for checkpoint files.
// HDF5's automatic error printing is switched off; every failure becomes an h5::Error whose
// message names the object (dataset, group or attribute path), so callers only prefix the file.
// Files are written reproducibly: no object timestamps, fixed library-version bounds, so equal
// content written in the same order gives byte-identical files.
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace tidalcrust::h5 {

/// An HDF5 call failed; the message names the object it concerned.
struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Switches off HDF5's printing of its error stack (we report through exceptions instead).
inline void silence_errors() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

/// Owns one HDF5 identifier and closes it with `Close`.
template <herr_t (*Close)(hid_t)>
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
    }
    return *this;
  }
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  explicit operator bool() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0) Close(id_);
    id_ = H5I_INVALID_HID;
  }
  /// Closes now and reports failure (a file close flushes, which can fail).
  void close(const std::string& what) {
    hid_t id = std::exchange(id_, H5I_INVALID_HID);
    if (id >= 0 && Close(id) < 0) throw Error(what);
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
};

using File = Handle<H5Fclose>;
using Group = Handle<H5Gclose>;
using Dataset = Handle<H5Dclose>;
using Dataspace = Handle<H5Sclose>;
using Attribute = Handle<H5Aclose>;
using PropList = Handle<H5Pclose>;
using Type = Handle<H5Tclose>;
/// An object opened by path whose kind (group or dataset) is not known in advance.
using Object = Handle<H5Oclose>;

/// Throws Error(what) when an HDF5 call returned a negative id or status.
inline hid_t check(hid_t id, const std::string& what) {
  if (id < 0) throw Error(what);
  return id;
}

/// Path of `name` below the object `loc`, for messages ("/checkpoint/springs/failed").
inline std::string object_path(hid_t loc, std::string_view name) {
  if (!name.empty() && name.front() == '/') return std::string(name);
  char buffer[512] = {0};
  ssize_t n = H5Iget_name(loc, buffer, sizeof buffer);
  std::string base = n > 0 ? std::string(buffer, std::min<std::size_t>(n, sizeof buffer - 1)) : "";
  if (name.empty()) return base.empty() ? "/" : base;
  if (base.empty() || base.back() != '/') base += '/';
  return base + std::string(name);
}

// ---- element types: file type (fixed little endian) and memory type -------------------------

/// How values of one C++ type are stored: the HDF5 file type, the memory type, the type class
/// and the name used in messages.
struct TypeInfo {
  hid_t file;
  hid_t memory;
  H5T_class_t type_class;
  const char* name;
};
template <typename T>
TypeInfo type_of();
template <> inline TypeInfo type_of<double>() { return {H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, H5T_FLOAT, "float64"}; }
template <> inline TypeInfo type_of<std::int32_t>() { return {H5T_STD_I32LE, H5T_NATIVE_INT32, H5T_INTEGER, "int32"}; }
template <> inline TypeInfo type_of<std::int64_t>() { return {H5T_STD_I64LE, H5T_NATIVE_INT64, H5T_INTEGER, "int64"}; }
template <> inline TypeInfo type_of<std::uint8_t>() { return {H5T_STD_U8LE, H5T_NATIVE_UINT8, H5T_INTEGER, "uint8"}; }

/// Checks that a stored type has the class, size and signedness of T (no silent conversion).
template <typename T>
void check_type(hid_t type, const std::string& what) {
  bool ok = H5Tget_class(type) == type_of<T>().type_class && H5Tget_size(type) == sizeof(T);
  if (ok && type_of<T>().type_class == H5T_INTEGER)
    ok = (H5Tget_sign(type) == H5T_SGN_2) == std::is_signed_v<T>;
  if (!ok) throw Error(what + ": stored type is not " + type_of<T>().name);
}

// ---- bounds: what a file can hold --------------------------------------------------------

/// The size in bytes of the file (or in-memory image) that holds the object `loc`.
inline hsize_t file_size_of(hid_t loc) {
  const hid_t file = H5Iget_file_id(loc);
  if (file < 0) throw Error("cannot find the file of " + object_path(loc, ""));
  hsize_t size = 0;
  const herr_t rc = H5Fget_filesize(file, &size);
  H5Fclose(file);
  if (rc < 0) throw Error("cannot read the size of the file of " + object_path(loc, ""));
  return size;
}

/// Error unless the values a dataset or attribute declares (its dataspace `space` of elements of
/// type `type`) fit in the file holding `loc`: every file written here stores each value it
/// declares (no compression, no sparse chunks; a variable-length string takes at least its
/// 8-byte pointer's worth as a heap reference), so a larger declaration is a damaged or hostile
/// file and is refused before any memory is reserved for it.
inline void check_fits_in_file(hid_t loc, hid_t type, hid_t space, const std::string& what) {
  const hssize_t count = H5Sget_simple_extent_npoints(space);
  if (count < 0) throw Error("cannot read the shape of " + what);
  if (count == 0) return;
  const std::size_t element = H5Tget_size(type);
  if (element == 0) throw Error("cannot read the type of " + what);
  const hsize_t file_bytes = file_size_of(loc);
  if (static_cast<hsize_t>(count) > file_bytes / element)
    throw Error(what + " declares " + std::to_string(count) + " values of " + std::to_string(element) +
                " bytes, more than the file's " + std::to_string(file_bytes) + " bytes can hold (damaged or not "
                "written by tidalcrust)");
}

/// Error unless the dataset `set` keeps its values in its own file: external raw-data files and
/// virtual datasets (other files' data) are refused, as external links are (refuse_external_links).
inline void check_self_contained(hid_t set, const std::string& what) {
  const hid_t dcpl = H5Dget_create_plist(set);
  if (dcpl < 0) throw Error("cannot read the properties of " + what);
  const int external = H5Pget_external_count(dcpl);
  const H5D_layout_t layout = H5Pget_layout(dcpl);
  H5Pclose(dcpl);
  if (external != 0 || layout == H5D_VIRTUAL)
    throw Error(what + " keeps its values in other files (external storage or a virtual dataset); refused");
}

/// The shape and size checks of a dataset before it is read: self-contained and fitting its file.
inline void check_dataset_readable(hid_t set, hid_t type, hid_t space, const std::string& what) {
  check_self_contained(set, what);
  check_fits_in_file(set, type, space, what);
}

/// Error naming the first external link below the root of `file` (H5Lvisit follows neither
/// soft nor external links): a checkpoint is one self-contained file, and following a link into
/// another file would read what the integrity record does not cover.
inline void refuse_external_links(hid_t file) {
  struct Found {
    std::string path;
  } found;
  auto visit = [](hid_t, const char* name, const H5L_info_t* info, void* data) -> herr_t {
    if (info->type != H5L_TYPE_EXTERNAL) return 0;
    static_cast<Found*>(data)->path = std::string("/") + name;
    return 1;
  };
  const herr_t rc = H5Lvisit(file, H5_INDEX_NAME, H5_ITER_INC, visit, &found);
  if (!found.path.empty()) throw Error("link " + found.path + " is an external link (to another file); refused");
  if (rc < 0) throw Error("cannot walk the file's groups (corrupt)");
}

// ---- files and groups ---------------------------------------------------------------------

/// Object creation property list of class `cls` with timestamps switched off.
inline PropList untimed_plist(hid_t cls) {
  PropList plist(check(H5Pcreate(cls), "H5Pcreate"));
  check(H5Pset_obj_track_times(plist.get(), false), "H5Pset_obj_track_times");
  return plist;
}

/// File access properties shared by every open: no HDF5 file locking. Writes go to a
/// temporary renamed into place and readers open finished files only, so the lock protects
/// nothing, and on file systems without locks (ENOLCK, e.g. some NFS mounts) it would make
/// every open fail.
inline PropList file_access_plist() {
  PropList fapl(check(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate"));
  check(H5Pset_file_locking(fapl.get(), false, true), "H5Pset_file_locking");
  return fapl;
}

/// Creates a file for reproducible writing, held in memory (HDF5's core driver without a
/// backing store): HDF5 never writes to disk, so a full disk cannot leave the library with a
/// half-flushed open file; the caller writes file_image() itself, with the errno of any failure.
inline File create_memory_file(const std::string& name) {
  silence_errors();
  PropList fcpl = untimed_plist(H5P_FILE_CREATE);  // also covers the root group
  PropList fapl = file_access_plist();
  check(H5Pset_fapl_core(fapl.get(), 1 << 20, false), "H5Pset_fapl_core");
  // Fixed bounds: the format does not drift with the library version.
  check(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18), "H5Pset_libver_bounds");
  check(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "H5Pset_fclose_degree");
  return File(check(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), "cannot create file"));
}

/// Bob Jenkins' lookup3 hashlittle with initial value 0: HDF5's metadata checksum.
inline std::uint32_t lookup3(const unsigned char* k, std::size_t length) {
  auto rot = [](std::uint32_t x, int r) { return (x << r) | (x >> (32 - r)); };
  std::uint32_t a, b, c;
  a = b = c = 0xdeadbeefu + static_cast<std::uint32_t>(length);
  auto word = [&](std::size_t i) {
    return static_cast<std::uint32_t>(k[i]) | static_cast<std::uint32_t>(k[i + 1]) << 8 |
           static_cast<std::uint32_t>(k[i + 2]) << 16 | static_cast<std::uint32_t>(k[i + 3]) << 24;
  };
  while (length > 12) {
    a += word(0);
    b += word(4);
    c += word(8);
    a -= c; a ^= rot(c, 4); c += b;
    b -= a; b ^= rot(a, 6); a += c;
    c -= b; c ^= rot(b, 8); b += a;
    a -= c; a ^= rot(c, 16); c += b;
    b -= a; b ^= rot(a, 19); a += c;
    c -= b; c ^= rot(b, 4); b += a;
    length -= 12;
    k += 12;
  }
  if (length == 0) return c;
  unsigned char tail[12] = {0};
  std::copy(k, k + length, tail);
  k = tail;
  a += word(0);
  b += word(4);
  c += word(8);
  c ^= b; c -= rot(b, 14);
  a ^= c; a -= rot(c, 11);
  b ^= a; b -= rot(a, 25);
  c ^= b; c -= rot(b, 16);
  a ^= c; a -= rot(c, 4);
  b ^= a; b -= rot(a, 14);
  c ^= b; c -= rot(b, 24);
  return c;
}

/// The bytes of an open file (flushed first), as they would be on disk. HDF5 1.10's
/// H5Fget_file_image rewrites the end-of-file address in the image's superblock without
/// updating the superblock checksum (versions 2 and 3); the checksum is recomputed here, so
/// the image opens like a file the library wrote itself.
inline std::string file_image(hid_t file) {
  check(H5Fflush(file, H5F_SCOPE_GLOBAL), "cannot flush");
  const ssize_t size = H5Fget_file_image(file, nullptr, 0);
  if (size < 0) throw Error("cannot get the file image");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  if (size > 0 && H5Fget_file_image(file, bytes.data(), bytes.size()) != size) throw Error("cannot get the file image");
  auto* image = reinterpret_cast<unsigned char*>(bytes.data());
  if (bytes.size() >= 12 && (image[8] == 2 || image[8] == 3)) {
    // Signature 8, version, sizes of offsets and lengths, flags, 4 addresses, checksum.
    const std::size_t covered = 12 + 4 * static_cast<std::size_t>(image[9]);
    if (bytes.size() < covered + 4) throw Error("file image too short for its superblock");
    const std::uint32_t sum = lookup3(image, covered);
    for (int i = 0; i < 4; ++i) image[covered + i] = static_cast<unsigned char>(sum >> (8 * i));
  }
  return bytes;
}

/// The cause HDF5 recorded for the call that just failed: the description of an entry that
/// carries an errno text if there is one, else the innermost (most specific) description.
inline std::string error_stack_text() {
  struct Found {
    std::string innermost, with_errno;
  } found;
  auto visit = [](unsigned n, const H5E_error2_t* e, void* data) -> herr_t {
    auto* f = static_cast<Found*>(data);
    const std::string desc = e->desc ? e->desc : "";
    if (n == 0) f->innermost = desc;
    if (f->with_errno.empty() && desc.find("errno") != std::string::npos) f->with_errno = desc;
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, visit, &found);
  const std::string& text = found.with_errno.empty() ? found.innermost : found.with_errno;
  return text.empty() ? "unknown HDF5 error" : text;
}

/// Opens a finished file for reading, without file locking (file_access_plist).
inline File open_file_readonly(const std::filesystem::path& path) {
  silence_errors();
  PropList fapl = file_access_plist();
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get());
  if (id < 0) throw Error(error_stack_text());
  return File(id);
}

/// The beginning of the message of a file image HDF5 cannot open.
inline constexpr const char* memory_image_error = "cannot open the file image: ";

/// Opens the file image `bytes` (as file_image returns it, or a file's bytes) in memory,
/// read-only or `writable` (HDF5 works on its own copy; nothing is ever written to disk); `name`
/// only names it in HDF5's messages.
inline File open_memory_image(const std::string& bytes, const std::string& name, bool writable = false) {
  silence_errors();
  PropList fapl = file_access_plist();
  check(H5Pset_fapl_core(fapl.get(), 1 << 20, false), "H5Pset_fapl_core");
  check(H5Pset_file_image(fapl.get(), const_cast<char*>(bytes.data()), bytes.size()), "H5Pset_file_image");
  const hid_t id = H5Fopen(name.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, fapl.get());
  if (id < 0) throw Error(memory_image_error + error_stack_text());
  return File(id);
}

inline Group create_group(hid_t loc, std::string_view name) {
  PropList gcpl = untimed_plist(H5P_GROUP_CREATE);
  std::string n(name);
  return Group(check(H5Gcreate2(loc, n.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                     "cannot create group " + object_path(loc, name)));
}

/// True if every component of the relative or absolute `path` exists as a link below loc.
inline bool exists(hid_t loc, std::string_view path) {
  std::string prefix;
  std::size_t start = 0;
  if (!path.empty() && path.front() == '/') {
    prefix = "/";
    start = 1;
  }
  while (start < path.size()) {
    std::size_t end = path.find('/', start);
    if (end == std::string_view::npos) end = path.size();
    prefix += std::string(path.substr(start, end - start));
    if (H5Lexists(loc, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    prefix += '/';
    start = end + 1;
  }
  return true;
}

inline Group open_group(hid_t loc, std::string_view name) {
  std::string n(name);
  if (!exists(loc, n)) throw Error("group " + object_path(loc, name) + " is missing");
  return Group(check(H5Gopen2(loc, n.c_str(), H5P_DEFAULT), "cannot open group " + object_path(loc, name)));
}

/// Makes `name` a second (hard) link to the existing object `target`.
inline void hard_link(hid_t loc, std::string_view target, std::string_view name) {
  std::string t(target), n(name);
  check(H5Lcreate_hard(loc, t.c_str(), loc, n.c_str(), H5P_DEFAULT, H5P_DEFAULT),
        "cannot link " + object_path(loc, name));
}

// ---- datasets -------------------------------------------------------------------------------

/// Writes a contiguous dataset of shape `dims` (empty dims: a scalar). Zero-size shapes allowed.
template <typename T>
void write_dataset(hid_t loc, std::string_view name, const T* data, const std::vector<hsize_t>& dims) {
  const std::string what = object_path(loc, name);
  Dataspace space(check(dims.empty() ? H5Screate(H5S_SCALAR)
                                     : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                        "cannot create dataspace for " + what));
  PropList dcpl = untimed_plist(H5P_DATASET_CREATE);
  std::string n(name);
  Dataset set(check(H5Dcreate2(loc, n.c_str(), type_of<T>().file, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                    "cannot create dataset " + what));
  hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count > 0)
    check(H5Dwrite(set.get(), type_of<T>().memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "cannot write dataset " + what);
}

template <typename T>
void write_dataset(hid_t loc, std::string_view name, const std::vector<T>& data, const std::vector<hsize_t>& dims) {
  write_dataset(loc, name, data.data(), dims);
}

/// A dataset read back: its values in row-major order and its shape.
template <typename T>
struct Array {
  std::vector<T> values;
  std::vector<hsize_t> dims;
};

/// Reads a whole dataset of element type T; Error if missing or of another type.
template <typename T>
Array<T> read_dataset(hid_t loc, std::string_view name) {
  const std::string what = "dataset " + object_path(loc, name);
  std::string n(name);
  if (!exists(loc, n)) throw Error(what + " is missing");
  {
    Object object(H5Oopen(loc, n.c_str(), H5P_DEFAULT));
    if (!object || H5Iget_type(object.get()) != H5I_DATASET) throw Error(what + " is not a dataset");
  }
  Dataset set(check(H5Dopen2(loc, n.c_str(), H5P_DEFAULT), "cannot open " + what));
  Type type(check(H5Dget_type(set.get()), "cannot read the type of " + what));
  check_type<T>(type.get(), what);
  Dataspace space(check(H5Dget_space(set.get()), "cannot read the shape of " + what));
  check_dataset_readable(set.get(), type.get(), space.get(), what);
  int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw Error("cannot read the shape of " + what);
  Array<T> out;
  out.dims.resize(rank);
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), out.dims.data(), nullptr);
  hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) throw Error("cannot read the shape of " + what);
  out.values.resize(static_cast<std::size_t>(count));
  if (count > 0)
    check(H5Dread(set.get(), type_of<T>().memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()),
          "cannot read " + what + " (corrupt data)");
  return out;
}

/// Writes a dataset whose first dimension is time (an H5MD `value`, `step` or `time`): chunked,
/// one sample per chunk, maxshape unlimited in the first dimension so that a reader or a later
/// tool can append samples (H5MD 1.1, time-dependent data). dims must be non-empty.
template <typename T>
void write_extensible_dataset(hid_t loc, std::string_view name, const T* data, const std::vector<hsize_t>& dims) {
  const std::string what = object_path(loc, name);
  std::vector<hsize_t> max = dims, chunk = dims;
  max.at(0) = H5S_UNLIMITED;
  chunk[0] = 1;
  for (auto& c : chunk) c = std::max<hsize_t>(c, 1);  // a chunk cannot have a zero dimension
  Dataspace space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max.data()),
                        "cannot create dataspace for " + what));
  PropList dcpl = untimed_plist(H5P_DATASET_CREATE);
  check(H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()), "cannot chunk " + what);
  std::string n(name);
  Dataset set(check(H5Dcreate2(loc, n.c_str(), type_of<T>().file, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                    "cannot create dataset " + what));
  if (H5Sget_simple_extent_npoints(space.get()) > 0)
    check(H5Dwrite(set.get(), type_of<T>().memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "cannot write dataset " + what);
}

/// Address of a dataset's raw data in the file (tests use it to corrupt bytes): of the data of
/// a contiguous dataset, of the first chunk of a chunked one.
inline haddr_t dataset_offset(hid_t loc, std::string_view name) {
  std::string n(name);
  Dataset set(check(H5Dopen2(loc, n.c_str(), H5P_DEFAULT), "cannot open dataset " + object_path(loc, name)));
  const haddr_t contiguous = H5Dget_offset(set.get());
  if (contiguous != HADDR_UNDEF) return contiguous;
  Dataspace space(check(H5Dget_space(set.get()), "cannot read the shape of " + object_path(loc, name)));
  const std::vector<hsize_t> first(static_cast<std::size_t>(std::max(H5Sget_simple_extent_ndims(space.get()), 0)), 0);
  haddr_t address = HADDR_UNDEF;
  hsize_t size = 0;
  unsigned filters = 0;
  check(H5Dget_chunk_info_by_coord(set.get(), first.data(), &filters, &address, &size),
        "cannot locate the data of " + object_path(loc, name));
  return address;
}

// ---- strings --------------------------------------------------------------------------------

/// Fixed-length UTF-8 string type of `size` bytes, padded with NULs.
inline Type fixed_string_type(std::size_t size) {
  Type type(check(H5Tcopy(H5T_C_S1), "H5Tcopy"));
  check(H5Tset_size(type.get(), std::max<std::size_t>(size, 1)), "H5Tset_size");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "H5Tset_strpad");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  return type;
}

/// Reads `count` strings stored with `stored` type through `read(memory_type, buffer)`.
/// Handles fixed-length (any padding) and variable-length strings.
template <typename ReadFn>
std::vector<std::string> read_strings(hid_t stored, std::size_t count, const std::string& what, ReadFn read) {
  if (H5Tget_class(stored) != H5T_STRING) throw Error(what + ": stored type is not a string");
  std::vector<std::string> out(count);
  if (count == 0) return out;
  if (H5Tis_variable_str(stored) > 0) {
    Type memory(check(H5Tcopy(H5T_C_S1), "H5Tcopy"));
    H5Tset_size(memory.get(), H5T_VARIABLE);
    H5Tset_cset(memory.get(), H5Tget_cset(stored));
    std::vector<char*> pointers(count, nullptr);
    check(read(memory.get(), pointers.data()), "cannot read " + what);
    for (std::size_t i = 0; i < count; ++i) out[i] = pointers[i] ? pointers[i] : "";
    Dataspace space(check(H5Screate_simple(1, std::vector<hsize_t>{count}.data(), nullptr), "H5Screate"));
#if H5_VERSION_GE(1, 12, 0)
    H5Treclaim(memory.get(), space.get(), H5P_DEFAULT, pointers.data());
#else
    H5Dvlen_reclaim(memory.get(), space.get(), H5P_DEFAULT, pointers.data());
#endif
    return out;
  }
  std::size_t size = H5Tget_size(stored);
  Type memory(check(H5Tcopy(stored), "H5Tcopy"));
  std::vector<char> buffer(size * count);
  check(read(memory.get(), buffer.data()), "cannot read " + what);
  for (std::size_t i = 0; i < count; ++i) {
    std::string s(buffer.data() + i * size, size);
    auto nul = s.find('\0');  // NULLTERM and NULLPAD end at the first NUL
    if (nul != std::string::npos) s.resize(nul);
    while (H5Tget_strpad(stored) == H5T_STR_SPACEPAD && !s.empty() && s.back() == ' ') s.pop_back();
    out[i] = std::move(s);
  }
  return out;
}

/// A scalar fixed-length string dataset.
inline void write_string_dataset(hid_t loc, std::string_view name, const std::string& text) {
  const std::string what = object_path(loc, name);
  Type type = fixed_string_type(text.size());
  Dataspace space(check(H5Screate(H5S_SCALAR), "H5Screate"));
  PropList dcpl = untimed_plist(H5P_DATASET_CREATE);
  std::string n(name);
  Dataset set(check(H5Dcreate2(loc, n.c_str(), type.get(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                    "cannot create dataset " + what));
  check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.c_str()), "cannot write dataset " + what);
}


// ---- attributes -----------------------------------------------------------------------------

/// Writes an attribute of shape `dims` (empty: scalar) from raw memory of type `memory`.
inline void write_attribute_raw(hid_t loc, std::string_view name, hid_t file_type, hid_t memory_type,
                                const void* data, const std::vector<hsize_t>& dims) {
  const std::string what = "attribute " + object_path(loc, "") + "@" + std::string(name);
  Dataspace space(check(dims.empty() ? H5Screate(H5S_SCALAR)
                                     : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                        "cannot create dataspace for " + what));
  std::string n(name);
  Attribute attr(check(H5Acreate2(loc, n.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                       "cannot create " + what));
  check(H5Awrite(attr.get(), memory_type, data), "cannot write " + what);
}

template <typename T>
void write_attribute(hid_t loc, std::string_view name, T value) {
  write_attribute_raw(loc, name, type_of<T>().file, type_of<T>().memory, &value, {});
}

template <typename T>
void write_attribute_array(hid_t loc, std::string_view name, const std::vector<T>& values) {
  write_attribute_raw(loc, name, type_of<T>().file, type_of<T>().memory, values.data(), {values.size()});
}

inline void write_string_attribute(hid_t loc, std::string_view name, const std::string& text) {
  Type type = fixed_string_type(text.size());
  write_attribute_raw(loc, name, type.get(), type.get(), text.c_str(), {});
}

/// Strings packed for a fixed-length string type: the element size (the longest, at least 1)
/// and the NUL-padded bytes.
inline std::pair<std::size_t, std::vector<char>> packed_strings(const std::vector<std::string>& texts) {
  std::size_t size = 1;
  for (const auto& t : texts) size = std::max(size, t.size());
  std::vector<char> buffer(size * texts.size(), '\0');
  for (std::size_t i = 0; i < texts.size(); ++i) std::copy(texts[i].begin(), texts[i].end(), buffer.begin() + i * size);
  return {size, std::move(buffer)};
}

inline void write_string_array_attribute(hid_t loc, std::string_view name, const std::vector<std::string>& texts) {
  const auto [size, buffer] = packed_strings(texts);
  Type type = fixed_string_type(size);
  write_attribute_raw(loc, name, type.get(), type.get(), buffer.data(), {texts.size()});
}

/// A 1-D fixed-length string dataset [n] (n may be 0).
inline void write_string_array_dataset(hid_t loc, std::string_view name, const std::vector<std::string>& texts) {
  const std::string what = object_path(loc, name);
  const auto [size, buffer] = packed_strings(texts);
  Type type = fixed_string_type(size);
  const hsize_t n = texts.size();
  Dataspace space(check(H5Screate_simple(1, &n, nullptr), "cannot create dataspace for " + what));
  PropList dcpl = untimed_plist(H5P_DATASET_CREATE);
  std::string nm(name);
  Dataset set(check(H5Dcreate2(loc, nm.c_str(), type.get(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                    "cannot create dataset " + what));
  if (n > 0)
    check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), "cannot write dataset " + what);
}

/// All strings of a string dataset (any string type, any shape) in row-major order, and its
/// rank; Error if missing or not strings.
inline std::pair<std::vector<std::string>, int> read_string_values(hid_t loc, std::string_view name) {
  const std::string what = "dataset " + object_path(loc, name);
  std::string n(name);
  if (!exists(loc, n)) throw Error(what + " is missing");
  Dataset set(check(H5Dopen2(loc, n.c_str(), H5P_DEFAULT), "cannot open " + what));
  Type type(check(H5Dget_type(set.get()), "cannot read the type of " + what));
  Dataspace space(check(H5Dget_space(set.get()), "cannot read the shape of " + what));
  check_dataset_readable(set.get(), type.get(), space.get(), what);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (rank < 0 || count < 0) throw Error("cannot read the shape of " + what);
  auto values = read_strings(type.get(), static_cast<std::size_t>(count), what, [&](hid_t memory, void* buffer) {
    return H5Dread(set.get(), memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
  });
  return {std::move(values), rank};
}

/// A dataset holding a single string (scalar or one element).
inline std::string read_string_dataset(hid_t loc, std::string_view name) {
  auto [values, rank] = read_string_values(loc, name);
  if (values.size() != 1) throw Error("dataset " + object_path(loc, name) + ": expected a single string");
  return values[0];
}

/// A 1-D string dataset [n].
inline std::vector<std::string> read_string_array_dataset(hid_t loc, std::string_view name) {
  auto [values, rank] = read_string_values(loc, name);
  if (rank != 1) throw Error("dataset " + object_path(loc, name) + ": expected a 1-D array of strings");
  return values;
}

/// A scalar variable-length ASCII string attribute: the type H5MD prescribes for its metadata
/// (h5md/author@name, ...) and for `unit` (h5py reads it as str, a fixed-length one as bytes).
inline void write_vl_string_attribute(hid_t loc, std::string_view name, const std::string& text) {
  Type type(check(H5Tcopy(H5T_C_S1), "H5Tcopy"));
  check(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
  check(H5Tset_cset(type.get(), H5T_CSET_ASCII), "H5Tset_cset");
  const char* pointer = text.c_str();
  write_attribute_raw(loc, name, type.get(), type.get(), &pointer, {});
}

/// An attribute holding an HDF5 object reference to the object at `target` (absolute path).
inline void write_object_reference_attribute(hid_t loc, std::string_view name, const std::string& target) {
  hobj_ref_t reference{};
  check(H5Rcreate(&reference, loc, target.c_str(), H5R_OBJECT, -1), "cannot reference " + target);
  write_attribute_raw(loc, name, H5T_STD_REF_OBJ, H5T_STD_REF_OBJ, &reference, {});
}

/// The path of the object an object-reference attribute points to; Error if it is missing,
/// not a reference or dangling.
inline std::string read_object_reference_attribute(hid_t loc, std::string_view name) {
  const std::string what = "attribute " + object_path(loc, "") + "@" + std::string(name);
  std::string n(name);
  if (H5Aexists(loc, n.c_str()) <= 0) throw Error(what + " is missing");
  Attribute attr(check(H5Aopen(loc, n.c_str(), H5P_DEFAULT), "cannot open " + what));
  Type type(check(H5Aget_type(attr.get()), "cannot read the type of " + what));
  if (H5Tequal(type.get(), H5T_STD_REF_OBJ) <= 0) throw Error(what + ": stored type is not an object reference");
  hobj_ref_t reference{};
  check(H5Aread(attr.get(), H5T_STD_REF_OBJ, &reference), "cannot read " + what);
  Object target(check(H5Rdereference2(loc, H5P_DEFAULT, H5R_OBJECT, &reference), what + ": dangling reference"));
  return object_path(target.get(), "");
}

/// Opens attribute `name` of `loc`; Error naming it if missing.
inline Attribute open_attribute(hid_t loc, std::string_view name, const std::string& what) {
  std::string n(name);
  if (H5Aexists(loc, n.c_str()) <= 0) throw Error(what + " is missing");
  return Attribute(check(H5Aopen(loc, n.c_str(), H5P_DEFAULT), "cannot open " + what));
}

/// Reads all elements of a numeric attribute of type T.
template <typename T>
std::vector<T> read_attribute_array(hid_t loc, std::string_view name) {
  const std::string what = "attribute " + object_path(loc, "") + "@" + std::string(name);
  Attribute attr = open_attribute(loc, name, what);
  Type type(check(H5Aget_type(attr.get()), "cannot read the type of " + what));
  check_type<T>(type.get(), what);
  Dataspace space(check(H5Aget_space(attr.get()), "cannot read the shape of " + what));
  check_fits_in_file(attr.get(), type.get(), space.get(), what);
  hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) throw Error("cannot read the shape of " + what);
  std::vector<T> values(static_cast<std::size_t>(count));
  if (count > 0) check(H5Aread(attr.get(), type_of<T>().memory, values.data()), "cannot read " + what);
  return values;
}

/// Reads a scalar (or one-element) numeric attribute of type T.
template <typename T>
T read_attribute(hid_t loc, std::string_view name) {
  auto values = read_attribute_array<T>(loc, name);
  if (values.size() != 1)
    throw Error("attribute " + object_path(loc, "") + "@" + std::string(name) + ": expected a single value");
  return values[0];
}

inline std::vector<std::string> read_string_array_attribute(hid_t loc, std::string_view name) {
  const std::string what = "attribute " + object_path(loc, "") + "@" + std::string(name);
  Attribute attr = open_attribute(loc, name, what);
  Type type(check(H5Aget_type(attr.get()), "cannot read the type of " + what));
  Dataspace space(check(H5Aget_space(attr.get()), "cannot read the shape of " + what));
  check_fits_in_file(attr.get(), type.get(), space.get(), what);
  hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) throw Error("cannot read the shape of " + what);
  return read_strings(type.get(), static_cast<std::size_t>(count), what,
                      [&](hid_t memory, void* buffer) { return H5Aread(attr.get(), memory, buffer); });
}

inline std::string read_string_attribute(hid_t loc, std::string_view name) {
  auto values = read_string_array_attribute(loc, name);
  if (values.size() != 1)
    throw Error("attribute " + object_path(loc, "") + "@" + std::string(name) + ": expected a single string");
  return values[0];
}

/// Names of all attributes of `loc`, in name order.
inline std::vector<std::string> attribute_names(hid_t loc) {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t index = 0;
  check(H5Aiterate2(loc, H5_INDEX_NAME, H5_ITER_INC, &index, collect, &names),
        "cannot list the attributes of " + object_path(loc, ""));
  return names;
}

}  // namespace tidalcrust::h5
