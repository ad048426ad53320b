#include <gtest/gtest.h>

#include <set>
#include <string>

#include "base/errors.hpp"
#include "bodies/body_type.hpp"
#include "bodies/build_body.hpp"
#include "model/config.hpp"
#include "support/force_test_bodies.hpp"

using namespace tidalcrust;

namespace {

Config with_core(Config config, double radius, double density_ratio, double modulus_ratio) {
  config.core.radius = radius;
  config.core.density_ratio = density_ratio;
  config.core.modulus_ratio = modulus_ratio;
  return config;
}

Vec3 position(const BuiltBody& b, std::size_t i) { return vec3_at(b.state.position, i); }

}  // namespace

TEST(BodyType, OneRowDescribesEachConfiguration) {
  const Config plain = test_support::small_body_config();
  EXPECT_EQ(body_type(plain).name, "homogeneous");
  EXPECT_EQ(body_type(with_core(plain, 0.4, 3, 10)).name, "layered");
  Config zero_core = plain;
  zero_core.core.radius = 0.0;  // no core: [core] with radius 0 is the homogeneous body
  EXPECT_EQ(body_type(zero_core).name, "homogeneous");
}

TEST(BuildBody, HomogeneousInteriorNodesShareTheInteriorMassEqually) {
  const Config config = test_support::small_body_config();
  const BuiltBody b = build_body(config);
  const std::size_t n_interior = b.body.count_species(Species::interior);
  ASSERT_GT(n_interior, 100u);
  for (std::size_t i = 0; i < n_interior; ++i)
    EXPECT_EQ(b.body.mass[i], (1.0 - config.shell.mass) / static_cast<double>(n_interior)) << i;
  for (std::size_t n = 0; n < b.body.spring_count(); ++n) {
    if (b.body.spring_kind[n] == static_cast<std::uint8_t>(SpringKind::interior)) {
      EXPECT_EQ(b.state.springs.stiffness[n], config.interior.spring_constant) << n;
    }
  }
}

TEST(BuildBody, LayeredCoreNodesAreDenserAndCoreSpringsStiffer) {
  const Config config = with_core(test_support::small_body_config(), 0.45, 3.0, 10.0);
  const BuiltBody b = build_body(config);
  const std::size_t n_interior = b.body.count_species(Species::interior);
  double core_mass = -1, mantle_mass = -1, interior_mass = 0;
  std::size_t core_nodes = 0;
  for (std::size_t i = 0; i < n_interior; ++i) {
    interior_mass += b.body.mass[i];
    if (position(b, i).norm() < 0.45) {
      ++core_nodes;
      if (core_mass < 0) core_mass = b.body.mass[i];
      EXPECT_EQ(b.body.mass[i], core_mass);
    } else {
      if (mantle_mass < 0) mantle_mass = b.body.mass[i];
      EXPECT_EQ(b.body.mass[i], mantle_mass);
    }
  }
  ASSERT_GT(core_nodes, 5u);
  EXPECT_DOUBLE_EQ(core_mass / mantle_mass, 3.0);
  EXPECT_NEAR(interior_mass, 1.0 - config.shell.mass, 1e-14);
  std::set<double> core_k, mantle_k;
  for (std::size_t n = 0; n < b.body.spring_count(); ++n) {
    if (b.body.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::interior)) continue;
    const auto [i, j] = b.body.springs[n];
    const Vec3 mid = 0.5 * (position(b, static_cast<std::size_t>(i)) + position(b, static_cast<std::size_t>(j)));
    (mid.norm() < 0.45 ? core_k : mantle_k).insert(b.state.springs.stiffness[n]);
  }
  EXPECT_EQ(core_k, std::set<double>{10.0 * config.interior.spring_constant});
  EXPECT_EQ(mantle_k, std::set<double>{config.interior.spring_constant});
}

TEST(BuildBody, TheSameConfigurationGivesTheSameBits) {
  const Config config = with_core(test_support::small_body_config(), 0.45, 3.0, 10.0);
  const BuiltBody a = build_body(config), b = build_body(config);
  EXPECT_EQ(a.body.mass, b.body.mass);
  EXPECT_EQ(a.state.position, b.state.position);
  EXPECT_EQ(a.state.springs.stiffness, b.state.springs.stiffness);
  EXPECT_EQ(a.state.springs.rest_length, b.state.springs.rest_length);
  EXPECT_EQ(a.state.hinges.rest_angle, b.state.hinges.rest_angle);
  EXPECT_EQ(a.body.softening, b.body.softening);
}

TEST(BuildBody, AMaterialBodyWithNoCrossSpringIsAnErrorNamingTheKey) {
  Config config = load_config(TIDALCRUST_SOURCE_DIR "/workflows/material-L3.toml");
  apply_override(config, "resolution.cross_per_shell_node=1e-4");  // rounds to 0 pairs of 642 shell nodes
  try {
    build_body(config);
    FAIL() << "built a shell without cross springs";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("resolution.cross_per_shell_node"), std::string::npos) << e.what();
  }
}
