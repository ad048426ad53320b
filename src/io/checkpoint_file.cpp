// Checkpoint files: the HDF5 layout of design.md "Checkpoints" (H5MD 1.1 compatible), written
// atomically and reproducibly, read back with full validation, plus the .xdmf sidecar.
#include "io/checkpoint_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "build_info.hpp"
#include "base/errors.hpp"
#include "io/atomic_file.hpp"
#include "io/hdf5_handles.hpp"
#include "io/state_hash.hpp"

namespace tidalcrust {

namespace fs = std::filesystem;

namespace {

// The flat [rows][cols] views below rely on std::array having no padding.
static_assert(sizeof(std::array<std::int32_t, 2>) == 2 * sizeof(std::int32_t));
static_assert(sizeof(std::array<std::int32_t, 4>) == 4 * sizeof(std::int32_t));
static_assert(sizeof(std::array<std::int32_t, 3>) == 3 * sizeof(std::int32_t));
static_assert(sizeof(std::array<double, 3>) == 3 * sizeof(double));

constexpr const char* stage_names[] = {"build", "stretch", "relax", "encounter"};

bool is_stage_name(const std::string& stage) {
  return std::any_of(std::begin(stage_names), std::end(stage_names), [&](const char* s) { return stage == s; });
}

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
constexpr const char* spring_damping = "/checkpoint/springs/damping";
constexpr const char* spring_kind = "/checkpoint/springs/kind";
constexpr const char* spring_failed = "/checkpoint/springs/failed";
constexpr const char* rest_angle = "/checkpoint/hinges/rest_angle";
constexpr const char* hinge_stiffness = "/checkpoint/hinges/stiffness";
constexpr const char* perturber = "/checkpoint/perturber";
constexpr const char* config = "/parameters/config";
}  // namespace path

std::string shape_text(const std::vector<hsize_t>& dims) {
  std::string s = "[";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? ", " : "") + std::to_string(dims[i]);
  return s + "]";
}

// ---- consistency of an in-memory checkpoint (checked before writing) ------------------------

/// Empty if every array has the size the body implies and every index is in range; otherwise
/// a message naming the dataset that would be wrong.
std::string consistency_problem(const Checkpoint& c) {
  const std::size_t n = c.body.mass.size(), ns = c.body.springs.size(), nh = c.body.hinges.size();
  auto size_problem = [](const char* dataset, std::size_t have, std::size_t want) {
    return have == want ? std::string() : fmt::format("{} has {} values, expected {}", dataset, have, want);
  };
  for (auto problem : {size_problem(path::species, c.body.species.size(), n),
                       size_problem(path::position, c.state.position.size(), 3 * n),
                       size_problem(path::velocity, c.state.velocity.size(), 3 * n),
                       size_problem(path::spring_kind, c.body.spring_kind.size(), ns),
                       size_problem(path::rest_length, c.state.springs.rest_length.size(), ns),
                       size_problem(path::spring_stiffness, c.state.springs.stiffness.size(), ns),
                       size_problem(path::spring_damping, c.state.springs.damping.size(), ns),
                       size_problem(path::spring_failed, c.state.springs.failed.size(), ns),
                       size_problem(path::rest_angle, c.state.hinges.rest_angle.size(), nh),
                       size_problem(path::hinge_stiffness, c.state.hinges.stiffness.size(), nh)})
    if (!problem.empty()) return problem;
  if (!is_stage_name(c.stage.stage)) return fmt::format("/checkpoint@stage '{}' is not a stage name", c.stage.stage);
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
  for (std::size_t r = 0; r < n; ++r)
    if (c.body.species[r] > 1) return fmt::format("{} row {}: species {} is not 0 or 1", path::species, r, +c.body.species[r]);
  for (std::size_t r = 0; r < ns; ++r) {
    if (c.body.spring_kind[r] > 2)
      return fmt::format("{} row {}: kind {} is not 0, 1 or 2", path::spring_kind, r, +c.body.spring_kind[r]);
    if (c.state.springs.failed[r] > 1)
      return fmt::format("{} row {}: flag {} is not 0 or 1", path::spring_failed, r, +c.state.springs.failed[r]);
  }
  for (std::size_t r = 0; r < c.observables.failures.size(); ++r) {
    auto s = c.observables.failures[r].spring;
    if (s < 0 || static_cast<std::size_t>(s) >= ns)
      return fmt::format("/observables/failures/spring row {}: spring index {} out of range [0, {})", r, s, ns);
  }
  return {};
}

// ---- writing --------------------------------------------------------------------------------

template <typename T, std::size_t K>
const T* flat(const std::vector<std::array<T, K>>& rows) {
  return rows.empty() ? nullptr : rows.front().data();
}

void write_h5md_header(hid_t root) {
  h5::Group h5md = h5::create_group(root, "h5md");
  h5::write_attribute_array<std::int32_t>(h5md.get(), "version", {1, 1});
  h5::Group author = h5::create_group(h5md.get(), "author");
  // A fixed author keeps files from different users byte-identical.
  h5::write_string_attribute(author.get(), "name", "tidalcrust user");
  h5::Group creator = h5::create_group(h5md.get(), "creator");
  h5::write_string_attribute(creator.get(), "name", "tidalcrust");
  h5::write_string_attribute(creator.get(), "version", build_info::version);
}

void write_particles(hid_t root, const Checkpoint& c) {
  const hsize_t n = c.body.mass.size();
  h5::Group particles = h5::create_group(root, "particles");
  h5::Group body = h5::create_group(particles.get(), "body");
  {
    h5::Group box = h5::create_group(body.get(), "box");
    h5::write_attribute<std::int32_t>(box.get(), "dimension", 3);
    h5::write_string_array_attribute(box.get(), "boundary", {"none", "none", "none"});
  }
  {
    h5::Group position = h5::create_group(body.get(), "position");
    h5::write_dataset(position.get(), "value", c.state.position, {1, n, 3});
    h5::write_dataset<std::int64_t>(position.get(), "step", &c.state.step, {1});
    h5::write_dataset<double>(position.get(), "time", &c.state.time, {1});
  }
  {
    h5::Group velocity = h5::create_group(body.get(), "velocity");
    h5::write_dataset(velocity.get(), "value", c.state.velocity, {1, n, 3});
    h5::hard_link(root, path::position_step, "/particles/body/velocity/step");
    h5::hard_link(root, path::position_time, "/particles/body/velocity/time");
  }
  h5::write_dataset(body.get(), "mass", c.body.mass, {n});
  h5::write_dataset(body.get(), "species", c.body.species, {n});
}

void write_connectivity(hid_t root, const Body& b) {
  h5::Group group = h5::create_group(root, "connectivity");
  h5::write_dataset(group.get(), "springs", flat(b.springs), {b.springs.size(), 2});
  h5::write_dataset(group.get(), "hinges", flat(b.hinges), {b.hinges.size(), 4});
  h5::write_dataset(group.get(), "faces", flat(b.faces), {b.faces.size(), 3});
}

void write_checkpoint_group(hid_t root, const Checkpoint& c, const std::string& hash) {
  h5::Group group = h5::create_group(root, "checkpoint");
  hid_t g = group.get();
  h5::write_attribute<std::int64_t>(g, "format_version", checkpoint_format_version);
  h5::write_string_attribute(g, "stage", c.stage.stage);
  h5::write_attribute<std::uint8_t>(g, "complete", c.stage.complete ? 1 : 0);
  h5::write_attribute<double>(g, "time", c.state.time);
  h5::write_attribute<std::int64_t>(g, "step", c.state.step);
  h5::write_attribute<double>(g, "dt", c.state.dt);
  h5::write_string_attribute(g, "state_hash", hash);
  h5::write_string_attribute(g, "parent_hash", c.stage.parent_hash);
  h5::write_attribute<std::int64_t>(g, "start_step", c.stage.start_step);
  h5::write_attribute<std::int64_t>(g, "end_step", c.stage.end_step);
  h5::write_attribute<double>(g, "softening", c.body.softening);

  const hsize_t ns = c.body.springs.size(), nh = c.body.hinges.size();
  {
    h5::Group springs = h5::create_group(g, "springs");
    h5::write_dataset(springs.get(), "rest_length", c.state.springs.rest_length, {ns});
    h5::write_dataset(springs.get(), "stiffness", c.state.springs.stiffness, {ns});
    h5::write_dataset(springs.get(), "damping", c.state.springs.damping, {ns});
    h5::write_dataset(springs.get(), "kind", c.body.spring_kind, {ns});
    h5::write_dataset(springs.get(), "failed", c.state.springs.failed, {ns});
  }
  {
    h5::Group hinges = h5::create_group(g, "hinges");
    h5::write_dataset(hinges.get(), "rest_angle", c.state.hinges.rest_angle, {nh});
    h5::write_dataset(hinges.get(), "stiffness", c.state.hinges.stiffness, {nh});
  }
  if (c.state.perturber.present) {
    h5::Group perturber = h5::create_group(g, "perturber");
    h5::write_dataset<double>(perturber.get(), "mass", &c.state.perturber.mass, {});
    h5::write_dataset(perturber.get(), "position", c.state.perturber.position.data(), {3});
    h5::write_dataset(perturber.get(), "velocity", c.state.perturber.velocity.data(), {3});
  }
  {
    h5::Group scalars = h5::create_group(g, "scalars");
    for (const auto& [name, value] : c.stage.scalars) h5::write_attribute<double>(scalars.get(), name, value);
  }
  {
    h5::Group labels = h5::create_group(g, "labels");
    for (const auto& [name, value] : c.stage.labels) h5::write_string_attribute(labels.get(), name, value);
  }
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

/// Gathers one member of each row into a column (rows of structs -> dataset columns).
template <typename Row, typename Get>
auto column(const std::vector<Row>& rows, Get get) {
  std::vector<std::decay_t<decltype(get(rows.front()))>> out;
  out.reserve(rows.size());
  for (const auto& r : rows) out.push_back(get(r));
  return out;
}

template <typename Row, typename Get>
std::vector<double> vector_column(const std::vector<Row>& rows, Get get) {
  std::vector<double> out;
  out.reserve(3 * rows.size());
  for (const auto& r : rows) {
    const std::array<double, 3>& v = get(r);
    out.insert(out.end(), v.begin(), v.end());
  }
  return out;
}

void write_observables(hid_t root, const Observables& o) {
  h5::Group group = h5::create_group(root, "observables");
  {
    const auto& rows = o.failures;
    const hsize_t n = rows.size();
    h5::Group failures = h5::create_group(group.get(), "failures");
    h5::write_dataset(failures.get(), "time", column(rows, [](const FailureEvent& e) { return e.time; }), {n});
    h5::write_dataset(failures.get(), "step", column(rows, [](const FailureEvent& e) { return e.step; }), {n});
    h5::write_dataset(failures.get(), "spring", column(rows, [](const FailureEvent& e) { return e.spring; }), {n});
    h5::write_dataset(failures.get(), "strain", column(rows, [](const FailureEvent& e) { return e.strain; }), {n});
    h5::write_dataset(failures.get(), "position",
                      vector_column(rows, [](const FailureEvent& e) -> const auto& { return e.position; }), {n, 3});
  }
  {
    const auto& rows = o.timeseries;
    const hsize_t n = rows.size();
    h5::Group series = h5::create_group(group.get(), "timeseries");
    using S = TimeseriesSample;
    h5::write_dataset(series.get(), "time", column(rows, [](const S& s) { return s.time; }), {n});
    h5::write_dataset(series.get(), "failed", column(rows, [](const S& s) { return s.failed; }), {n});
    h5::write_dataset(series.get(), "kinetic_energy", column(rows, [](const S& s) { return s.kinetic_energy; }), {n});
    h5::write_dataset(series.get(), "momentum",
                      vector_column(rows, [](const S& s) -> const auto& { return s.momentum; }), {n, 3});
    h5::write_dataset(series.get(), "angular_momentum",
                      vector_column(rows, [](const S& s) -> const auto& { return s.angular_momentum; }), {n, 3});
    h5::write_dataset(series.get(), "perturber_offset",
                      vector_column(rows, [](const S& s) -> const auto& { return s.perturber_offset; }), {n, 3});
  }
}

void write_hdf5(const fs::path& file, const Checkpoint& c) {
  h5::File f = h5::create_file(file);
  const hid_t root = f.get();
  write_h5md_header(root);
  write_particles(root, c);
  write_connectivity(root, c.body);
  write_checkpoint_group(root, c, state_hash(c.state));
  write_parameters(root, c);
  write_observables(root, c.observables);
  h5::check(H5Fflush(root, H5F_SCOPE_LOCAL), "cannot flush");
  f.close("cannot close (disk full?)");
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
  // position/value and velocity/value are [1][N][3]: select the one time slice.
  auto slice = [&](const char* dataset) {
    return fmt::format(
        "<DataItem ItemType=\"HyperSlab\" Type=\"HyperSlab\" Dimensions=\"{0} 3\">\n"
        "            <DataItem Dimensions=\"3 3\" Format=\"XML\">0 0 0 1 1 1 1 {0} 3</DataItem>\n"
        "            {1}\n"
        "          </DataItem>",
        n, heavy(fmt::format("1 {} 3", n), "Float", 8, dataset));
  };
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
                   xml_escape(c.stage.stage));
  x += fmt::format("      <Time Value=\"{}\"/>\n", c.state.time);
  if (n > 0) {
    x += "      <Grid Name=\"particles\" GridType=\"Uniform\">\n";
    x += fmt::format("        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"{0}\" NodesPerElement=\"1\">\n"
                     "          <DataItem Dimensions=\"{0}\" NumberType=\"Int\" Precision=\"4\" Format=\"XML\">",
                     n);
    for (std::size_t i = 0; i < n; ++i) x += (i % 20 == 0 ? "\n" : " ") + std::to_string(i);
    x += "\n          </DataItem>\n        </Topology>\n";
    x += geometry;
    x += attribute("species", "Node", n, "UChar", 1, path::species);
    x += attribute("mass", "Node", n, "Float", 8, path::mass);
    x += fmt::format("        <Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n          {}\n"
                     "        </Attribute>\n",
                     slice(path::velocity));
    x += "      </Grid>\n";
  }
  if (ns > 0) {
    x += "      <Grid Name=\"springs\" GridType=\"Uniform\">\n";
    x += fmt::format("        <Topology TopologyType=\"Polyline\" NumberOfElements=\"{}\" NodesPerElement=\"2\">\n"
                     "          {}\n        </Topology>\n",
                     ns, heavy(fmt::format("{} 2", ns), "Int", 4, path::springs));
    x += geometry;
    x += attribute("failed", "Cell", ns, "UChar", 1, path::spring_failed);
    x += attribute("kind", "Cell", ns, "UChar", 1, path::spring_kind);
    x += attribute("stiffness", "Cell", ns, "Float", 8, path::spring_stiffness);
    x += "      </Grid>\n";
  }
  if (nf > 0) {
    x += "      <Grid Name=\"shell\" GridType=\"Uniform\">\n";
    x += fmt::format("        <Topology TopologyType=\"Triangle\" NumberOfElements=\"{}\">\n"
                     "          {}\n        </Topology>\n",
                     nf, heavy(fmt::format("{} 3", nf), "Int", 4, path::faces));
    x += geometry;
    x += "      </Grid>\n";
  }
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

/// Reads a [rows][K] dataset whose row count defines a size (springs, hinges, faces, ...).
template <typename T>
h5::Array<T> read_rows(hid_t root, const char* dataset, hsize_t columns) {
  auto array = h5::read_dataset<T>(root, dataset);
  const bool ok = columns == 0 ? array.dims.size() == 1 : (array.dims.size() == 2 && array.dims[1] == columns);
  if (!ok)
    throw h5::Error(fmt::format("dataset {} has shape {}, expected {}", dataset, shape_text(array.dims),
                                columns == 0 ? std::string("[n]") : fmt::format("[n, {}]", columns)));
  return array;
}

template <std::size_t K>
std::vector<std::array<std::int32_t, K>> to_rows(const std::vector<std::int32_t>& values) {
  std::vector<std::array<std::int32_t, K>> rows(values.size() / K);
  if (!rows.empty()) std::memcpy(rows.data(), values.data(), values.size() * sizeof(std::int32_t));
  return rows;
}

std::array<double, 3> row3(const std::vector<double>& values, std::size_t i) {
  return {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
}

void read_stage_info(hid_t root, Checkpoint& c) {
  h5::Group g = h5::open_group(root, "/checkpoint");
  const std::int64_t version = h5::read_attribute<std::int64_t>(g.get(), "format_version");
  if (version != checkpoint_format_version)
    throw h5::Error(fmt::format("attribute /checkpoint@format_version is {}, this tidalcrust reads version {}",
                                version, checkpoint_format_version));
  c.stage.stage = h5::read_string_attribute(g.get(), "stage");
  if (!is_stage_name(c.stage.stage))
    throw h5::Error(fmt::format("attribute /checkpoint@stage is '{}', expected one of build, stretch, relax, encounter",
                                c.stage.stage));
  const auto complete = h5::read_attribute<std::uint8_t>(g.get(), "complete");
  if (complete > 1) throw h5::Error(fmt::format("attribute /checkpoint@complete is {}, expected 0 or 1", +complete));
  c.stage.complete = complete == 1;
  c.state.time = h5::read_attribute<double>(g.get(), "time");
  c.state.step = h5::read_attribute<std::int64_t>(g.get(), "step");
  c.state.dt = h5::read_attribute<double>(g.get(), "dt");
  c.stage.parent_hash = h5::read_string_attribute(g.get(), "parent_hash");
  c.stage.start_step = h5::read_attribute<std::int64_t>(g.get(), "start_step");
  c.stage.end_step = h5::read_attribute<std::int64_t>(g.get(), "end_step");
  c.body.softening = h5::read_attribute<double>(g.get(), "softening");
  {
    h5::Group scalars = h5::open_group(g.get(), "scalars");
    for (const auto& name : h5::attribute_names(scalars.get()))
      c.stage.scalars[name] = h5::read_attribute<double>(scalars.get(), name);
  }
  {
    h5::Group labels = h5::open_group(g.get(), "labels");
    for (const auto& name : h5::attribute_names(labels.get()))
      c.stage.labels[name] = h5::read_string_attribute(labels.get(), name);
  }
}

void read_body_and_state(hid_t root, Checkpoint& c) {
  auto position = h5::read_dataset<double>(root, path::position);
  if (position.dims.size() != 3 || position.dims[0] != 1 || position.dims[2] != 3)
    throw h5::Error(fmt::format("dataset {} has shape {}, expected [1, N, 3]", path::position, shape_text(position.dims)));
  const hsize_t n = position.dims[1];
  const char* n_from = "N from /particles/body/position/value";
  c.state.position = std::move(position.values);
  c.state.velocity = read_shaped<double>(root, path::velocity, {1, n, 3}, n_from);
  c.body.mass = read_shaped<double>(root, path::mass, {n}, n_from);
  c.body.species = read_shaped<std::uint8_t>(root, path::species, {n}, n_from);

  const auto step = read_shaped<std::int64_t>(root, path::position_step, {1}, "one time slice");
  const auto time = read_shaped<double>(root, path::position_time, {1}, "one time slice");
  if (step[0] != c.state.step || std::memcmp(&time[0], &c.state.time, sizeof(double)) != 0)
    throw h5::Error(fmt::format("datasets {} and {} ({}, {}) disagree with /checkpoint@step and @time ({}, {})",
                                path::position_step, path::position_time, step[0], time[0], c.state.step,
                                c.state.time));

  auto springs = read_rows<std::int32_t>(root, path::springs, 2);
  const hsize_t ns = springs.dims[0];
  c.body.springs = to_rows<2>(springs.values);
  auto hinges = read_rows<std::int32_t>(root, path::hinges, 4);
  const hsize_t nh = hinges.dims[0];
  c.body.hinges = to_rows<4>(hinges.values);
  c.body.faces = to_rows<3>(read_rows<std::int32_t>(root, path::faces, 3).values);

  const char* ns_from = "Ns from /connectivity/springs";
  const char* nh_from = "Nh from /connectivity/hinges";
  c.state.springs.rest_length = read_shaped<double>(root, path::rest_length, {ns}, ns_from);
  c.state.springs.stiffness = read_shaped<double>(root, path::spring_stiffness, {ns}, ns_from);
  c.state.springs.damping = read_shaped<double>(root, path::spring_damping, {ns}, ns_from);
  c.body.spring_kind = read_shaped<std::uint8_t>(root, path::spring_kind, {ns}, ns_from);
  c.state.springs.failed = read_shaped<std::uint8_t>(root, path::spring_failed, {ns}, ns_from);
  c.state.hinges.rest_angle = read_shaped<double>(root, path::rest_angle, {nh}, nh_from);
  c.state.hinges.stiffness = read_shaped<double>(root, path::hinge_stiffness, {nh}, nh_from);

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

void read_observables(hid_t root, Observables& o) {
  {
    auto time = read_rows<double>(root, "/observables/failures/time", 0);
    const hsize_t n = time.dims[0];
    const char* n_from = "n from /observables/failures/time";
    auto step = read_shaped<std::int64_t>(root, "/observables/failures/step", {n}, n_from);
    auto spring = read_shaped<std::int32_t>(root, "/observables/failures/spring", {n}, n_from);
    auto strain = read_shaped<double>(root, "/observables/failures/strain", {n}, n_from);
    auto position = read_shaped<double>(root, "/observables/failures/position", {n, 3}, n_from);
    o.failures.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      o.failures[i] = {time.values[i], step[i], spring[i], strain[i], row3(position, i)};
  }
  {
    auto time = read_rows<double>(root, "/observables/timeseries/time", 0);
    const hsize_t n = time.dims[0];
    const char* n_from = "n from /observables/timeseries/time";
    auto failed = read_shaped<std::int64_t>(root, "/observables/timeseries/failed", {n}, n_from);
    auto energy = read_shaped<double>(root, "/observables/timeseries/kinetic_energy", {n}, n_from);
    auto momentum = read_shaped<double>(root, "/observables/timeseries/momentum", {n, 3}, n_from);
    auto angular = read_shaped<double>(root, "/observables/timeseries/angular_momentum", {n, 3}, n_from);
    auto offset = read_shaped<double>(root, "/observables/timeseries/perturber_offset", {n, 3}, n_from);
    o.timeseries.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      o.timeseries[i] = {time.values[i], failed[i], energy[i], row3(momentum, i), row3(angular, i), row3(offset, i)};
  }
}

}  // namespace

void write_checkpoint(const fs::path& file, const Checkpoint& checkpoint) {
  if (auto problem = consistency_problem(checkpoint); !problem.empty())
    throw std::logic_error(fmt::format("write_checkpoint {}: inconsistent checkpoint: {}", file.string(), problem));
  replace_file_atomically(file, [&](const fs::path& tmp) {
    try {
      write_hdf5(tmp, checkpoint);
    } catch (const h5::Error& err) {
      throw InputError(fmt::format("{}: cannot write checkpoint ({} {}): folder missing or not writable, or disk full",
                                   file.string(), err.what(), tmp.string()));
    }
  });
  write_file_atomically(sidecar_path(file), xdmf_text(checkpoint, file.filename().string()));
}

Checkpoint read_checkpoint(const fs::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError(fmt::format("{}: no such checkpoint file", name));
  if (!fs::is_regular_file(file, ec)) throw InputError(fmt::format("{}: not a regular file", name));
  h5::silence_errors();
  if (H5Fis_hdf5(file.c_str()) <= 0) throw InputError(fmt::format("{}: not an HDF5 file or truncated", name));
  h5::File f;
  try {
    f = h5::open_file_readonly(file);
  } catch (const h5::Error&) {
    throw InputError(fmt::format("{}: not an HDF5 file or truncated", name));
  }
  Checkpoint c;
  std::string stored_hash;
  try {
    const hid_t root = f.get();
    read_stage_info(root, c);
    h5::Group g = h5::open_group(root, "/checkpoint");
    stored_hash = h5::read_string_attribute(g.get(), "state_hash");
    read_body_and_state(root, c);
    c.config_toml = h5::read_string_dataset(root, path::config);
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
  return c;
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
