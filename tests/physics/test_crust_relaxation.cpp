// The balanced crust support: cross springs that alone carry each shell node's weight.
#include <gtest/gtest.h>

#include <cmath>

#include "base/errors.hpp"
#include "base/vec3.hpp"
#include "physics/crust_relaxation.hpp"

using namespace tidalcrust;

namespace {

/// One shell node at (0, 0, 1) held by cross springs from interior nodes below it; gravity g
/// pulls it toward the origin. Springs start at their rest lengths (no tension).
struct Tripod {
  Body body;
  State state;
  std::vector<double> gravity;
  explicit Tripod(const std::vector<Vec3>& feet) {
    body.mass.push_back(1e-4);
    body.species.push_back(static_cast<std::uint8_t>(Species::shell));
    state.position = {0, 0, 1};
    for (std::size_t f = 0; f < feet.size(); ++f) {
      body.mass.push_back(0.1);
      body.species.push_back(static_cast<std::uint8_t>(Species::interior));
      state.position.insert(state.position.end(), {feet[f].x(), feet[f].y(), feet[f].z()});
      body.springs.push_back({static_cast<std::int32_t>(f + 1), 0});
      body.spring_kind.push_back(static_cast<std::uint8_t>(SpringKind::cross));
      state.springs.rest_length.push_back((Vec3(0, 0, 1) - feet[f]).norm());
      state.springs.stiffness.push_back(0.005);
      state.springs.failed.push_back(0);
    }
    state.velocity.assign(state.position.size(), 0.0);
    gravity.assign(state.position.size(), 0.0);
    gravity[0] = 0.3;  // a sideways pull as well as the weight: the node's g = (0.3, 0, -0.9)
    gravity[2] = -0.9;
  }
  /// Net force of the cross springs on the shell node plus its weight (G M^2/R^2).
  Vec3 net_force() const {
    Vec3 f = body.mass[0] * vec3_at(gravity, 0);
    for (std::size_t n = 0; n < body.springs.size(); ++n) {
      const Vec3 d = vec3_at(state.position, 0) - vec3_at(state.position, static_cast<std::size_t>(body.springs[n][0]));
      f -= state.springs.stiffness[n] * (d.norm() - state.springs.rest_length[n]) * d.normalized();
    }
    return f;
  }
};

}  // namespace

TEST(BalancedCrustSupport, ThreeDirectionsCarryTheWeightExactly) {
  Tripod t({{0.1, 0, 0.85}, {-0.05, 0.09, 0.85}, {-0.05, -0.09, 0.85}, {0, 0.02, 0.8}});
  ASSERT_GT(t.net_force().norm(), 5e-5);
  const CrossBalance b = balance_cross_springs(t.body, t.state, t.gravity);
  EXPECT_LT(t.net_force().norm(), 1e-18);
  EXPECT_LT(b.max_residual, 1e-12);
  EXPECT_EQ(b.unbalanced_nodes, 0);
  // Hanging on springs below it, the node is held up by compression: rest lengths grew.
  for (std::size_t n = 0; n < 4; ++n) EXPECT_GT(t.state.springs.rest_length[n], (Vec3(0, 0, 1) - vec3_at(t.state.position, n + 1)).norm());
}

TEST(BalancedCrustSupport, ABalancedNodeIsLeftAlone) {
  Tripod t({{0.1, 0, 0.85}, {-0.05, 0.09, 0.85}, {-0.05, -0.09, 0.85}});
  balance_cross_springs(t.body, t.state, t.gravity);
  const auto once = t.state.springs.rest_length;
  balance_cross_springs(t.body, t.state, t.gravity);
  for (std::size_t n = 0; n < once.size(); ++n) EXPECT_NEAR(t.state.springs.rest_length[n], once[n], 1e-15);
}

TEST(BalancedCrustSupport, CoplanarSpringsGiveTheBestTheyCanAndSaySo) {
  // Two springs in the x-z plane cannot push along y; the residual is the y part of the weight.
  Tripod t({{0.1, 0, 0.85}, {-0.1, 0, 0.85}});
  t.gravity[1] = 0.4;  // g = (0.3, 0.4, -0.9)
  const CrossBalance b = balance_cross_springs(t.body, t.state, t.gravity);
  EXPECT_EQ(b.unbalanced_nodes, 1);
  EXPECT_NEAR(b.max_residual, 0.4 / std::sqrt(0.09 + 0.16 + 0.81), 1e-12);
  EXPECT_NEAR(t.net_force().y(), 1e-4 * 0.4, 1e-17);
  EXPECT_NEAR(t.net_force().x(), 0.0, 1e-18);
  EXPECT_NEAR(t.net_force().z(), 0.0, 1e-18);
}

TEST(BalancedCrustSupport, SpringsTooWeakForTheWeightAreAnError) {
  Tripod t({{0.1, 0, 0.85}, {-0.05, 0.09, 0.85}, {-0.05, -0.09, 0.85}});
  for (double& k : t.state.springs.stiffness) k = 1e-6;
  EXPECT_THROW(balance_cross_springs(t.body, t.state, t.gravity), InputError);
}

// The lithostatic strain takes the interior's modulus from its springs deeper than d_I below r_I:
// a body whose r_I - d_I leaves none is bad input (exit 2 naming the keys), not an internal error.
TEST(LithostaticCrust, NoInteriorDeeperThanTheSpringReachIsAClearError) {
  Body body;
  State state;
  for (int k = 0; k < 2; ++k) {
    body.mass.push_back(0.01);
    body.species.push_back(static_cast<std::uint8_t>(Species::shell));
  }
  state.position = {1, 0, 0, 0, 1, 0};
  state.velocity.assign(6, 0.0);
  body.springs.push_back({0, 1});
  body.spring_kind.push_back(static_cast<std::uint8_t>(SpringKind::shell));
  state.springs.rest_length.push_back(std::sqrt(2.0));
  state.springs.stiffness.push_back(0.1);
  state.springs.failed.push_back(0);
  const std::vector<double> gravity = {-1, 0, 0, 0, -1, 0};
  try {
    lithostatic_crust_strain(body, state, gravity, 0.3, 0.4);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("interior.radius - interior.spring_distance = -0.1"), std::string::npos)
        << e.what();
  }
}
