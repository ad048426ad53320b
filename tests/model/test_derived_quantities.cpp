#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "model/body.hpp"
#include "model/derived_quantities.hpp"
#include "model/state.hpp"

using namespace tidalcrust;

namespace {

constexpr double pi = std::numbers::pi;

/// Two interior nodes (0.4 each), two shell nodes (0.1 each); one interior spring, one shell
/// spring, two cross springs. Every node carries exactly two springs (b = 2).
void small_body(Body& body, State& state) {
  body.mass = {0.4, 0.4, 0.1, 0.1};
  body.species = {0, 0, 1, 1};
  body.springs = {{0, 1}, {2, 3}, {1, 2}, {0, 3}};
  body.spring_kind = {0, 1, 2, 2};
  state.position.assign(12, 0.0);
  state.velocity.assign(12, 0.0);
  state.springs.rest_length = {0.5, 0.2, 0.3, 0.1};
  state.springs.stiffness = {2.0, 0.06, 0.01, 0.03};
  state.springs.failed.assign(4, 0);
}

}  // namespace

TEST(DerivedQuantities, TableThreeEquationsOnAHandBuiltBody) {
  Body body;
  State state;
  small_body(body, state);
  const DerivedQuantities q = derive_quantities(body, state, 1.0);

  const double volume = 4.0 / 3.0 * pi;
  const double E_I = 2.0 * 0.5 * 0.5 / (6 * volume);  // eq. 15
  EXPECT_DOUBLE_EQ(q.E_I, E_I);
  EXPECT_DOUBLE_EQ(q.L_I, 0.5);
  EXPECT_DOUBLE_EQ(q.k_I, 2.0);
  EXPECT_DOUBLE_EQ(q.L_S, 0.2);
  EXPECT_DOUBLE_EQ(q.k_S, 0.06);
  EXPECT_DOUBLE_EQ(q.M_S, 0.2);
  EXPECT_DOUBLE_EQ(q.L_C, 0.2);
  EXPECT_DOUBLE_EQ(q.k_C, 0.02);
  // nu = 1/4: (1-nu)/((1+nu)(1-2nu)) = 0.75/0.625 = 1.2, rho = 3/(4 pi).
  EXPECT_NEAR(q.V_IP, std::sqrt(E_I / (3 / (4 * pi)) * 1.2), 1e-14);
  EXPECT_NEAR(q.V_SP, std::sqrt(0.06 * 4 * pi / 0.2), 1e-14);
  EXPECT_NEAR(q.V_Co, std::sqrt(0.02 * 2 / 0.2) * 0.2, 1e-14);
  EXPECT_NEAR(q.h_S, 2 / std::sqrt(3.0) * 0.06 / E_I, 1e-12);
  // Smallest sqrt(mu/(k b)) is the interior spring: mu = 0.2, k = 2, b = 2.
  EXPECT_NEAR(q.dt_max, std::sqrt(0.2 / (2.0 * 2)), 1e-15);
}

TEST(DerivedQuantities, PaperNumbersReproduceTableThree) {
  // Paper T column: k_S = 0.06, M_S = 0.07 gives V_SP = 3.28; k_C = 0.005, N_C = 5966,
  // L_C = 0.156 gives V_Co ~ 3.2 (Table 3 prints 3.3).
  Body body;
  State state;
  const int n_cross = 5966;
  body.mass = {0.93, 0.07};
  body.species = {0, 1};
  body.springs.push_back({0, 1});
  body.spring_kind.push_back(1);
  state.springs.rest_length.push_back(0.075);
  state.springs.stiffness.push_back(0.06);
  for (int n = 0; n < n_cross; ++n) {
    body.springs.push_back({0, 1});
    body.spring_kind.push_back(2);
    state.springs.rest_length.push_back(0.156);
    state.springs.stiffness.push_back(0.005);
  }
  const DerivedQuantities q = derive_quantities(body, state, 0.92);
  EXPECT_NEAR(q.V_SP, 3.28, 0.005);
  EXPECT_NEAR(q.V_Co, 3.22, 0.01);
}

TEST(DerivedQuantities, BodyWithoutShellHasZeroShellFields) {
  Body body;
  State state;
  body.mass = {0.5, 0.5};
  body.species = {0, 0};
  body.springs = {{0, 1}};
  body.spring_kind = {0};
  state.springs.rest_length = {0.3};
  state.springs.stiffness = {0.0076};
  const DerivedQuantities q = derive_quantities(body, state, 1.0);
  EXPECT_GT(q.E_I, 0);
  EXPECT_GT(q.V_IP, 0);
  EXPECT_EQ(q.M_S, 0);
  EXPECT_EQ(q.L_S, 0);
  EXPECT_EQ(q.k_S, 0);
  EXPECT_EQ(q.L_C, 0);
  EXPECT_EQ(q.k_C, 0);
  EXPECT_EQ(q.V_SP, 0);
  EXPECT_EQ(q.V_Co, 0);
  EXPECT_EQ(q.h_S, 0);
  // mu = 0.25, k = 0.0076, b = 1.
  EXPECT_NEAR(q.dt_max, std::sqrt(0.25 / 0.0076), 1e-14);
}

TEST(DerivedQuantities, EmptyBodyGivesZerosNotInfinities) {
  const DerivedQuantities q = derive_quantities(Body{}, State{}, 1.0);
  EXPECT_EQ(q.E_I, 0);
  EXPECT_EQ(q.V_IP, 0);
  EXPECT_EQ(q.dt_max, 0);
}
