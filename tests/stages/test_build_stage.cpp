#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <set>

#include "stages/build_stage.hpp"
#include "support/files.hpp"
#include "support/force_test_bodies.hpp"
#include "model/derived_quantities.hpp"
#include "base/errors.hpp"
#include "forces/hinge_geometry.hpp"

using namespace tidalcrust;

namespace {

/// Shell level 2 (162 nodes) and ~200 interior nodes.
Config small_config() { return test_support::small_body_config(); }

Vec3 at(const Checkpoint& c, std::int32_t i) { return vec3_at(c.state.position, static_cast<std::size_t>(i)); }

bool is_shell(const Checkpoint& c, std::int32_t i) {
  return c.body.species[static_cast<std::size_t>(i)] == static_cast<std::uint8_t>(Species::shell);
}

std::string error_of(const Config& config) {
  try {
    build_stage(config);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(BuildStage, CountsOrderingAndSpecies) {
  const Config config = small_config();
  const Checkpoint c = build_stage(config);
  const Body& b = c.body;
  const std::size_t ni = b.count_species(Species::interior);
  EXPECT_EQ(ni, 200u);
  EXPECT_EQ(b.count_species(Species::shell), 162u);
  EXPECT_EQ(b.particle_count(), 362u);
  for (std::size_t i = 0; i < b.particle_count(); ++i) EXPECT_EQ(is_shell(c, static_cast<std::int32_t>(i)), i >= ni);
  EXPECT_EQ(b.count_springs(SpringKind::shell), 480u);
  EXPECT_EQ(b.hinge_count(), 480u);
  EXPECT_EQ(b.faces.size(), 320u);
  EXPECT_GT(b.count_springs(SpringKind::cross), 162u);
  // Springs ordered interior, shell, cross; within each kind i < j and sorted.
  for (std::size_t s = 1; s < b.spring_count(); ++s) {
    EXPECT_LE(b.spring_kind[s - 1], b.spring_kind[s]);
    if (b.spring_kind[s - 1] == b.spring_kind[s]) {
      EXPECT_LT(b.springs[s - 1], b.springs[s]);
    }
  }
  for (const auto& [i, j] : b.springs) EXPECT_LT(i, j);
  for (const auto& f : b.faces)
    for (auto i : f) EXPECT_TRUE(is_shell(c, i));
}

TEST(BuildStage, SpringsAreExactlyThePairsCloserThanTheirDistance) {
  const Config config = small_config();
  const Checkpoint c = build_stage(config);
  const Body& b = c.body;
  std::set<std::array<std::int32_t, 2>> built[3];
  for (std::size_t s = 0; s < b.spring_count(); ++s) built[b.spring_kind[s]].insert(b.springs[s]);
  std::set<std::array<std::int32_t, 2>> expected_interior, expected_cross;
  const auto n = static_cast<std::int32_t>(b.particle_count());
  for (std::int32_t i = 0; i < n; ++i)
    for (std::int32_t j = i + 1; j < n; ++j) {
      const double d = (at(c, i) - at(c, j)).norm();
      if (!is_shell(c, i) && !is_shell(c, j) && d < config.interior.spring_distance) expected_interior.insert({i, j});
      if (!is_shell(c, i) && is_shell(c, j) && d < config.cross.distance) expected_cross.insert({i, j});
    }
  EXPECT_EQ(built[0], expected_interior);
  EXPECT_EQ(built[2], expected_cross);
  for (const auto& [i, j] : built[1]) {
    EXPECT_TRUE(is_shell(c, i) && is_shell(c, j));
    EXPECT_LT((at(c, i) - at(c, j)).norm(), 0.35);  // a level-2 edge, never a chord across
  }
}

TEST(BuildStage, StateStartsAtRestWithBuiltLengthsAndConfiguredStiffness) {
  const Config config = small_config();
  const Checkpoint c = build_stage(config);
  const State& s = c.state;
  EXPECT_EQ(s.time, 0.0);
  EXPECT_EQ(s.step, 0);
  EXPECT_EQ(c.stage.clock, (StepClock{0.0, 0, 0.003}));
  EXPECT_EQ(s.position.size(), 3 * c.body.particle_count());
  for (double v : s.velocity) EXPECT_EQ(v, 0.0);
  const double k[3] = {config.interior.spring_constant, config.shell.spring_constant, config.cross.spring_constant};
  ASSERT_EQ(s.springs.rest_length.size(), c.body.spring_count());
  for (std::size_t n = 0; n < c.body.spring_count(); ++n) {
    const auto [i, j] = c.body.springs[n];
    EXPECT_EQ(s.springs.rest_length[n], (at(c, i) - at(c, j)).norm());
    EXPECT_EQ(s.springs.stiffness[n], k[c.body.spring_kind[n]]);
    EXPECT_EQ(s.springs.failed[n], 0);
  }
  EXPECT_FALSE(s.perturber.present);
}

TEST(BuildStage, HingeRestAnglesReproduceTheBuiltShapeWithOneSign) {
  const Config config = small_config();
  const Checkpoint c = build_stage(config);
  ASSERT_EQ(c.state.hinges.rest_angle.size(), c.body.hinge_count());
  for (std::size_t h = 0; h < c.body.hinge_count(); ++h) {
    const auto [w1, w2, a, b] = c.body.hinges[h];
    for (auto i : c.body.hinges[h]) EXPECT_TRUE(is_shell(c, i));
    EXPECT_EQ(c.state.hinges.rest_angle[h], hinge_angle(at(c, w1), at(c, w2), at(c, a), at(c, b)));
    EXPECT_GT(c.state.hinges.rest_angle[h], 0.0) << "hinge " << h;
    EXPECT_EQ(c.body.hinge_stiffness[h], config.shell.bending_constant);
  }
}

TEST(BuildStage, MassesSumToOneAndShellCarriesItsShare) {
  const Config config = small_config();
  const Checkpoint c = build_stage(config);
  double total = 0, shell = 0;
  for (std::size_t i = 0; i < c.body.particle_count(); ++i) {
    total += c.body.mass[i];
    if (is_shell(c, static_cast<std::int32_t>(i))) shell += c.body.mass[i];
  }
  EXPECT_NEAR(total, 1.0, 1e-13);
  EXPECT_NEAR(shell, config.shell.mass, 1e-14);
  EXPECT_EQ(c.body.mass.front(), 0.9 / 200);
  EXPECT_EQ(c.body.mass.back(), 0.1 / 162);
}

TEST(BuildStage, SofteningIsAFractionOfTheMinimumSpacingAndStageInfoIsFilled) {
  const Config config = small_config();
  const Checkpoint c = build_stage(config);
  double best = std::numeric_limits<double>::infinity();
  const auto n = static_cast<std::int32_t>(c.body.particle_count());
  for (std::int32_t i = 0; i < n; ++i)
    for (std::int32_t j = i + 1; j < n; ++j) best = std::min(best, (at(c, i) - at(c, j)).norm());
  EXPECT_EQ(c.stage.as<BuildRecord>().min_spacing, best);
  EXPECT_EQ(c.body.softening, 0.01 * best);
  EXPECT_STREQ(c.stage.name(), "build");
  EXPECT_TRUE(c.stage.complete);
  EXPECT_EQ(c.stage.clock.start_step, 0);
  EXPECT_EQ(c.stage.end_step, 0);
  EXPECT_EQ(c.stage.parent_hash, "");
  EXPECT_EQ(c.stage.as<BuildRecord>().interior_nodes, 200);
  EXPECT_GE(c.stage.as<BuildRecord>().interior_trials, 200);
  EXPECT_EQ(c.config_toml, to_toml(config));
  EXPECT_EQ(to_toml(parse_config(c.config_toml, "stored")), c.config_toml);
}

TEST(BuildStage, SameSeedSameBitsOtherSeedOtherBody) {
  Config config = small_config();
  const Checkpoint a = build_stage(config), b = build_stage(config);
  ASSERT_EQ(a.state.position.size(), b.state.position.size());
  for (std::size_t i = 0; i < a.state.position.size(); ++i)
    ASSERT_EQ(std::bit_cast<std::uint64_t>(a.state.position[i]), std::bit_cast<std::uint64_t>(b.state.position[i]));
  EXPECT_EQ(a.body.springs, b.body.springs);
  config.workflow.seed = 4;
  const Checkpoint other = build_stage(config);
  EXPECT_NE(other.state.position[0], a.state.position[0]);
}

TEST(BuildStage, BodyWithoutShellIsInteriorOnly) {
  Config config = small_config();
  config.shell.enabled = false;
  config.interior.radius = 1.0;
  const Checkpoint c = build_stage(config);
  EXPECT_EQ(c.body.count_species(Species::shell), 0u);
  EXPECT_EQ(c.body.spring_count(), c.body.count_springs(SpringKind::interior));
  EXPECT_EQ(c.body.hinge_count(), 0u);
  EXPECT_TRUE(c.body.faces.empty());
  for (double m : c.body.mass) EXPECT_EQ(m, 1.0 / 200);
  const DerivedQuantities q = derive_quantities(c.body, c.state, config.interior.radius);
  EXPECT_EQ(q.M_S, 0.0);
  EXPECT_EQ(q.V_Co, 0.0);
  EXPECT_GT(q.E_I, 0.0);
}

TEST(BuildStage, ImpossibleConfigurationsNameTheKey) {
  Config touching = small_config();
  touching.interior.radius = 1.0;
  EXPECT_NE(error_of(touching).find("interior.radius"), std::string::npos);
  Config massless = small_config();
  massless.shell.mass = 0;
  EXPECT_NE(error_of(massless).find("shell.mass"), std::string::npos);
  Config short_reach = small_config();
  short_reach.cross.distance = 0.1;  // gap 1 - 0.85 = 0.15
  EXPECT_NE(error_of(short_reach).find("cross.distance"), std::string::npos);
}

namespace {
Config workflow(const char* name) { return load_config(test_support::workflow_file(name)); }
}  // namespace

// paper-T builds in a few hundredths of a second: Table 3, T-series column.
TEST(BuildStage, PaperTBodyMatchesTableThree) {
  const Config config = workflow("paper-T.toml");
  const Checkpoint c = build_stage(config);
  const Body& b = c.body;
  EXPECT_EQ(b.count_species(Species::shell), 2562u);
  EXPECT_EQ(b.count_springs(SpringKind::shell), 7680u);
  EXPECT_EQ(b.hinge_count(), 7680u);
  EXPECT_EQ(b.faces.size(), 5120u);
  EXPECT_EQ(b.count_species(Species::interior), 1869u);
  EXPECT_NEAR(static_cast<double>(b.count_springs(SpringKind::interior)), 23363, 0.05 * 23363);
  EXPECT_NEAR(static_cast<double>(b.count_springs(SpringKind::cross)), 5966, 0.05 * 5966);
  const DerivedQuantities q = derive_quantities(b, c.state, config.interior.radius);
  EXPECT_NEAR(q.L_I, 0.176, 0.003);
  EXPECT_NEAR(q.L_S, 0.075, 0.001);
  EXPECT_NEAR(q.L_C, 0.156, 0.005);
  EXPECT_NEAR(q.M_S, 0.07, 1e-12);
  EXPECT_NEAR(q.V_SP, 3.28, 0.005);
  EXPECT_NEAR(q.V_Co, 3.3, 0.3);
  // Eq. 15 on the built body gives ~3.1; Table 3 prints 3.73 (see the builder report).
  EXPECT_GT(q.E_I, 2.8);
  EXPECT_LT(q.E_I, 3.8);
  EXPECT_GT(q.dt_max, config.integrator.dt);
}

TEST(BuildStage, QuickAndPaperNWorkflowsBuild) {
  const Config quick = workflow("quick.toml");
  const Checkpoint q = build_stage(quick);
  EXPECT_EQ(q.body.count_species(Species::interior), static_cast<std::size_t>(quick.interior.count));
  EXPECT_EQ(q.body.count_species(Species::shell), 642u);
  const DerivedQuantities dq = derive_quantities(q.body, q.state, quick.interior.radius);
  EXPECT_GT(dq.E_I, 3.0);
  EXPECT_LT(dq.E_I, 4.0);
  EXPECT_GT(dq.dt_max, quick.integrator.dt);

  const Config paper_n = workflow("paper-N.toml");
  const Checkpoint n = build_stage(paper_n);
  EXPECT_EQ(n.body.count_species(Species::interior), 798u);
  EXPECT_EQ(n.body.count_species(Species::shell), 0u);
  EXPECT_NEAR(static_cast<double>(n.body.spring_count()), 11632, 0.1 * 11632);
  EXPECT_GT(derive_quantities(n.body, n.state, 1.0).dt_max, paper_n.integrator.dt);
}
