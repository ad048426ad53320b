#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

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

// The key fuzz of issue 28 carried past validate (tests/model/test_config.cpp checks the ranges):
// every numeric key that the build reads, at the ends of its range and, where the range reaches 0
// or infinity, at 1e-320, 1e-300, 1e300 and 1e308. A value that validate accepts either builds a
// body whose derived quantities are finite (node masses normal numbers, every spring's and
// hinge's omega^2 one that a time step resolves) or is refused by an InputError of one line that
// names a key: never a derived quantity that overflowed or underflowed (shell.mass = 1e-320 gave
// shell nodes of 6e-323 M and a stretch error naming no key; spring constants of 1e308 an
// infinite acceleration at the first step, exit 1).
TEST(BuildBody, EveryValueThatValidatesBuildsFiniteScalesOrNamesTheKey) {
  const Config base = test_support::small_body_config();
  std::vector<std::pair<std::string, std::string>> cases;
  for (const KeyInfo& key : describe_keys(base)) {
    if ((key.type != "number" && key.type != "integer") || !key.read_by.contains(StageId::build)) continue;
    if (key.section == "material" || key.section == "resolution") continue;  // need a [material] body
    const std::string name = key.section + "." + key.name;
    const auto comma = key.range.find(", ");
    const std::string low = key.range.substr(1, comma - 1), high = key.range.substr(comma + 2, key.range.size() - comma - 3);
    std::vector<std::string> values = {low, high == "inf" ? "1e308" : high};
    if (std::stod(low) == 0) values.insert(values.end(), {"1e-320", "1e-300"});
    if (high == "inf") values.push_back("1e300");
    for (const std::string& v : values) {
      // Bodies too large for a unit test (the range allows 1,000,000 nodes) are not fuzzed here.
      if ((name == "interior.count" || name == "shell.level" || name == "interior.max_trials") && v == high) continue;
      cases.emplace_back(name, v);
    }
  }
  ASSERT_GT(cases.size(), 30u);
  for (const auto& [name, value] : cases) {
    Config config = base;
    try {
      apply_override(config, name + "=" + value);
      validate(config, "--set");
    } catch (const InputError&) {
      continue;  // refused before building: tests/model/test_config.cpp checks that message
    }
    try {
      const BuiltBody built = build_body(config);
      for (double m : built.body.mass)
        ASSERT_TRUE(std::isnormal(m)) << name << "=" << value << ": a node mass of " << m;
      for (std::size_t s = 0; s < built.body.spring_count(); ++s) {
        const auto [i, j] = built.body.springs[s];
        const double omega2 = built.state.springs.stiffness[s] *
                              (1 / built.body.mass[static_cast<std::size_t>(i)] + 1 / built.body.mass[static_cast<std::size_t>(j)]);
        ASSERT_TRUE(std::isfinite(omega2) && omega2 <= 4 / (min_time_step * min_time_step))
            << name << "=" << value << ": spring " << s << " has omega^2 = " << omega2;
      }
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      bool names_a_key = false;
      for (const KeyInfo& key : describe_keys(base))
        names_a_key = names_a_key || message.find(key.section + "." + key.name) != std::string::npos;
      EXPECT_TRUE(names_a_key) << name << "=" << value << ": " << message;
    }
  }
}

// The two examples of issue 28: each refused by the build, naming the key.
TEST(BuildBody, UnintegrableScalesAreRefusedNamingTheKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"shell.mass=1e-320", "shell.mass = 9.99989e-321 and interior.count = 200 give shell nodes of"},
      {"shell.mass=1e-300", "(shell.mass = 1e-300, interior.count = 200) give the shell springs omega^2"},
      {"shell.spring_constant=1e308", "shell.spring_constant = 1e+308"},
      {"interior.spring_constant=1e308", "interior.spring_constant = 1e+308"},
      {"cross.spring_constant=1e308", "cross.spring_constant = 1e+308"},
      {"shell.bending_constant=1e308", "shell.bending_constant = 1e+308"},
  };
  for (const auto& [assignment, expected] : cases) {
    Config config = test_support::small_body_config();
    apply_override(config, assignment);
    validate(config, "--set");
    try {
      build_body(config);
      ADD_FAILURE() << assignment << " was built";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << assignment << ": " << e.what();
      const bool subnormal = std::string(assignment) == "shell.mass=1e-320";
      EXPECT_NE(std::string(e.what()).find(subnormal ? "not a normal number" : "which no time step resolves"),
                std::string::npos)
          << e.what();
    }
  }
}

// A crust that varies (docs/crust.md): the builder samples [crust] into the body. A uniform crust
// has strength factor 1 everywhere; a thickness dichotomy toward +y (s11 = 0.5) makes the +y shell
// nodes heavier and their springs and hinges stiffer (t and t^3 of the node-mean-normalised
// factor), keeps the crust's mass, and a weak line lowers the strength of the springs on it only.
TEST(BuildBody, ACrustThatVariesIsSampledIntoMassesStiffnessesAndStrengths) {
  const Config plain = test_support::small_body_config();
  const BuiltBody uniform = build_body(plain);
  ASSERT_EQ(uniform.body.strength_factor.size(), uniform.body.spring_count());
  for (double f : uniform.body.strength_factor) EXPECT_EQ(f, 1.0);

  Config config = plain;
  config.crust.thickness_harmonics = "s11 = 0.5";
  config.crust.weak_lines = "pole_lon = 0, pole_lat = 0, half_width = 6, factor = 0.4";
  const BuiltBody varied = build_body(config);
  const Body& b = varied.body;
  ASSERT_EQ(b.spring_count(), uniform.body.spring_count());
  double shell_mass = 0, total = 0, heaviest_y = -2, lightest_y = 2, heaviest = 0, lightest = 1;
  for (std::size_t i = 0; i < b.particle_count(); ++i) {
    total += b.mass[i];
    if (b.species[i] != static_cast<std::uint8_t>(Species::shell)) {
      EXPECT_EQ(b.mass[i], uniform.body.mass[i]);  // the interior as before
      continue;
    }
    shell_mass += b.mass[i];
    const Vec3 p = position(varied, i);
    EXPECT_NEAR(b.mass[i] / uniform.body.mass[i], 1 + 0.5 * p.y(), 1e-12) << i;  // the icosphere's node mean of y is 0
    if (b.mass[i] > heaviest) heaviest = b.mass[i], heaviest_y = p.y();
    if (b.mass[i] < lightest) lightest = b.mass[i], lightest_y = p.y();
  }
  EXPECT_NEAR(shell_mass, config.shell.mass, 1e-14);
  EXPECT_NEAR(total, 1.0, 1e-14);
  EXPECT_GT(heaviest_y, 0.99);
  EXPECT_LT(lightest_y, -0.99);
  std::size_t weak = 0, shell = 0;
  for (std::size_t n = 0; n < b.spring_count(); ++n) {
    const Vec3 mid = 0.5 * (position(varied, static_cast<std::size_t>(b.springs[n][0])) +
                            position(varied, static_cast<std::size_t>(b.springs[n][1])));
    if (b.spring_kind[n] != static_cast<std::uint8_t>(SpringKind::shell)) {
      EXPECT_EQ(b.strength_factor[n], 1.0);
      EXPECT_EQ(varied.state.springs.stiffness[n], uniform.state.springs.stiffness[n]);
      continue;
    }
    ++shell;
    const double t = 1 + 0.5 * mid.y() / mid.norm();
    EXPECT_NEAR(varied.state.springs.stiffness[n], uniform.state.springs.stiffness[n] * t, 1e-12) << n;
    const double from_pole = std::acos(mid.normalized().x()) * 180 / M_PI;
    EXPECT_EQ(b.strength_factor[n], std::abs(from_pole - 90) <= 6 ? 0.4 : 1.0) << n;
    weak += b.strength_factor[n] < 1;
  }
  EXPECT_GT(weak, shell / 20);  // a 12-degree band: ~10% of the sphere
  EXPECT_LT(weak, shell / 6);
  for (std::size_t h = 0; h < b.hinge_count(); ++h) {
    const Vec3 mid = 0.5 * (position(varied, static_cast<std::size_t>(b.hinges[h][2])) +
                            position(varied, static_cast<std::size_t>(b.hinges[h][3])));
    const double t = 1 + 0.5 * mid.y() / mid.norm();
    EXPECT_NEAR(b.hinge_stiffness[h], uniform.body.hinge_stiffness[h] * t * t * t, 1e-12) << h;
  }
}

TEST(BuildBody, ACrustFactorThatIsNotPositiveSomewhereIsRefusedNamingTheKey) {
  Config config = test_support::small_body_config();
  config.crust.thickness_harmonics = "c10 = 1.2";  // < 0 south of lat -56 deg
  try {
    build_body(config);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("crust.thickness_harmonics (with crust.map_file): the crust's thickness factor "
                                          "is -0.",
                                          0),
              0u)
        << e.what();
  }
  config.crust.thickness_harmonics.reset();
  config.crust.strength_harmonics = "s11 = -1.2";  // < 0 within 34 deg of +y
  try {
    build_body(config);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crust.strength_harmonics"), std::string::npos) << e.what();
  }
}
