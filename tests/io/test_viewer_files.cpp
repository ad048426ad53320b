// What outside readers need of a checkpoint, checked structurally (no python, no viewer): the
// .xdmf sidecar names only datasets that exist with the shape and type it declares, with no
// HyperSlab (ParaView's Xdmf3 readers load 0 points from one); the file is valid H5MD 1.1
// (version, author, creator, units, particles_group references, extensible time-dependent
// elements, nothing but H5MD elements in /observables). `make check-viewers` opens the files
// in ParaView and MDAnalysis themselves.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/checkpoint_file.hpp"
#include "io/hdf5_handles.hpp"
#include "model/moon_units.hpp"
#include "support/files.hpp"
#include "support/synthetic_checkpoint.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

namespace {

/// Shape, maximum shape and (XDMF NumberType, Precision) of a stored dataset.
struct StoredShape {
  std::vector<hsize_t> dims, max;
  std::string number_type;
  int precision = 0;
};

StoredShape stored_shape(hid_t root, const std::string& dataset) {
  h5::Dataset set(h5::check(H5Dopen2(root, dataset.c_str(), H5P_DEFAULT), "open " + dataset));
  h5::Dataspace space(H5Dget_space(set.get()));
  h5::Type type(H5Dget_type(set.get()));
  StoredShape s;
  const int rank = H5Sget_simple_extent_ndims(space.get());
  s.dims.resize(rank);
  s.max.resize(rank);
  H5Sget_simple_extent_dims(space.get(), s.dims.data(), s.max.data());
  s.precision = static_cast<int>(H5Tget_size(type.get()));
  if (H5Tget_class(type.get()) == H5T_FLOAT) s.number_type = "Float";
  else if (H5Tget_sign(type.get()) == H5T_SGN_NONE) s.number_type = s.precision == 1 ? "UChar" : "UInt";
  else s.number_type = s.precision == 1 ? "Char" : "Int";
  return s;
}

std::vector<hsize_t> numbers(const std::string& text) {
  std::vector<hsize_t> out;
  std::istringstream in(text);
  for (hsize_t v; in >> v;) out.push_back(v);
  return out;
}

/// The checkpoints the sidecar tests cover: an encounter with perturber, failures and faces,
/// and a build-like one without perturber, observables or faces.
std::map<std::string, Checkpoint> sidecar_cases() {
  std::map<std::string, Checkpoint> cases{{"encounter", synthetic_checkpoint()}};
  Checkpoint build = synthetic_checkpoint();
  build.stage.record = BuildRecord{200, 0, 0.1};
  build.state.perturber = Perturber{};
  build.observables = Observables{};
  build.body.faces.clear();
  cases.emplace("build", build);
  return cases;
}

std::string h5md_string(hid_t root, const char* group, const char* attribute) {
  h5::Group g = h5::open_group(root, group);
  return h5::read_string_attribute(g.get(), attribute);
}

std::string unit_of(hid_t root, const char* dataset) {
  h5::Object object(H5Oopen(root, dataset, H5P_DEFAULT));
  return h5::read_string_attribute(object.get(), "unit");
}

/// True if the attribute is stored as a variable-length string (H5MD's VL String[]).
bool is_variable_length_string(hid_t root, const char* object_path, const char* attribute) {
  h5::Object object(H5Oopen(root, object_path, H5P_DEFAULT));
  h5::Attribute attr(H5Aopen(object.get(), attribute, H5P_DEFAULT));
  h5::Type type(H5Aget_type(attr.get()));
  return H5Tget_class(type.get()) == H5T_STRING && H5Tis_variable_str(type.get()) > 0;
}

/// The file address of the object at `path` (equal for two hard links to one object).
haddr_t object_address(hid_t root, const char* path) {
  H5O_info_t info{};
  h5::check(H5Oget_info_by_name2(root, path, &info, H5O_INFO_BASIC, H5P_DEFAULT), path);
  return info.addr;
}

}  // namespace

TEST(ViewerFiles, SidecarDeclaresExactlyTheStoredShapesAndTypes) {
  for (const auto& [name, checkpoint] : sidecar_cases()) {
    const ScratchFolder scratch("sidecar_" + name);
    write_checkpoint(scratch.path / "c.h5", checkpoint);
    const std::string xml = read_file(scratch.path / "c.xdmf");
    h5::File f = h5::open_file_readonly(scratch.path / "c.h5");
    const std::regex item(
        R"re(<DataItem Dimensions="([0-9 ]+)" NumberType="(\w+)" Precision="(\d)" Format="HDF">([^<>:]+):(/[^<]+)</DataItem>)re");
    int references = 0;
    for (auto it = std::sregex_iterator(xml.begin(), xml.end(), item); it != std::sregex_iterator(); ++it) {
      const auto& m = *it;
      ++references;
      EXPECT_EQ(m[4].str(), "c.h5");
      ASSERT_TRUE(h5::exists(f.get(), m[5].str())) << name << ": " << m[5].str();
      const StoredShape stored = stored_shape(f.get(), m[5].str());
      EXPECT_EQ(numbers(m[1].str()), stored.dims) << name << ": " << m[5].str();
      EXPECT_EQ(m[2].str(), stored.number_type) << name << ": " << m[5].str();
      EXPECT_EQ(std::stoi(m[3].str()), stored.precision) << name << ": " << m[5].str();
    }
    // Every heavy DataItem matched the pattern above: none is left unchecked.
    std::size_t hdf_items = 0;
    for (std::size_t at = xml.find("Format=\"HDF\""); at != std::string::npos; at = xml.find("Format=\"HDF\"", at + 1))
      ++hdf_items;
    EXPECT_EQ(static_cast<std::size_t>(references), hdf_items) << name;
    EXPECT_GE(references, name == "build" ? 8 : 9) << name;
  }
}

TEST(ViewerFiles, SidecarHasNoHyperSlabAndOnePlainDataItemPerGeometryTopologyAndAttribute) {
  for (const auto& [name, checkpoint] : sidecar_cases()) {
    const ScratchFolder scratch("sidecar_plain_" + name);
    write_checkpoint(scratch.path / "c.h5", checkpoint);
    const std::string xml = read_file(scratch.path / "c.xdmf");
    EXPECT_EQ(xml.find("HyperSlab"), std::string::npos) << name;
    EXPECT_EQ(xml.find("ItemType"), std::string::npos) << name;
    // The legacy XDMFReader wants the DataItem as the first child of each of these elements.
    const std::regex holder(R"re(<(Geometry|Topology|Attribute)[^>]*>\s*<DataItem [^>]*>[^<]*</DataItem>\s*</\1>)re");
    std::size_t holders = 0;
    for (const char* tag : {"<Geometry ", "<Topology ", "<Attribute "})
      for (std::size_t at = xml.find(tag); at != std::string::npos; at = xml.find(tag, at + 1)) ++holders;
    const auto plain = static_cast<std::size_t>(
        std::distance(std::sregex_iterator(xml.begin(), xml.end(), holder), std::sregex_iterator()));
    EXPECT_EQ(plain, holders) << name;
    // The points of every grid are the N particles: [1][N][3] holds N * 3 coordinates.
    const std::size_t n = checkpoint.body.mass.size();
    EXPECT_NE(xml.find(fmt::format("<DataItem Dimensions=\"1 {} 3\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                                   "c.h5:/particles/body/position/value</DataItem>",
                                   n)),
              std::string::npos)
        << name;
  }
}

TEST(ViewerFiles, H5mdVersionAuthorAndCreatorAreSet) {
  const ScratchFolder scratch("h5md_header");
  const char* outside = std::getenv("TIDALCRUST_AUTHOR");
  const std::string saved = outside ? outside : "";
  ::setenv("TIDALCRUST_AUTHOR", "Ada Lovelace", 1);
  write_checkpoint(scratch.path / "named.h5", synthetic_checkpoint());
  ::unsetenv("TIDALCRUST_AUTHOR");
  write_checkpoint(scratch.path / "account.h5", synthetic_checkpoint());
  if (outside) ::setenv("TIDALCRUST_AUTHOR", saved.c_str(), 1);
  h5::File named = h5::open_file_readonly(scratch.path / "named.h5");
  h5::File account = h5::open_file_readonly(scratch.path / "account.h5");
  {
    h5::Group g = h5::open_group(named.get(), "/h5md");
    EXPECT_EQ(h5::read_attribute_array<std::int32_t>(g.get(), "version"), (std::vector<std::int32_t>{1, 1}));
  }
  EXPECT_EQ(h5md_string(named.get(), "/h5md/author", "name"), "Ada Lovelace");
  const std::string from_account = h5md_string(account.get(), "/h5md/author", "name");
  EXPECT_FALSE(from_account.empty());
  EXPECT_NE(from_account, "tidalcrust user");  // the old placeholder
  EXPECT_EQ(h5md_string(named.get(), "/h5md/creator", "name"), "tidalcrust");
  EXPECT_FALSE(h5md_string(named.get(), "/h5md/creator", "version").empty());
  for (auto [object, attribute] : {std::pair{"/h5md/author", "name"}, std::pair{"/h5md/creator", "name"},
                                   std::pair{"/h5md/creator", "version"}})
    EXPECT_TRUE(is_variable_length_string(named.get(), object, attribute)) << object << "@" << attribute;
}

TEST(ViewerFiles, ConnectivityListsReferenceTheParticlesGroup) {
  const ScratchFolder scratch("h5md_connectivity");
  write_checkpoint(scratch.path / "c.h5", synthetic_checkpoint());
  h5::File f = h5::open_file_readonly(scratch.path / "c.h5");
  for (const char* list : {"/connectivity/springs", "/connectivity/hinges", "/connectivity/faces"}) {
    h5::Object object(H5Oopen(f.get(), list, H5P_DEFAULT));
    ASSERT_TRUE(object) << list;
    EXPECT_EQ(h5::read_object_reference_attribute(object.get(), "particles_group"), "/particles/body") << list;
  }
}

TEST(ViewerFiles, DimensionfulElementsCarryUnitsOfTheUnitsModule) {
  const ScratchFolder scratch("h5md_units");
  write_checkpoint(scratch.path / "c.h5", synthetic_checkpoint());
  h5::File f = h5::open_file_readonly(scratch.path / "c.h5");
  {
    h5::Group units = h5::open_group(f.get(), "/h5md/modules/units");
    EXPECT_EQ(h5::read_attribute_array<std::int32_t>(units.get(), "version"), (std::vector<std::int32_t>{1, 0}));
    EXPECT_EQ(h5::read_string_attribute(units.get(), "system"), "SI");
    EXPECT_NE(h5::read_string_attribute(units.get(), "reduced_units").find("G = M = R = 1"), std::string::npos);
  }
  // Strings MDAnalysis's H5MDReader translates (nm, ps, "nm ps-1") and H5MD's SI system allows.
  EXPECT_EQ(unit_of(f.get(), "/particles/body/position/value"), "nm");
  EXPECT_EQ(unit_of(f.get(), "/particles/body/position/time"), "ps");
  EXPECT_EQ(unit_of(f.get(), "/particles/body/velocity/time"), "ps");  // the same dataset, hard-linked
  EXPECT_EQ(unit_of(f.get(), "/particles/body/velocity/value"), "nm ps-1");
  EXPECT_EQ(unit_of(f.get(), "/particles/body/mass"), "14983000 kg");
  EXPECT_TRUE(is_variable_length_string(f.get(), "/particles/body/position/value", "unit"));
}

// Of a [moon] workflow the unit strings are the moon's own units, with H5MD's numeric factor (a
// decimal fraction, no exponent): one stored number times its unit string is its SI value, as
// udunits2 reads the string (docs/checkpoint-layout.md, "Units in the file").
TEST(ViewerFiles, AMoonsUnitStringsAreItsOwnUnits) {
  const ScratchFolder scratch("h5md_moon_units");
  Checkpoint c = synthetic_checkpoint();
  c.config_toml = "[workflow]\nname = \"synthetic\"\n[moon]\npreset = \"tethys\"\n";
  write_checkpoint(scratch.path / "c.h5", c);
  h5::File f = h5::open_file_readonly(scratch.path / "c.h5");
  const ModelUnits u = model_units(0.62e21, 531e3);
  EXPECT_EQ(unit_of(f.get(), "/particles/body/position/value"), "531000.0 m");
  EXPECT_EQ(unit_of(f.get(), "/particles/body/mass"), "620000000000000000000.0 kg");
  for (const auto& [dataset, dimension] : {std::pair{"/particles/body/position/value", Dimension::length},
                                           std::pair{"/particles/body/position/time", Dimension::time},
                                           std::pair{"/particles/body/velocity/value", Dimension::speed},
                                           std::pair{"/particles/body/mass", Dimension::mass}}) {
    const std::string unit = unit_of(f.get(), dataset);
    EXPECT_EQ(unit.find_first_of("eE"), std::string::npos) << unit;  // no exponent
    const double one = quantity_si("1 " + unit, dimension, dataset);
    EXPECT_NEAR(one, model_unit(u, dimension), 1e-15 * model_unit(u, dimension)) << unit;
  }
  h5::Group units = h5::open_group(f.get(), "/h5md/modules/units");
  const std::string reduced = h5::read_string_attribute(units.get(), "reduced_units");
  EXPECT_NE(reduced.find("(Tethys)"), std::string::npos) << reduced;
  EXPECT_NE(reduced.find("R = 531000.0 m"), std::string::npos) << reduced;
  // The file reads back as any other (the unit strings are not read).
  EXPECT_EQ(read_checkpoint(scratch.path / "c.h5").config_toml, c.config_toml);
}

TEST(ViewerFiles, TimeDependentElementsHaveStepTimeValueExtensibleInTime) {
  const ScratchFolder scratch("h5md_elements");
  const Checkpoint c = synthetic_checkpoint();
  write_checkpoint(scratch.path / "c.h5", c);
  h5::File f = h5::open_file_readonly(scratch.path / "c.h5");
  const hsize_t n = c.body.mass.size();
  for (const std::string element : {"/particles/body/position", "/particles/body/velocity"}) {
    const StoredShape step = stored_shape(f.get(), element + "/step");
    const StoredShape time = stored_shape(f.get(), element + "/time");
    const StoredShape value = stored_shape(f.get(), element + "/value");
    EXPECT_EQ(step.number_type, "Int") << element;
    EXPECT_EQ(time.number_type, "Float") << element;
    EXPECT_EQ(step.dims, std::vector<hsize_t>{1}) << element;
    EXPECT_EQ(time.dims, std::vector<hsize_t>{1}) << element;
    EXPECT_EQ(value.dims, (std::vector<hsize_t>{1, n, 3})) << element;
    for (const StoredShape* s : {&step, &time, &value}) EXPECT_EQ(s->max.at(0), H5S_UNLIMITED) << element;
    EXPECT_EQ(value.max, (std::vector<hsize_t>{H5S_UNLIMITED, n, 3})) << element;
  }
  // Sampled together: velocity's step and time are position's (H5MD asks for hard links).
  EXPECT_EQ(object_address(f.get(), "/particles/body/velocity/step"),
            object_address(f.get(), "/particles/body/position/step"));
  EXPECT_EQ(object_address(f.get(), "/particles/body/velocity/time"),
            object_address(f.get(), "/particles/body/position/time"));
}

TEST(ViewerFiles, ObservablesHoldOnlyH5mdElementsAndOurRecordsLiveInCheckpoint) {
  const ScratchFolder scratch("h5md_observables");
  const Checkpoint c = synthetic_checkpoint();
  ASSERT_FALSE(c.observables.failures.empty());
  write_checkpoint(scratch.path / "c.h5", c);
  h5::File f = h5::open_file_readonly(scratch.path / "c.h5");
  // /observables is optional in H5MD; each of its members would have to be an element with a
  // `value`. The failure log (events, not samples of one quantity) and the timeseries are ours.
  if (h5::exists(f.get(), "/observables")) {
    h5::Group g = h5::open_group(f.get(), "/observables");
    hsize_t count = 0;
    H5Gget_num_objs(g.get(), &count);
    for (hsize_t i = 0; i < count; ++i) {
      char member[256] = {0};
      H5Gget_objname_by_idx(g.get(), i, member, sizeof member);
      EXPECT_TRUE(h5::exists(g.get(), std::string(member) + "/value")) << member;
    }
  }
  EXPECT_EQ(stored_shape(f.get(), "/checkpoint/failures/position").dims,
            (std::vector<hsize_t>{c.observables.failures.size(), 3}));
  EXPECT_EQ(stored_shape(f.get(), "/checkpoint/timeseries/time").dims,
            std::vector<hsize_t>{c.observables.timeseries.size()});
}

TEST(ViewerFiles, SpeciesAndSpringKindsAreLabelled) {
  const ScratchFolder scratch("h5md_labels");
  write_checkpoint(scratch.path / "c.h5", synthetic_checkpoint());
  h5::File f = h5::open_file_readonly(scratch.path / "c.h5");
  h5::Object species(H5Oopen(f.get(), "/particles/body/species", H5P_DEFAULT));
  EXPECT_EQ(h5::read_string_array_attribute(species.get(), "labels"), (std::vector<std::string>{"interior", "shell"}));
  h5::Object kind(H5Oopen(f.get(), "/checkpoint/springs/kind", H5P_DEFAULT));
  EXPECT_EQ(h5::read_string_array_attribute(kind.get(), "labels"),
            (std::vector<std::string>{"interior", "shell", "cross"}));
}
