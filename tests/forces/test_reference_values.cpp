// The force laws against stored reference values (tests/reference/forces.toml, README there):
// a small fixed configuration and the forces and energies every law must give on it. The forces
// were generated once from the code before the force laws became evaluators, the energies from
// independent formulas, so the code is checked against stored numbers and not against itself.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "forces/force_field.hpp"
#include "forces/hinge_force.hpp"
#include "forces/perturber_gravity.hpp"
#include "forces/spring_force.hpp"

using namespace tidalcrust;

namespace {

constexpr const char* reference_file = TIDALCRUST_SOURCE_DIR "/tests/reference/forces.toml";

/// Every number under `node`, nested arrays flattened in order.
void flatten(const toml::node& node, std::vector<double>& out) {
  if (const toml::array* array = node.as_array()) {
    for (const toml::node& element : *array) flatten(element, out);
  } else {
    const std::optional<double> value = node.value<double>();
    if (!value) throw std::runtime_error(fmt::format("{}: a non-number in a numeric array", reference_file));
    out.push_back(*value);
  }
}

std::vector<double> numbers(const toml::table& table, std::string_view path) {
  const toml::node* node = table.at_path(path).node();
  if (!node) throw std::runtime_error(fmt::format("{}: no {}", reference_file, path));
  std::vector<double> out;
  flatten(*node, out);
  return out;
}

double number(const toml::table& table, std::string_view path) {
  const std::vector<double> v = numbers(table, path);
  if (v.size() != 1) throw std::runtime_error(fmt::format("{}: {} is not one number", reference_file, path));
  return v[0];
}

template <typename Int>
std::vector<Int> integers(const toml::table& table, std::string_view path) {
  std::vector<Int> out;
  for (double v : numbers(table, path)) out.push_back(static_cast<Int>(v));
  return out;
}

/// The fixed configuration of [configuration].
struct ReferenceCase {
  toml::table table;
  Body body;
  State state;
  ForceOptions options;
};

ReferenceCase load_reference() {
  ReferenceCase c;
  c.table = toml::parse_file(reference_file);
  const toml::table& t = c.table;
  Body& body = c.body;
  State& state = c.state;
  body.mass = numbers(t, "configuration.mass");
  body.species = integers<std::uint8_t>(t, "configuration.species");
  body.softening = number(t, "configuration.softening");
  const std::vector<std::int32_t> ends = integers<std::int32_t>(t, "configuration.springs.ends");
  for (std::size_t s = 0; s + 1 < ends.size(); s += 2) body.springs.push_back({ends[s], ends[s + 1]});
  body.spring_kind = integers<std::uint8_t>(t, "configuration.springs.kind");
  const std::vector<std::int32_t> corners = integers<std::int32_t>(t, "configuration.hinges.corners");
  for (std::size_t h = 0; h + 3 < corners.size(); h += 4)
    body.hinges.push_back({corners[h], corners[h + 1], corners[h + 2], corners[h + 3]});
  state.position = numbers(t, "configuration.position");
  state.velocity = numbers(t, "configuration.velocity");
  state.springs.rest_length = numbers(t, "configuration.springs.rest_length");
  state.springs.stiffness = numbers(t, "configuration.springs.stiffness");
  state.springs.failed.assign(body.spring_count(), 0);
  state.hinges.rest_angle = numbers(t, "configuration.hinges.rest_angle");
  body.hinge_stiffness = numbers(t, "configuration.hinges.stiffness");
  state.perturber.present = true;
  state.perturber.mass = number(t, "configuration.perturber.mass");
  const std::vector<double> px = numbers(t, "configuration.perturber.position");
  const std::vector<double> pv = numbers(t, "configuration.perturber.velocity");
  for (std::size_t k = 0; k < 3; ++k) {
    state.perturber.position[k] = px.at(k);
    state.perturber.velocity[k] = pv.at(k);
  }
  c.options.damping = number(t, "configuration.springs.damping");
  c.options.cross_nonlinear = t.at_path("configuration.cross.nonlinear").value_or(false);
  c.options.cross_strain_scale = number(t, "configuration.cross.strain_scale");
  c.options.cross_min_force_factor = number(t, "configuration.cross.min_force_factor");
  return c;
}

/// Printed instead of checked when TIDALCRUST_PRINT_REFERENCE is set: the values the code gives
/// now, in the file's layout, for a DELIBERATE regeneration (tests/reference/README.md).
bool printing() { return std::getenv("TIDALCRUST_PRINT_REFERENCE") != nullptr; }

void print_values(std::string_view path, const std::vector<double>& values) {
  std::string line = fmt::format("{} = [", path);
  for (std::size_t i = 0; i < values.size(); ++i) line += fmt::format("{}{}", i ? ", " : "", values[i]);
  fmt::print("{}]\n", line);
}

/// |computed - expected| <= tolerance * max |expected| for every element of the array at `path`,
/// with the tolerance of its table.
void expect_reference(const ReferenceCase& c, std::string_view path, const std::vector<double>& computed) {
  if (printing()) return print_values(path, computed);
  const std::vector<double> expected = numbers(c.table, path);
  const double tolerance = number(c.table, std::string(path.substr(0, path.find('.'))) + ".tolerance");
  ASSERT_EQ(computed.size(), expected.size()) << path;
  double scale = 0;
  for (double e : expected) scale = std::max(scale, std::abs(e));
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_LE(std::abs(computed[i] - expected[i]), tolerance * scale)
        << path << "[" << i << "]: computed " << fmt::format("{}", computed[i]) << ", stored "
        << fmt::format("{}", expected[i]);
}

}  // namespace

TEST(ReferenceValues, SpringForces) {
  const ReferenceCase c = load_reference();
  ForceField field(c.body, c.options);
  field.compute_spring_forces(c.state.position.data(), c.state.velocity.data(), c.state.springs);
  expect_reference(c, "springs.force", field.spring_forces());
}

TEST(ReferenceValues, HingeForces) {
  const ReferenceCase c = load_reference();
  ForceField field(c.body, c.options);
  EXPECT_EQ(field.compute_hinge_forces(c.state.position.data(), c.state.hinges), -1);
  expect_reference(c, "hinges.force", field.hinge_forces());
}

TEST(ReferenceValues, SelfGravity) {
  const ReferenceCase c = load_reference();
  ForceField field(c.body, c.options);
  std::vector<double> a(c.state.position.size());
  field.compute_gravity(c.state.position.data(), a.data());
  expect_reference(c, "self_gravity.acceleration", a);
}

TEST(ReferenceValues, Perturber) {
  const ReferenceCase c = load_reference();
  std::vector<double> a(c.state.position.size(), 0.0);
  const std::array<double, 3> back =
      add_perturber_gravity(c.body.mass, c.body.softening, c.state.position.data(), c.state.perturber, a.data());
  expect_reference(c, "perturber.acceleration", a);
  expect_reference(c, "perturber.perturber_acceleration", {back.begin(), back.end()});
}

TEST(ReferenceValues, AllLawsTogether) {
  const ReferenceCase c = load_reference();
  ForceField field(c.body, c.options);
  Accelerations a;
  EXPECT_FALSE(field.compute(c.state, a).any());
  expect_reference(c, "total.acceleration", a.body);
  expect_reference(c, "total.perturber_acceleration", {a.perturber.begin(), a.perturber.end()});
}

TEST(ReferenceValues, SpringEnergiesAndDampingPower) {
  const ReferenceCase c = load_reference();
  const CrossSoftening cross{c.options.cross_strain_scale, c.options.cross_min_force_factor};
  std::vector<double> energy, power;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s) {
    const auto [i, j] = c.body.springs[s];
    const Vec3 d = vec3_at(c.state.position, static_cast<std::size_t>(i)) -
                   vec3_at(c.state.position, static_cast<std::size_t>(j));
    const Vec3 dv = vec3_at(c.state.velocity, static_cast<std::size_t>(i)) -
                    vec3_at(c.state.velocity, static_cast<std::size_t>(j));
    const bool softened = c.body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::cross);
    const double mu = reduced_mass(c.body.mass[static_cast<std::size_t>(i)], c.body.mass[static_cast<std::size_t>(j)]);
    const SpringEvaluator spring(c.state.springs.rest_length[s], c.state.springs.stiffness[s],
                                 c.options.damping * mu, softened ? &cross : nullptr);
    const SpringForceEnergy r = spring.force_and_energy(d.norm(), d.dot(dv));
    energy.push_back(r.energy);
    power.push_back(r.dissipated_power);
  }
  expect_reference(c, "springs.elastic_energy", energy);
  expect_reference(c, "springs.dissipated_power", power);
}

TEST(ReferenceValues, HingeEnergies) {
  const ReferenceCase c = load_reference();
  std::vector<double> energy;
  for (std::size_t h = 0; h < c.body.hinge_count(); ++h) {
    const auto& v = c.body.hinges[h];
    auto x = [&](int corner) { return vec3_at(c.state.position, static_cast<std::size_t>(v[corner])); };
    energy.push_back(HingeEvaluator(c.state.hinges.rest_angle[h], c.body.hinge_stiffness[h])
                         .force_and_energy(x(0), x(1), x(2), x(3))
                         .energy);
  }
  expect_reference(c, "hinges.energy", energy);
}

TEST(ReferenceValues, EnergiesOfEveryLaw) {
  const ReferenceCase c = load_reference();
  ForceField field(c.body, c.options);
  const Energies e = field.energies(c.state);
  expect_reference(c, "self_gravity.energy", {e.self_gravity});
  expect_reference(c, "perturber.energy", {e.perturber});
  if (printing()) return;
  // The totals are the stored per-element values summed.
  auto sum = [&](std::string_view path) {
    double total = 0;
    for (double v : numbers(c.table, path)) total += v;
    return total;
  };
  EXPECT_NEAR(e.spring, sum("springs.elastic_energy"), 1e-12 * e.spring);
  EXPECT_NEAR(e.damping_power, sum("springs.dissipated_power"), 1e-12 * e.damping_power);
  EXPECT_NEAR(e.hinge, sum("hinges.energy"), 1e-12 * e.hinge);
}
