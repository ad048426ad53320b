// Checkpoint files: the HDF5 layout of docs/checkpoint-layout.md (valid H5MD 1.1), written
// atomically and reproducibly, read back with full validation, plus the .xdmf sidecar.
#include "io/checkpoint_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <optional>
#include <cmath>
#include <thread>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <string_view>

#include "build_info.hpp"
#include "base/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/checkpoint_upgrade.hpp"
#include "io/content_hash.hpp"
#include "io/hdf5_handles.hpp"
#include "io/state_hash.hpp"
#include "base/invariant.hpp"
#include "io/test_points.hpp"
#include "model/config.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

// The flat [rows][cols] views below rely on std::array having no padding.
static_assert(sizeof(std::array<std::int32_t, 2>) == 2 * sizeof(std::int32_t));
static_assert(sizeof(std::array<std::int32_t, 4>) == 4 * sizeof(std::int32_t));
static_assert(sizeof(std::array<std::int32_t, 3>) == 3 * sizeof(std::int32_t));
static_assert(sizeof(std::array<double, 3>) == 3 * sizeof(double));

/// Paths shared by writer, reader and the XDMF sidecar.
namespace path {
constexpr const char* position = "/particles/body/position/value";
constexpr const char* position_step = "/particles/body/position/step";
constexpr const char* position_time = "/particles/body/position/time";
constexpr const char* velocity = "/particles/body/velocity/value";
constexpr const char* mass = "/particles/body/mass";
constexpr const char* species = "/particles/body/species";
constexpr const char* springs = "/connectivity/springs";
constexpr const char* hinges = "/connectivity/hinges";
constexpr const char* faces = "/connectivity/faces";
constexpr const char* rest_length = "/checkpoint/springs/rest_length";
constexpr const char* spring_stiffness = "/checkpoint/springs/stiffness";
constexpr const char* spring_kind = "/checkpoint/springs/kind";
constexpr const char* spring_failed = "/checkpoint/springs/failed";
constexpr const char* strength_factor = "/checkpoint/springs/strength_factor";
constexpr const char* rest_angle = "/checkpoint/hinges/rest_angle";
constexpr const char* hinge_stiffness = "/checkpoint/hinges/stiffness";
constexpr const char* perturber = "/checkpoint/perturber";
constexpr const char* record = "/checkpoint/record";
constexpr const char* config = "/parameters/config";
constexpr const char* particles_group = "/particles/body";
constexpr const char* failures = "/checkpoint/failures";
constexpr const char* timeseries = "/checkpoint/timeseries";
}  // namespace path

/// H5MD units module strings (SI system) for the H5MD elements: the numbers are in the model's
/// units G = M = R = 1 (R, t_grav, sqrt(GM/R), M), and the `unit` attributes say what one of them
/// is (docs/checkpoint-layout.md, "Units in the file"). Of a [moon] workflow they are the moon's
/// own (H5MD's numeric factor: "531000.0 m", "1902.19... s", "279.15... m s-1", "620000...000.0 kg"),
/// so that a stored number times its unit string is its SI value. Without [moon] the model has no
/// scale, and they name the exact realization R = 1 nm, t_grav = 1 ps (M = R^3/(G t_grav^2) =
/// 1.4983e7 kg with CODATA 2018 G), which readers that convert units (MDAnalysis) accept.
struct UnitStrings {
  std::string length, time, velocity, mass, reduced_units;
};

/// `value` as an H5MD numeric factor: a decimal fraction with its point, no exponent (the shortest
/// text that reads back to the same double; "531000.0"). With the point, unit libraries read a
/// factor beyond the integers' range (udunits2 refuses "620000000000000000000 kg", reads
/// "620000000000000000000.0 kg").
std::string h5md_factor(double value) {
  char text[400];
  const auto [end, error] = std::to_chars(text, text + sizeof text, value, std::chars_format::fixed);
  TIDALCRUST_ASSERT(error == std::errc(), "a model unit too large to write as a decimal fraction");
  std::string factor(text, end);
  return factor.find('.') == std::string::npos ? factor + ".0" : factor;
}

/// The unit strings of checkpoint `c`: its moon's units (stored_moon of its configuration), else
/// the realization in nm and ps. A stored configuration that cannot be read (never one a stage
/// wrote) gives the latter: the file is written all the same.
UnitStrings unit_strings(const Checkpoint& c) {
  std::optional<MoonScale> moon;
  try {
    moon = stored_moon(c.config_toml, "/parameters/config");
  } catch (const InputError&) {
  }
  if (!moon)
    return {"nm", "ps", "nm ps-1", "14983000 kg",
            "G = M = R = 1: lengths in body radii R, times in t_grav = sqrt(R^3/(G M)), velocities in "
            "sqrt(G M/R), masses in M. The workflow gives no moon ([moon]), so the model has no scale: the unit "
            "strings name the exact realization R = 1 nm, t_grav = 1 ps (M = 1.4983e7 kg); for a real moon scale "
            "by its R and t_grav (tidalcrust estimate) or give the workflow a [moon]."};
  const ModelUnits& u = moon->units;
  return {h5md_factor(u.radius_m) + " m", h5md_factor(u.time_s) + " s", h5md_factor(u.speed_m_s) + " m s-1",
          h5md_factor(u.mass_kg) + " kg",
          fmt::format("G = M = R = 1 for the moon of [moon] ({}): lengths in R = {} m, times in t_grav = sqrt(R^3/(G M)) "
                      "= {} s, velocities in sqrt(G M/R) = {} m/s, masses in M = {} kg (G = {} m^3 kg^-1 s^-2). The "
                      "unit strings are these units, so a stored number times its unit string is its SI value.",
                      moon->name, h5md_factor(u.radius_m), h5md_factor(u.time_s), h5md_factor(u.speed_m_s),
                      h5md_factor(u.mass_kg), gravitational_constant_si)};
}

std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + "]";
}

// ---- the layout of the per-element arrays and of the observables, listed once -------------------

/// What the first dimension of a per-element array counts.
enum class Rows { particles, springs, hinges, faces };
constexpr const char* rows_symbol[] = {"N", "Ns", "Nh", "Nf"};

/// [rows] (columns 0), [rows][K], or one H5MD time slice [1][rows][K].
struct Shape {
  Rows rows;
  std::size_t columns = 0;
  bool time_slice = false;
};

/// Every per-element array of a checkpoint, in stored order, as visit(path, array, shape). The
/// first array of each kind of rows defines its count (when reading: N from the positions, Ns
/// from the springs, Nh from the hinges, Nf from the faces). The writer, the reader and the
/// consistency check all walk this list. C is Checkpoint or const Checkpoint.
template <typename C, typename Visit>
void visit_element_arrays(C& c, Visit&& visit) {
  visit(path::position, c.state.position, Shape{Rows::particles, 3, true});
  visit(path::velocity, c.state.velocity, Shape{Rows::particles, 3, true});
  visit(path::mass, c.body.mass, Shape{Rows::particles});
  visit(path::species, c.body.species, Shape{Rows::particles});
  visit(path::springs, c.body.springs, Shape{Rows::springs, 2});
  visit(path::rest_length, c.state.springs.rest_length, Shape{Rows::springs});
  visit(path::spring_stiffness, c.state.springs.stiffness, Shape{Rows::springs});
  visit(path::spring_kind, c.body.spring_kind, Shape{Rows::springs});
  visit(path::spring_failed, c.state.springs.failed, Shape{Rows::springs});
  visit(path::strength_factor, c.body.strength_factor, Shape{Rows::springs});
  visit(path::hinges, c.body.hinges, Shape{Rows::hinges, 4});
  visit(path::rest_angle, c.state.hinges.rest_angle, Shape{Rows::hinges});
  visit(path::hinge_stiffness, c.body.hinge_stiffness, Shape{Rows::hinges});
  visit(path::faces, c.body.faces, Shape{Rows::faces, 3});
}

/// The columns of the failure log and of the timeseries: visit(name, member pointer). A 3-vector
/// member is an [n][3] dataset, any other an [n] one; the first column defines n.
template <typename Visit>
void visit_columns(std::type_identity<FailureEvent>, Visit&& visit) {
  visit("time", &FailureEvent::time);
  visit("step", &FailureEvent::step);
  visit("spring", &FailureEvent::spring);
  visit("strain", &FailureEvent::strain);
  visit("position", &FailureEvent::position);
  visit("released_energy", &FailureEvent::released_energy);
}
template <typename Visit>
void visit_columns(std::type_identity<TimeseriesSample>, Visit&& visit) {
  visit("time", &TimeseriesSample::time);
  visit("failed", &TimeseriesSample::failed);
  visit("kinetic_energy", &TimeseriesSample::kinetic_energy);
  visit("momentum", &TimeseriesSample::momentum);
  visit("angular_momentum", &TimeseriesSample::angular_momentum);
  visit("perturber_offset", &TimeseriesSample::perturber_offset);
  visit("internal_kinetic_energy", &TimeseriesSample::internal_kinetic_energy);
  visit("spring_energy", &TimeseriesSample::spring_energy);
  visit("hinge_energy", &TimeseriesSample::hinge_energy);
  visit("self_gravity_energy", &TimeseriesSample::self_gravity_energy);
  visit("perturber_energy", &TimeseriesSample::perturber_energy);
  visit("damping_dissipated", &TimeseriesSample::damping_dissipated);
  visit("failure_released", &TimeseriesSample::failure_released);
  visit("hinge_residual_work", &TimeseriesSample::hinge_residual_work);
}

/// The observables groups and the rows each holds.
template <typename O, typename Visit>
void visit_observables(O& o, Visit&& visit) {
  visit(path::failures, o.failures);
  visit(path::timeseries, o.timeseries);
}

/// Element type, value count and first value of an array stored flat (rows of std::array are
/// stored as [rows][K]; the static_asserts above guarantee they have no padding).
template <typename T>
struct Flat {
  using value_type = T;
  static constexpr std::size_t width = 1;
};
template <typename T, std::size_t K>
struct Flat<std::array<T, K>> {
  using value_type = T;
  static constexpr std::size_t width = K;
};
template <typename E>
std::size_t value_count(const std::vector<E>& v) { return v.size() * Flat<E>::width; }
template <typename E>
const auto* flat_data(const std::vector<E>& v) {
  return reinterpret_cast<const typename Flat<E>::value_type*>(v.data());
}

std::vector<hsize_t> dims_of(const Shape& shape, hsize_t rows) {
  if (shape.time_slice) return {1, rows, shape.columns};
  if (shape.columns > 0) return {rows, shape.columns};
  return {rows};
}

/// [n] for a column of numbers, [n][3] for a column of 3-vectors.
template <typename Value>
std::vector<hsize_t> column_dims(hsize_t n) {
  if constexpr (Flat<Value>::width > 1) return {n, Flat<Value>::width};
  else return {n};
}

/// The number of rows a per-element array holds in memory.
template <typename E>
std::size_t rows_of(const std::vector<E>& v, const Shape& shape) {
  return value_count(v) / std::max<std::size_t>(shape.columns, 1);
}

// ---- consistency of an in-memory checkpoint (checked before writing) ------------------------

/// Empty if every array has the size the body implies and every index is in range; otherwise
/// a message naming the dataset that would be wrong.
std::string consistency_problem(const Checkpoint& c) {
  // Sizes: the first array of each kind of rows sets the count the others must have.
  std::array<std::optional<std::size_t>, 4> count;
  std::string problem;
  visit_element_arrays(c, [&](const char* dataset, const auto& values, const Shape& shape) {
    auto& rows = count[static_cast<std::size_t>(shape.rows)];
    const std::size_t width = std::max<std::size_t>(shape.columns, 1);
    if (!rows) rows = rows_of(values, shape);
    if (problem.empty() && value_count(values) != *rows * width)
      problem = fmt::format("{} has {} values, expected {} ({} = {})", dataset, value_count(values), *rows * width,
                            rows_symbol[static_cast<std::size_t>(shape.rows)], *rows);
  });
  if (!problem.empty()) return problem;
  const std::size_t n = c.body.mass.size(), ns = c.body.springs.size(), nh = c.body.hinges.size();
  auto index_problem = [n](const char* dataset, std::size_t row, std::int32_t index) {
    return (index < 0 || static_cast<std::size_t>(index) >= n)
               ? fmt::format("{} row {}: particle index {} out of range [0, {})", dataset, row, index, n)
               : std::string();
  };
  for (std::size_t r = 0; r < ns; ++r)
    for (auto i : c.body.springs[r])
      if (auto p = index_problem(path::springs, r, i); !p.empty()) return p;
  for (std::size_t r = 0; r < nh; ++r)
    for (auto i : c.body.hinges[r])
      if (auto p = index_problem(path::hinges, r, i); !p.empty()) return p;
  for (std::size_t r = 0; r < c.body.faces.size(); ++r)
    for (auto i : c.body.faces[r])
      if (auto p = index_problem(path::faces, r, i); !p.empty()) return p;
  const std::uint8_t highest_species = c.body.liquid.present() ? 2 : 1;
  for (std::size_t r = 0; r < n; ++r)
    if (c.body.species[r] > highest_species)
      return fmt::format("{} row {}: species {} is not {}", path::species, r, +c.body.species[r],
                         c.body.liquid.present() ? "0, 1 or 2" : "0 or 1 (2, liquid, needs /checkpoint/liquid)");
  if (c.body.liquid.present()) {
    const auto& tets = c.body.liquid.tetrahedra;
    std::vector<std::uint8_t> node(n, 0);  // a corner of a tetrahedron: a pressure node
    for (std::size_t t = 0; t < tets.size(); ++t) {
      bool in_layer = false;
      for (const std::int32_t i : tets[t]) {
        if (auto p = index_problem("/checkpoint/liquid/tetrahedra", t, i); !p.empty()) return p;
        in_layer = in_layer || c.body.species[static_cast<std::size_t>(i)] != 0;
        node[static_cast<std::size_t>(i)] = 1;
      }
      if (!in_layer) return fmt::format("/checkpoint/liquid/tetrahedra row {}: every corner is an interior node", t);
    }
    if (c.state.liquid_rest_volume.size() != n)
      return fmt::format("/checkpoint/liquid/rest_volume has {} values, expected N = {}", c.state.liquid_rest_volume.size(), n);
    for (std::size_t r = 0; r < n; ++r) {
      const double v = c.state.liquid_rest_volume[r];
      if (c.body.species[r] == 2 && !node[r])
        return fmt::format("/checkpoint/liquid/tetrahedra: liquid particle {} is the corner of no tetrahedron", r);
      if (node[r] ? !(v > 0 && std::isfinite(v)) : v != 0)
        return fmt::format("/checkpoint/liquid/rest_volume row {}: {} is not {}", r, v,
                           node[r] ? "finite and > 0 (a corner of a tetrahedron)" : "0 (no tetrahedron's corner)");
    }
    if (!c.state.liquid_support.empty()) {
      if (c.state.liquid_support.size() != 3 * n)
        return fmt::format("/checkpoint/liquid/support has {} rows, expected N = {}", c.state.liquid_support.size() / 3, n);
      if (!(c.body.liquid.maxwell_time > 0))
        return "/checkpoint/liquid/support is set but /checkpoint/liquid@maxwell_time is 0 (an elastic liquid has none)";
      for (std::size_t k = 0; k < 3 * n; ++k)
        if (!std::isfinite(c.state.liquid_support[k]))
          return fmt::format("/checkpoint/liquid/support row {}: {} is not finite", k / 3, c.state.liquid_support[k]);
    }
  } else if (!c.state.liquid_rest_volume.empty() || !c.state.liquid_support.empty()) {
    return "the state has liquid rest volumes or a liquid support but the body no liquid layer";
  }
  const std::uint8_t highest_kind = c.body.liquid.present() ? 3 : 2;
  for (std::size_t r = 0; r < ns; ++r) {
    if (c.body.spring_kind[r] > highest_kind)
      return fmt::format("{} row {}: kind {} is not {}", path::spring_kind, r, +c.body.spring_kind[r],
                         c.body.liquid.present() ? "0, 1, 2 or 3" : "0, 1 or 2 (3, liquid, needs /checkpoint/liquid)");
    if (c.state.springs.failed[r] > 1)
      return fmt::format("{} row {}: flag {} is not 0 or 1", path::spring_failed, r, +c.state.springs.failed[r]);
    if (!(c.body.strength_factor[r] > 0) || !std::isfinite(c.body.strength_factor[r]))
      return fmt::format("{} row {}: factor {} is not finite and > 0", path::strength_factor, r, c.body.strength_factor[r]);
  }
  for (std::size_t r = 0; r < c.observables.failures.size(); ++r) {
    auto s = c.observables.failures[r].spring;
    if (s < 0 || static_cast<std::size_t>(s) >= ns)
      return fmt::format("{}/spring row {}: spring index {} out of range [0, {})", path::failures, r, s, ns);
  }
  return {};
}

// ---- writing --------------------------------------------------------------------------------

/// The person responsible for the run (H5MD's /h5md/author@name): $TIDALCRUST_AUTHOR if set,
/// else the full name of the account (first field of the passwd GECOS entry), else its login
/// name, else "unknown". Files written by the same author of equal checkpoints stay
/// byte-identical.
std::string author_name() {
  if (const char* set = std::getenv("TIDALCRUST_AUTHOR"); set && *set) return set;
  struct passwd entry {};
  struct passwd* found = nullptr;
  std::vector<char> buffer(16384);
  if (::getpwuid_r(::getuid(), &entry, buffer.data(), buffer.size(), &found) == 0 && found) {
    const std::string gecos = found->pw_gecos ? found->pw_gecos : "";
    const std::string full = gecos.substr(0, gecos.find(','));
    if (!full.empty()) return full;
    if (found->pw_name && *found->pw_name) return found->pw_name;
  }
  return "unknown";
}

/// /h5md: the H5MD version, author, creator and the units module (variable-length strings,
/// as the specification prescribes).
void write_h5md_header(hid_t root, const UnitStrings& unit) {
  h5::Group h5md = h5::create_group(root, "h5md");
  h5::write_attribute_array<std::int32_t>(h5md.get(), "version", {1, 1});
  h5::Group author = h5::create_group(h5md.get(), "author");
  h5::write_vl_string_attribute(author.get(), "name", author_name());
  h5::Group creator = h5::create_group(h5md.get(), "creator");
  h5::write_vl_string_attribute(creator.get(), "name", "tidalcrust");
  h5::write_vl_string_attribute(creator.get(), "version", build_info::version);
  h5::Group modules = h5::create_group(h5md.get(), "modules");
  h5::Group units = h5::create_group(modules.get(), "units");
  h5::write_attribute_array<std::int32_t>(units.get(), "version", {1, 0});
  h5::write_vl_string_attribute(units.get(), "system", "SI");
  h5::write_vl_string_attribute(units.get(), "reduced_units", unit.reduced_units);
}

/// Applies `edit(id)` to the group or dataset at `object_path`.
template <typename Edit>
void edit_object(hid_t root, const char* object_path, Edit edit) {
  h5::Object object(h5::check(H5Oopen(root, object_path, H5P_DEFAULT), fmt::format("cannot open {}", object_path)));
  edit(object.get());
}

/// The H5MD metadata of the stored arrays: units, the particles group of each connectivity
/// list, and the names of the integer codes of species and spring kinds (labels[i] names code i).
void write_h5md_metadata(hid_t root, const UnitStrings& unit, bool liquid) {
  for (auto [dataset, u] : {std::pair{path::position, &unit.length}, std::pair{path::position_time, &unit.time},
                            std::pair{path::velocity, &unit.velocity}, std::pair{path::mass, &unit.mass}})
    edit_object(root, dataset, [&](hid_t id) { h5::write_vl_string_attribute(id, "unit", *u); });
  for (const char* list : {path::springs, path::hinges, path::faces})
    edit_object(root, list, [](hid_t id) { h5::write_object_reference_attribute(id, "particles_group", path::particles_group); });
  // "liquid" only where there is one: every other file keeps its bytes.
  edit_object(root, path::species, [&](hid_t id) {
    h5::write_string_array_attribute(id, "labels",
                                     liquid ? std::vector<std::string>{"interior", "shell", "liquid"}
                                            : std::vector<std::string>{"interior", "shell"});
  });
  edit_object(root, path::spring_kind, [&](hid_t id) {
    h5::write_string_array_attribute(id, "labels",
                                     liquid ? std::vector<std::string>{"interior", "shell", "cross", "liquid"}
                                            : std::vector<std::string>{"interior", "shell", "cross"});
  });
}

/// The groups of /particles and /connectivity with their H5MD metadata, and every per-element
/// array (visit_element_arrays) in them and in /checkpoint/{springs,hinges}.
void write_body_and_state(hid_t root, const Checkpoint& c, const UnitStrings& unit) {
  {
    h5::Group particles = h5::create_group(root, "particles");
    h5::Group body = h5::create_group(particles.get(), "body");
    h5::Group box = h5::create_group(body.get(), "box");
    h5::write_attribute<std::int32_t>(box.get(), "dimension", 3);
    h5::write_string_array_attribute(box.get(), "boundary", {"none", "none", "none"});
    h5::Group position = h5::create_group(body.get(), "position");
    h5::write_extensible_dataset<std::int64_t>(position.get(), "step", &c.state.step, {1});
    h5::write_extensible_dataset<double>(position.get(), "time", &c.state.time, {1});
    h5::create_group(body.get(), "velocity");
    h5::hard_link(root, path::position_step, "/particles/body/velocity/step");
    h5::hard_link(root, path::position_time, "/particles/body/velocity/time");
    h5::create_group(root, "connectivity");
    h5::Group checkpoint = h5::create_group(root, "checkpoint");
    h5::create_group(checkpoint.get(), "springs");
    h5::create_group(checkpoint.get(), "hinges");
  }
  visit_element_arrays(c, [&](const char* dataset, const auto& values, const Shape& shape) {
    const auto dims = dims_of(shape, rows_of(values, shape));
    if (shape.time_slice) h5::write_extensible_dataset(root, dataset, flat_data(values), dims);
    else h5::write_dataset(root, dataset, flat_data(values), dims);
  });
  write_h5md_metadata(root, unit, c.body.liquid.present());
}

/// Writes one stage-record field under /checkpoint/record: numbers and flags as attributes,
/// lists as 1-D datasets (visit_fields in model/stage_records.hpp lists the fields).
struct RecordWriter {
  hid_t group;
  void operator()(const char* name, double v, const char*, const char*) const {
    h5::write_attribute<double>(group, name, v);
  }
  void operator()(const char* name, std::int64_t v, const char*, const char*) const {
    h5::write_attribute<std::int64_t>(group, name, v);
  }
  void operator()(const char* name, bool v, const char*, const char*) const {
    h5::write_attribute<std::uint8_t>(group, name, v ? 1 : 0);
  }
  void operator()(const char* name, const std::string& v, const char*, const char*) const {
    h5::write_string_attribute(group, name, v);
  }
  /// An optional name: "" when absent (a name is never empty).
  void operator()(const char* name, const std::optional<std::string>& v, const char*, const char*) const {
    h5::write_string_attribute(group, name, v.value_or(""));
  }
  template <Choice E>
  void operator()(const char* name, E v, const char*, const char*) const {  // by its name (model/choices.hpp)
    h5::write_string_attribute(group, name, std::string(choice_name(v)));
  }
  template <typename T>
  void operator()(const char* name, const std::vector<T>& v, const char*, const char*) const {
    h5::write_dataset(group, name, v, {v.size()});
  }
};

/// Reads one stage-record field back; a missing or mistyped field is an h5::Error naming it.
struct RecordReader {
  hid_t group;
  void operator()(const char* name, double& v, const char*, const char*) const {
    v = h5::read_attribute<double>(group, name);
  }
  void operator()(const char* name, std::int64_t& v, const char*, const char*) const {
    v = h5::read_attribute<std::int64_t>(group, name);
  }
  void operator()(const char* name, bool& v, const char*, const char*) const {
    const auto flag = h5::read_attribute<std::uint8_t>(group, name);
    if (flag > 1) throw h5::Error(fmt::format("attribute {}@{} is {}, expected 0 or 1", path::record, name, +flag));
    v = flag == 1;
  }
  void operator()(const char* name, std::string& v, const char*, const char*) const {
    v = h5::read_string_attribute(group, name);
  }
  void operator()(const char* name, std::optional<std::string>& v, const char*, const char*) const {
    std::string text = h5::read_string_attribute(group, name);
    v = text.empty() ? std::nullopt : std::optional<std::string>(std::move(text));
  }
  template <Choice E>
  void operator()(const char* name, E& v, const char*, const char*) const {
    const std::string text = h5::read_string_attribute(group, name);
    const auto value = find_choice<E>(text);
    if (!value)
      throw h5::Error(fmt::format("attribute {}@{} is \"{}\", expected one of: {}", path::record, name, text,
                                  choice_names<E>()));
    v = *value;
  }
  template <typename T>
  void operator()(const char* name, std::vector<T>& v, const char*, const char*) const {
    auto array = h5::read_dataset<T>(group, name);
    if (array.dims.size() != 1)
      throw h5::Error(fmt::format("dataset {}/{} has shape {}, expected [k]", path::record, name, shape_text(array.dims)));
    v = std::move(array.values);
  }
};

/// /checkpoint/liquid, only for a body with a liquid layer (docs/checkpoint-layout.md): the bulk
/// modulus K and the Maxwell time tau_M (attributes), the layer's tetrahedra [Nt][4] (the body),
/// each particle's rest volume [N] and, once a Maxwell liquid's relaxation has ended, its support
/// [N][3] (the state). read_liquid_layer reads it back.
void write_liquid_layer(hid_t checkpoint, const LiquidLayer& liquid, const State& state) {
  h5::Group group = h5::create_group(checkpoint, "liquid");
  h5::write_attribute<double>(group.get(), "bulk_modulus", liquid.bulk_modulus);
  h5::write_attribute<double>(group.get(), "maxwell_time", liquid.maxwell_time);
  h5::write_dataset(group.get(), "tetrahedra", liquid.tetrahedra.empty() ? nullptr : liquid.tetrahedra[0].data(),
                    {liquid.tetrahedra.size(), 4});
  h5::write_dataset(group.get(), "rest_volume", state.liquid_rest_volume.data(), {state.liquid_rest_volume.size()});
  if (!state.liquid_support.empty())
    h5::write_dataset(group.get(), "support", state.liquid_support.data(), {state.liquid_support.size() / 3, 3});
}

/// Reads /checkpoint/liquid when the file has it (else the body has no liquid layer); the
/// consistency check then checks its values against the particles.
void read_liquid_layer(hid_t checkpoint, Body& body, State& state) {
  if (H5Lexists(checkpoint, "liquid", H5P_DEFAULT) <= 0) return;
  h5::Group group = h5::open_group(checkpoint, "liquid");
  body.liquid.bulk_modulus = h5::read_attribute<double>(group.get(), "bulk_modulus");
  if (!(body.liquid.bulk_modulus > 0) || !std::isfinite(body.liquid.bulk_modulus))
    throw h5::Error(fmt::format("attribute /checkpoint/liquid@bulk_modulus is {}, expected a finite number > 0",
                                body.liquid.bulk_modulus));
  body.liquid.maxwell_time = h5::read_attribute<double>(group.get(), "maxwell_time");
  if (!(body.liquid.maxwell_time >= 0) || !std::isfinite(body.liquid.maxwell_time))
    throw h5::Error(fmt::format("attribute /checkpoint/liquid@maxwell_time is {}, expected a finite number >= 0",
                                body.liquid.maxwell_time));
  auto tets = h5::read_dataset<std::int32_t>(group.get(), "tetrahedra");
  if (tets.dims.size() != 2 || tets.dims[1] != 4)
    throw h5::Error("dataset /checkpoint/liquid/tetrahedra is not [Nt][4]");
  body.liquid.tetrahedra.resize(tets.dims[0]);
  for (std::size_t t = 0; t < tets.dims[0]; ++t)
    for (int v = 0; v < 4; ++v) body.liquid.tetrahedra[t][static_cast<std::size_t>(v)] = tets.values[4 * t + static_cast<std::size_t>(v)];
  auto volume = h5::read_dataset<double>(group.get(), "rest_volume");
  if (volume.dims.size() != 1)
    throw h5::Error(fmt::format("dataset /checkpoint/liquid/rest_volume has {} dimensions, expected 1 [N]", volume.dims.size()));
  state.liquid_rest_volume = std::move(volume.values);
  if (H5Lexists(group.get(), "support", H5P_DEFAULT) > 0) {
    auto support = h5::read_dataset<double>(group.get(), "support");
    if (support.dims.size() != 2 || support.dims[1] != 3)
      throw h5::Error("dataset /checkpoint/liquid/support is not [N][3]");
    state.liquid_support = std::move(support.values);
  }
}

void write_checkpoint_group(hid_t root, const Checkpoint& c, const std::string& hash) {
  h5::Group group = h5::open_group(root, "/checkpoint");
  hid_t g = group.get();
  h5::write_attribute<std::int64_t>(g, "format_version", checkpoint_format_version);
  h5::write_string_attribute(g, "stage", c.stage.name());
  h5::write_attribute<std::uint8_t>(g, "complete", c.stage.complete ? 1 : 0);
  h5::write_attribute<double>(g, "time", c.state.time);
  h5::write_attribute<std::int64_t>(g, "step", c.state.step);
  h5::write_attribute<double>(g, "dt", c.stage.clock.dt);
  h5::write_attribute<double>(g, "start_time", c.stage.clock.start_time);
  h5::write_attribute<std::int64_t>(g, "start_step", c.stage.clock.start_step);
  h5::write_attribute<std::int64_t>(g, "end_step", c.stage.end_step);
  h5::write_string_attribute(g, "state_hash", hash);
  h5::write_string_attribute(g, "parent_hash", c.stage.parent_hash);
  h5::write_string_attribute(g, "fingerprint", c.stage.fingerprint);
  h5::write_string_attribute(g, "diagnostic", c.stage.diagnostic);
  h5::write_string_attribute(g, "gravity_kernel", c.stage.gravity_kernel);
  h5::write_string_attribute(g, "gravity_kernel_changes", c.stage.gravity_kernel_changes);
  h5::write_attribute<double>(g, "softening", c.body.softening);

  if (c.body.liquid.present()) write_liquid_layer(g, c.body.liquid, c.state);
  if (c.state.perturber.present) {
    h5::Group perturber = h5::create_group(g, "perturber");
    h5::write_dataset<double>(perturber.get(), "mass", &c.state.perturber.mass, {});
    h5::write_dataset(perturber.get(), "position", c.state.perturber.position.data(), {3});
    h5::write_dataset(perturber.get(), "velocity", c.state.perturber.velocity.data(), {3});
  }
  h5::Group record = h5::create_group(g, "record");
  std::visit([&](const auto& r) { visit_fields(r, RecordWriter{record.get()}); }, c.stage.record);
}

void write_parameters(hid_t root, const Checkpoint& c) {
  h5::Group group = h5::create_group(root, "parameters");
  h5::write_string_dataset(group.get(), "config", c.config_toml);
  h5::Group provenance = h5::create_group(group.get(), "provenance");
  h5::write_string_attribute(provenance.get(), "version", build_info::version);
  h5::write_string_attribute(provenance.get(), "git_commit", build_info::git_commit);
  h5::write_string_attribute(provenance.get(), "compiler", build_info::compiler);
  h5::write_string_attribute(provenance.get(), "build_flags", build_info::build_flags);
}

/// The failure log and the timeseries, one dataset per column (visit_columns). They live in our
/// own /checkpoint group: H5MD's /observables holds only H5MD elements (step, time, value).
void write_observables(hid_t root, const Observables& o) {
  visit_observables(o, [&](const char* group_path, const auto& rows) {
    using Row = typename std::decay_t<decltype(rows)>::value_type;
    h5::Group group = h5::create_group(root, group_path);
    visit_columns(std::type_identity<Row>{}, [&](const char* name, auto member) {
      using Value = std::decay_t<decltype(std::declval<Row>().*member)>;
      std::vector<Value> column;
      column.reserve(rows.size());
      for (const Row& row : rows) column.push_back(row.*member);
      h5::write_dataset(group.get(), name, flat_data(column), column_dims<Value>(rows.size()));
    });
  });
}

/// The bytes of the checkpoint file of `c`, built in memory (h5::create_memory_file); `file`
/// only names it.
/// About the bytes the checkpoint file of `c` takes: its arrays, observables and configuration,
/// and HDF5's metadata.
std::size_t estimated_file_bytes(const Checkpoint& c) {
  std::size_t bytes = 256 * 1024 + c.config_toml.size();
  visit_element_arrays(c, [&](const char*, const auto& values, const Shape&) {
    bytes += values.size() * sizeof(values[0]);
  });
  bytes += c.observables.failures.size() * sizeof(FailureEvent);
  bytes += c.observables.timeseries.size() * sizeof(TimeseriesSample);
  return bytes;
}

/// HDF5 does not survive every failed allocation (a SIGSEGV inside the library when memory runs
/// out while it opens the in-memory image), so the memory the write needs at its peak (the file
/// being built, three images of it, HDF5's caches) is reserved before HDF5 starts, and given back
/// at once (glibc returns blocks this large to the system): an InputError naming the file here,
/// when the address space (ulimit -v) or the machine cannot hold it, instead of a crash later.
/// Measured on the quick body (0.4 MB file) and a level-5 one (3.3 MB): every ulimit -v from
/// 36 to 70 MB gives exit 0, 1 (out of memory before writing) or 2, never a signal.
void reserve_memory_for_writing(const fs::path& file, const Checkpoint& c) {
  // HDF5's core driver grows its buffer in 1 MB steps: the file, its image, the image opened for
  // the digests and the final image, each rounded up, and HDF5's caches.
  const std::size_t megabytes = (estimated_file_bytes(c) >> 20) + 1;
  const std::size_t needed = (4 * megabytes + 2) << 20;
  void* reserve = std::malloc(needed);
  if (!reserve) {
    throw InputError(fmt::format("{}: not enough memory to build the checkpoint (about {} MB needed; the limit of this "
                                 "process, ulimit -v, or of the machine); nothing was written",
                                 file.string(), needed >> 20));
  }
  std::free(reserve);
}

std::string hdf5_bytes(const fs::path& file, const Checkpoint& c) {
  h5::File f = h5::create_memory_file(file.string());
  const hid_t root = f.get();
  const UnitStrings unit = unit_strings(c);
  write_h5md_header(root, unit);
  write_body_and_state(root, c, unit);
  write_checkpoint_group(root, c, state_hash(c.state));
  write_parameters(root, c);
  write_observables(root, c.observables);
  // The digests come from the file image itself, opened as a reader opens the file, so they
  // cover exactly the bytes that reach the disk; then the record is added to that image.
  std::vector<ObjectDigest> digests;
  {
    // Another name: HDF5 would take the same name for the open file being written.
    h5::File image = h5::open_memory_image(h5::file_image(root), file.string() + " (image)");
    digests = object_digests(image.get());
  }
  write_integrity_record(root, digests);
  std::string bytes = h5::file_image(root);
  f.close("cannot close");
  return bytes;
}

// ---- XDMF sidecar ---------------------------------------------------------------------------

std::string xml_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += ch;
    }
  }
  return out;
}

/// The XDMF 3 description of the particles, springs and shell faces of `c` stored in `h5_name`
/// (a file name relative to the sidecar's folder).
std::string xdmf_text(const Checkpoint& c, const std::string& h5_name) {
  const std::string h5 = xml_escape(h5_name);
  const std::size_t n = c.body.mass.size(), ns = c.body.springs.size(), nf = c.body.faces.size();
  auto heavy = [&](const std::string& dims, const char* number_type, int precision, const char* dataset) {
    return fmt::format(
        "<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" Format=\"HDF\">{}:{}</DataItem>", dims,
        number_type, precision, h5, dataset);
  };
  // position/value and velocity/value are [1][N][3], H5MD's one time slice: a plain DataItem
  // on the whole dataset gives N points in every XDMF reader (a HyperSlab of it loads 0 points in
  // ParaView's Xdmf3 readers and warns in the legacy one).
  auto slice = [&](const char* dataset) { return heavy(fmt::format("1 {} 3", n), "Float", 8, dataset); };
  const std::string geometry = fmt::format(
      "        <Geometry GeometryType=\"XYZ\">\n          {}\n        </Geometry>\n", slice(path::position));
  auto attribute = [&](const char* name, const char* center, std::size_t count, const char* number_type,
                       int precision, const char* dataset) {
    return fmt::format("        <Attribute Name=\"{}\" AttributeType=\"Scalar\" Center=\"{}\">\n          {}\n"
                       "        </Attribute>\n",
                       name, center, heavy(std::to_string(count), number_type, precision, dataset));
  };

  std::string x = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
  x += fmt::format("    <Grid Name=\"{}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n",
                   xml_escape(c.stage.name()));
  x += fmt::format("      <Time Value=\"{}\"/>\n", c.state.time);
  // One uniform grid: its topology, the shared geometry, then its attributes.
  auto grid = [&](const char* name, const char* type, std::size_t count, const char* nodes_per_element,
                  const std::string& connectivity, const std::string& attributes) {
    return fmt::format("      <Grid Name=\"{}\" GridType=\"Uniform\">\n"
                       "        <Topology TopologyType=\"{}\" NumberOfElements=\"{}\"{}>\n          {}\n"
                       "        </Topology>\n{}{}      </Grid>\n",
                       name, type, count, nodes_per_element, connectivity, geometry, attributes);
  };
  if (n > 0) {
    std::string indices = fmt::format("<DataItem Dimensions=\"{}\" NumberType=\"Int\" Precision=\"4\" Format=\"XML\">", n);
    for (std::size_t i = 0; i < n; ++i) indices += (i % 20 == 0 ? "\n" : " ") + std::to_string(i);
    indices += "\n          </DataItem>";
    x += grid("particles", "Polyvertex", n, " NodesPerElement=\"1\"", indices,
              attribute("species", "Node", n, "UChar", 1, path::species) +
                  attribute("mass", "Node", n, "Float", 8, path::mass) +
                  fmt::format("        <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n"
                              "          {}\n        </Attribute>\n",
                              slice(path::velocity)));
  }
  if (ns > 0)
    x += grid("springs", "Polyline", ns, " NodesPerElement=\"2\"", heavy(fmt::format("{} 2", ns), "Int", 4, path::springs),
              attribute("failed", "Cell", ns, "UChar", 1, path::spring_failed) +
                  attribute("kind", "Cell", ns, "UChar", 1, path::spring_kind) +
                  attribute("stiffness", "Cell", ns, "Float", 8, path::spring_stiffness) +
                  attribute("strength_factor", "Cell", ns, "Float", 8, path::strength_factor));
  if (nf > 0) x += grid("shell", "Triangle", nf, "", heavy(fmt::format("{} 3", nf), "Int", 4, path::faces), "");
  x += "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return x;
}

fs::path sidecar_path(const fs::path& file) {
  fs::path p = file;
  return p.replace_extension(".xdmf");
}

// ---- reading --------------------------------------------------------------------------------

/// Reads a dataset and checks its shape; `why` says where the expected sizes come from.
template <typename T>
std::vector<T> read_shaped(hid_t root, const char* dataset, const std::vector<hsize_t>& expected, const char* why) {
  auto array = h5::read_dataset<T>(root, dataset);
  if (array.dims != expected)
    throw h5::Error(fmt::format("dataset {} has shape {}, expected {} ({})", dataset, shape_text(array.dims),
                                shape_text(expected), why));
  return std::move(array.values);
}

/// Reads an array stored flat into `out` (rows of std::array from [rows][K]).
template <typename E>
void unflatten(std::vector<typename Flat<E>::value_type>&& values, std::vector<E>& out) {
  if constexpr (Flat<E>::width == 1) {
    out = std::move(values);
  } else {
    out.resize(values.size() / Flat<E>::width);
    if (!out.empty()) std::memcpy(out.data(), values.data(), values.size() * sizeof(values[0]));
  }
}

/// The shape an array must have; `defined` is the row count set by an earlier array, or none
/// when this array defines it (then any row count is accepted).
std::string shape_pattern(const Shape& shape, std::optional<hsize_t> defined) {
  const std::string rows = defined ? std::to_string(*defined) : rows_symbol[static_cast<std::size_t>(shape.rows)];
  if (shape.time_slice) return fmt::format("[1, {}, {}]", rows, shape.columns);
  if (shape.columns > 0) return fmt::format("[{}, {}]", rows, shape.columns);
  return fmt::format("[{}]", rows);
}

/// Every per-element array (visit_element_arrays), each shape checked against the row counts.
void read_element_arrays(hid_t root, Checkpoint& c) {
  std::array<std::optional<hsize_t>, 4> count;
  std::array<const char*, 4> defined_by{};
  visit_element_arrays(c, [&](const char* dataset, auto& values, const Shape& shape) {
    using E = typename std::decay_t<decltype(values)>::value_type;
    auto array = h5::read_dataset<typename Flat<E>::value_type>(root, dataset);
    const std::size_t kind = static_cast<std::size_t>(shape.rows);
    const std::size_t rank = shape.time_slice ? 3 : shape.columns > 0 ? 2 : 1;
    const std::size_t row_axis = shape.time_slice ? 1 : 0;
    const bool rank_ok = array.dims.size() == rank && (!shape.time_slice || array.dims[0] == 1) &&
                         (shape.columns == 0 || array.dims.back() == shape.columns);
    if (rank_ok && !count[kind]) {
      count[kind] = array.dims[row_axis];
      defined_by[kind] = dataset;
    }
    if (!rank_ok || array.dims[row_axis] != *count[kind])
      throw h5::Error(fmt::format("dataset {} has shape {}, expected {}{}", dataset, shape_text(array.dims),
                                  shape_pattern(shape, rank_ok ? count[kind] : std::nullopt),
                                  rank_ok ? fmt::format(" ({} from {})", rows_symbol[kind], defined_by[kind]) : ""));
    unflatten(std::move(array.values), values);
  });
}

/// Which program wrote the file (/parameters/provenance), for inspect.
void read_provenance(hid_t root, Provenance& p) {
  h5::Group g = h5::open_group(root, "/parameters/provenance");
  p.version = h5::read_string_attribute(g.get(), "version");
  p.git_commit = h5::read_string_attribute(g.get(), "git_commit");
  p.compiler = h5::read_string_attribute(g.get(), "compiler");
  p.build_flags = h5::read_string_attribute(g.get(), "build_flags");
}


/// The file's format version, read first (every format has kept /checkpoint@format_version):
/// a file of another version may lay out anything else. One it cannot read is an h5::Error
/// saying which versions this program reads.
std::int64_t readable_format_version(hid_t root) {
  h5::Group g = h5::open_group(root, "/checkpoint");
  const std::int64_t version = h5::read_attribute<std::int64_t>(g.get(), "format_version");
  if (version > checkpoint_format_version)
    throw h5::Error(fmt::format("written by a newer tidalcrust (format {}); this one reads up to {}", version,
                                checkpoint_format_version));
  if (version < oldest_readable_format)
    throw h5::Error(fmt::format("written in format {}, too old: this tidalcrust reads formats {} to {} "
                                "(docs/checkpoint-layout.md, Format versions)",
                                version, oldest_readable_format, checkpoint_format_version));
  return version;
}

/// Format 4 on carry the integrity record, and some format 3 files (written between the
/// integrity check and format 4): verified wherever there is one, required from format 4.
bool carries_integrity_record(hid_t root, std::int64_t version) {
  return version >= 4 || h5::exists(root, integrity_group);
}

void read_stage_info(hid_t root, Checkpoint& c) {
  h5::Group g = h5::open_group(root, "/checkpoint");
  const std::string stage = h5::read_string_attribute(g.get(), "stage");
  if (!make_stage_record(stage, c.stage.record))
    throw h5::Error(
        fmt::format("attribute /checkpoint@stage is '{}', expected one of build, stretch, relax, encounter", stage));
  const auto complete = h5::read_attribute<std::uint8_t>(g.get(), "complete");
  if (complete > 1) throw h5::Error(fmt::format("attribute /checkpoint@complete is {}, expected 0 or 1", +complete));
  c.stage.complete = complete == 1;
  c.state.time = h5::read_attribute<double>(g.get(), "time");
  c.state.step = h5::read_attribute<std::int64_t>(g.get(), "step");
  c.stage.clock.dt = h5::read_attribute<double>(g.get(), "dt");
  if (!(c.stage.clock.dt > 0) || !std::isfinite(c.stage.clock.dt))
    throw h5::Error(fmt::format("attribute /checkpoint@dt is {}, expected a finite number > 0", c.stage.clock.dt));
  c.stage.clock.start_time = h5::read_attribute<double>(g.get(), "start_time");
  c.stage.clock.start_step = h5::read_attribute<std::int64_t>(g.get(), "start_step");
  c.stage.end_step = h5::read_attribute<std::int64_t>(g.get(), "end_step");
  c.stage.parent_hash = h5::read_string_attribute(g.get(), "parent_hash");
  c.stage.fingerprint = h5::read_string_attribute(g.get(), "fingerprint");
  c.stage.diagnostic = h5::read_string_attribute(g.get(), "diagnostic");
  // Absent in files written before the kernel was recorded: unknown, and never refused.
  for (auto [name, value] : {std::pair{"gravity_kernel", &c.stage.gravity_kernel},
                             std::pair{"gravity_kernel_changes", &c.stage.gravity_kernel_changes}})
    if (H5Aexists(g.get(), name) > 0) *value = h5::read_string_attribute(g.get(), name);
  c.body.softening = h5::read_attribute<double>(g.get(), "softening");
  read_liquid_layer(g.get(), c.body, c.state);
  h5::Group record = h5::open_group(g.get(), "record");
  std::visit([&](auto& r) { visit_fields(r, RecordReader{record.get()}); }, c.stage.record);
}

void read_body_and_state(hid_t root, Checkpoint& c) {
  read_element_arrays(root, c);
  const auto step = read_shaped<std::int64_t>(root, path::position_step, {1}, "one time slice");
  const auto time = read_shaped<double>(root, path::position_time, {1}, "one time slice");
  if (step[0] != c.state.step || std::memcmp(&time[0], &c.state.time, sizeof(double)) != 0)
    throw h5::Error(fmt::format("datasets {} and {} ({}, {}) disagree with /checkpoint@step and @time ({}, {})",
                                path::position_step, path::position_time, step[0], time[0], c.state.step,
                                c.state.time));

  c.state.perturber = Perturber{};
  if (h5::exists(root, path::perturber)) {
    auto& p = c.state.perturber;
    p.present = true;
    p.mass = read_shaped<double>(root, "/checkpoint/perturber/mass", {}, "a scalar")[0];
    auto pos = read_shaped<double>(root, "/checkpoint/perturber/position", {3}, "a 3-vector");
    auto vel = read_shaped<double>(root, "/checkpoint/perturber/velocity", {3}, "a 3-vector");
    std::copy(pos.begin(), pos.end(), p.position.begin());
    std::copy(vel.begin(), vel.end(), p.velocity.begin());
  }
}

/// The failure log and the timeseries (visit_columns); the first column of each defines n.
void read_observables(hid_t root, Observables& o) {
  visit_observables(o, [&](const char* group_path, auto& rows) {
    using Row = typename std::decay_t<decltype(rows)>::value_type;
    h5::Group group = h5::open_group(root, group_path);
    std::optional<hsize_t> n;
    std::string first;
    visit_columns(std::type_identity<Row>{}, [&](const char* name, auto member) {
      using Value = std::decay_t<decltype(std::declval<Row>().*member)>;
      const std::string dataset = fmt::format("{}/{}", group_path, name);
      auto array = h5::read_dataset<typename Flat<Value>::value_type>(root, dataset);
      const bool rank_ok = array.dims.size() == column_dims<Value>(0).size() &&
                           (Flat<Value>::width == 1 || array.dims[1] == Flat<Value>::width);
      if (rank_ok && !n) {
        n = array.dims[0];
        first = dataset;
        rows.resize(*n);
      }
      if (!rank_ok || array.dims[0] != *n)
        throw h5::Error(fmt::format("dataset {} has shape {}, expected [{}{}]{}", dataset, shape_text(array.dims),
                                    n ? std::to_string(*n) : "n", Flat<Value>::width > 1 ? ", 3" : "",
                                    n ? fmt::format(" (n from {})", first) : ""));
      std::vector<Value> column;
      unflatten(std::move(array.values), column);
      for (std::size_t i = 0; i < rows.size(); ++i) rows[i].*member = column[i];
    });
  });
}

/// How often a read that fails with a transient error (EIO, EAGAIN, ESTALE, ETIMEDOUT, ENOMEM:
/// a flaky disk, an NFS hiccup) is tried in all, and the pause before the first retry (doubled
/// each time; the wait is for the file system to recover, its length changes no result).
constexpr int read_attempts = 4;
constexpr auto first_retry_pause = std::chrono::milliseconds(50);

bool transient_read_error(int err) {
  return err == EIO || err == EAGAIN || err == ESTALE || err == ETIMEDOUT || err == ENOMEM || err == EINTR;
}

/// One attempt at the whole file: its bytes, or the errno of the failed call (`what` says which).
int read_all_bytes(const fs::path& file, std::string& bytes, std::string& what) {
  bytes.clear();
  if (const int injected = test_point_read_attempt(); injected != 0) return what = "cannot read checkpoint", injected;
  // O_NONBLOCK: opening a FIFO must not wait for a writer.
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return what = errno == ENOENT ? "no such checkpoint file" : "cannot open checkpoint", errno;
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return what = "cannot open checkpoint", err;
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    what = S_ISDIR(st.st_mode) ? std::strerror(EISDIR) : "a FIFO, socket or device";
    return -1;
  }
  bytes.resize(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::pread(fd, bytes.data() + done, bytes.size() - done, static_cast<off_t>(done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      return what = "cannot read checkpoint", err;
    }
    if (n == 0) break;  // shorter than fstat said: truncated meanwhile; the signature or HDF5 says so
    done += static_cast<std::size_t>(n);
  }
  bytes.resize(done);
  ::close(fd);
  return 0;
}

/// The bytes of `file`, read with plain POSIX calls before HDF5 sees them (HDF5 then reads
/// only memory): a missing file, a denied permission, a folder, a FIFO or an I/O error is
/// reported with its real cause (the errno text) instead of as "not an HDF5 file" or a missing
/// group; a transient error is tried again (read_attempts) before it is reported. Then checks
/// the HDF5 signature at offset 0 (where every file written here has it).
std::string checkpoint_bytes(const fs::path& file) {
  const std::string name = file.string();
  std::string bytes, what;
  int err = 0;
  auto pause = first_retry_pause;
  for (int attempt = 1;; ++attempt, pause *= 2) {
    err = read_all_bytes(file, bytes, what);
    if (err == 0 || !transient_read_error(err) || attempt == read_attempts) {
      if (err == -1) throw InputError(fmt::format("{}: not a regular file ({})", name, what));
      if (err != 0)
        throw InputError(fmt::format("{}: {}: {}{}", name, what, std::strerror(err),
                                     attempt > 1 ? fmt::format(" ({} attempts)", attempt) : ""));
      break;
    }
    std::this_thread::sleep_for(pause);
  }
  static constexpr char signature[8] = {'\x89', 'H', 'D', 'F', '\r', '\n', '\x1a', '\n'};
  if (bytes.size() < sizeof signature || std::memcmp(bytes.data(), signature, sizeof signature) != 0)
    throw InputError(fmt::format("{}: not an HDF5 file or truncated (no HDF5 signature at its start)", name));
  return bytes;
}

}  // namespace

void write_checkpoint(const fs::path& file, const Checkpoint& checkpoint) {
  const auto problem = consistency_problem(checkpoint);
  TIDALCRUST_ASSERT(problem.empty(),
                    fmt::format("write_checkpoint {}: inconsistent checkpoint: {}", file.string(), problem));
  std::string bytes, sidecar;
  try {
    reserve_memory_for_writing(file, checkpoint);
    bytes = hdf5_bytes(file, checkpoint);
    sidecar = xdmf_text(checkpoint, file.filename().string());
  } catch (const h5::Error& err) {
    throw InputError(fmt::format("{}: cannot build the checkpoint in memory: {}", file.string(), err.what()));
  } catch (const std::bad_alloc&) {
    throw InputError(fmt::format("{}: not enough memory to build the checkpoint (the limit of this process, ulimit "
                                 "-v, or of the machine); nothing was written",
                                 file.string()));
  }
  // The bytes reach the disk through plain writes, so a failure (disk full, quota, folder not
  // writable) is reported with its errno text and HDF5 never holds a half-written file.
  write_file_atomically(file, bytes);
  write_file_atomically(sidecar_path(file), sidecar);
}

namespace {

/// read_checkpoint, but for std::bad_alloc.
Checkpoint read_checkpoint_file(const fs::path& file) {
  const std::string name = file.string();
  const std::string bytes = checkpoint_bytes(file);
  h5::File f;
  try {
    // Not the file's own name: the core driver then looks for that file on disk.
    f = h5::open_memory_image(bytes, name + " (in memory)");
  } catch (const h5::Error& err) {
    std::string why = err.what();
    if (why.starts_with(h5::memory_image_error)) why.erase(0, std::strlen(h5::memory_image_error));
    throw InputError(fmt::format("{}: not an HDF5 file or truncated (HDF5 cannot open it: {})", name, why));
  }
  Checkpoint c;
  std::string stored_hash;
  std::int64_t version = 0;
  try {
    const hid_t stored = f.get();
    h5::refuse_external_links(stored);  // before any path is opened: it might lead into another file
    version = readable_format_version(stored);
    // Every byte the reads below use is verified, on the file as stored, before any of it is
    // upgraded or interpreted.
    if (carries_integrity_record(stored, version)) verify_integrity(stored);
    // An older layout is upgraded in a writable copy in memory; the file is never touched.
    h5::File upgraded;
    if (needs_layout_upgrade(stored, version)) {
      upgraded = h5::open_memory_image(bytes, name + " (upgraded)", true);
      upgrade_layout(upgraded.get(), version);
    }
    const hid_t root = upgraded ? upgraded.get() : stored;
    read_stage_info(root, c);
    h5::Group g = h5::open_group(root, "/checkpoint");
    stored_hash = h5::read_string_attribute(g.get(), "state_hash");
    read_body_and_state(root, c);
    c.config_toml = h5::read_string_dataset(root, path::config);
    read_provenance(root, c.provenance);
    c.provenance.format_version = version;
    read_observables(root, c.observables);
  } catch (const h5::Error& err) {
    throw InputError(fmt::format("{}: {}", name, err.what()));
  }
  if (auto problem = consistency_problem(c); !problem.empty())
    throw InputError(fmt::format("{}: dataset {}", name, problem));
  const std::string computed = state_hash(c.state);
  if (computed != stored_hash)
    throw InputError(fmt::format("{}: state_hash mismatch: stored {}, computed {} (file modified or corrupt)", name,
                                 stored_hash, computed));
  upgrade_meaning(c, version);
  return c;
}

}  // namespace

Checkpoint read_checkpoint(const fs::path& file) {
  try {
    return read_checkpoint_file(file);
  } catch (const std::bad_alloc&) {
    throw InputError(fmt::format("{}: not enough memory to read the checkpoint (the limit of this process, ulimit -v, "
                                 "or of the machine)",
                                 file.string()));
  }
}

bool is_valid_checkpoint(const fs::path& file) {
  try {
    read_checkpoint(file);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace tidalcrust
