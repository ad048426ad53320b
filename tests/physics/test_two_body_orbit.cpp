#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>

#include "base/errors.hpp"
#include "physics/two_body_orbit.hpp"

using namespace tidalcrust;

namespace {

/// Classic RK4 of the relative two-body problem r'' = -mu r / |r|^3 over time `duration`
/// (negative integrates backward), in `steps` equal steps.
RelativeState integrate_rk4(RelativeState s, double mu, double duration, int steps) {
  const double h = duration / steps;
  auto accel = [mu](const Vec3& r) { return Vec3(-mu * r / std::pow(r.norm(), 3)); };
  for (int i = 0; i < steps; ++i) {
    const Vec3 k1x = s.velocity, k1v = accel(s.position);
    const Vec3 k2x = s.velocity + 0.5 * h * k1v, k2v = accel(s.position + 0.5 * h * k1x);
    const Vec3 k3x = s.velocity + 0.5 * h * k2v, k3v = accel(s.position + 0.5 * h * k2x);
    const Vec3 k4x = s.velocity + h * k3v, k4v = accel(s.position + h * k3x);
    s.position += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
    s.velocity += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  }
  return s;
}

double energy(const RelativeState& s, double mu) { return 0.5 * s.velocity.squaredNorm() - mu / s.position.norm(); }

/// Integrates from distance r before pericenter for the predicted time and checks that the
/// orbit arrives at pericenter (0, q, 0) with velocity (-V_q, 0, 0).
void expect_reaches_pericenter(const TwoBodyOrbit& orbit, double r) {
  const auto start = encounter_start(orbit, r);
  EXPECT_NEAR(start.relative.position.norm(), r, 1e-13 * r);
  EXPECT_NEAR(energy(start.relative, orbit.mu()), orbit.specific_energy(), 1e-13);
  const Vec3 L = start.relative.position.cross(start.relative.velocity);
  EXPECT_NEAR(L.z(), orbit.pericenter() * orbit.pericenter_speed(), 1e-13);
  EXPECT_NEAR(L.x(), 0.0, 1e-15);
  EXPECT_NEAR(L.y(), 0.0, 1e-15);
  EXPECT_LT(start.relative.position.dot(start.relative.velocity), 0.0);  // approaching
  EXPECT_GT(start.relative.position.x(), 0.0);                           // comes in from +x

  const auto end = integrate_rk4(start.relative, orbit.mu(), start.time_to_pericenter, 20000);
  const double q = orbit.pericenter(), vq = orbit.pericenter_speed();
  EXPECT_NEAR(end.position.x(), 0.0, 1e-6 * q);
  EXPECT_NEAR(end.position.y(), q, 1e-6 * q);
  EXPECT_NEAR(end.position.norm(), q, 1e-6 * q);
  EXPECT_NEAR(end.velocity.x(), -vq, 1e-6 * vq);
  EXPECT_NEAR(end.velocity.y(), 0.0, 1e-6 * vq);
  EXPECT_NEAR(end.velocity.norm(), vq, 1e-6 * vq);
}

void expect_same_state(const RelativeState& a, const RelativeState& b, double tol) {
  EXPECT_NEAR((a.position - b.position).norm(), 0.0, tol * b.position.norm());
  EXPECT_NEAR((a.velocity - b.velocity).norm(), 0.0, tol * b.velocity.norm());
}

}  // namespace

TEST(TwoBodyOrbit, ClassifiesByEccentricity) {
  const double mu = 2.0, q = 2.0, escape = std::sqrt(2.0 * mu / q);
  const TwoBodyOrbit parabolic(mu, q, escape);
  EXPECT_EQ(parabolic.type(), OrbitType::parabolic);
  EXPECT_NEAR(parabolic.eccentricity(), 1.0, 1e-15);
  EXPECT_EQ(TwoBodyOrbit(mu, q, 1.2).type(), OrbitType::elliptic);
  EXPECT_NEAR(TwoBodyOrbit(mu, q, 1.2).eccentricity(), 0.44, 1e-14);
  EXPECT_NEAR(TwoBodyOrbit(mu, q, 1.2).apocenter(), 2.0 * 1.44 / 0.56, 1e-13);
  EXPECT_EQ(TwoBodyOrbit(mu, q, 1.5).type(), OrbitType::hyperbolic);
  EXPECT_EQ(TwoBodyOrbit(mu, q, escape * (1 + 1e-6)).type(), OrbitType::hyperbolic);
  EXPECT_EQ(TwoBodyOrbit(mu, q, escape * (1 - 1e-6)).type(), OrbitType::elliptic);
  EXPECT_STREQ(orbit_type_name(OrbitType::hyperbolic), "hyperbolic");
}

TEST(TwoBodyOrbit, FrameAtPericenter) {
  const TwoBodyOrbit orbit(1.5, 1.84, 1.60);
  const auto peri = orbit.state_at_time(0.0);
  EXPECT_NEAR((peri.position - Vec3(0.0, 1.84, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((peri.velocity - Vec3(-1.60, 0.0, 0.0)).norm(), 0.0, 1e-15);
  const auto out = orbit.state_at_distance(3.0, OrbitBranch::outgoing);
  EXPECT_LT(out.position.x(), 0.0);  // leaves toward -x
  EXPECT_GT(out.position.dot(out.velocity), 0.0);
}

TEST(TwoBodyOrbit, ParabolicReachesPericenterAtPredictedTime) {
  const double mu = 2.0, q = 2.0;
  const TwoBodyOrbit orbit(mu, q, std::sqrt(2.0 * mu / q));
  ASSERT_EQ(orbit.type(), OrbitType::parabolic);
  expect_reaches_pericenter(orbit, 3.0);
  expect_reaches_pericenter(orbit, 10.0);
}

TEST(TwoBodyOrbit, HyperbolicReachesPericenterAtPredictedTime) {
  expect_reaches_pericenter(TwoBodyOrbit(2.0, 2.0, 1.8), 3.0);
  expect_reaches_pericenter(TwoBodyOrbit(1.1, 1.47, 1.62), 3.0);
}

TEST(TwoBodyOrbit, EllipticReachesPericenterAtPredictedTime) {
  const TwoBodyOrbit orbit(2.0, 2.0, 1.2);
  ASSERT_EQ(orbit.type(), OrbitType::elliptic);
  expect_reaches_pericenter(orbit, 3.0);
  expect_reaches_pericenter(orbit, orbit.apocenter());  // from apocenter: half a period
  EXPECT_NEAR(orbit.time_to_pericenter(orbit.apocenter()), 0.5 * orbit.period(), 1e-13 * orbit.period());
}

// Near e = 1 (outside the parabolic tolerance) the elliptic and hyperbolic time formulas have no
// cancellation: they agree with RK4, and with Barker's equation to about |e - 1|.
TEST(TwoBodyOrbit, NearlyParabolicOrbitsAreAccurate) {
  const double mu = 2.0, q = 2.0, escape = std::sqrt(2.0 * mu / q);
  const double t_parabolic = TwoBodyOrbit(mu, q, escape).time_to_pericenter(3.0);
  for (double de : {-1e-6, -4e-9, 4e-9, 1e-6}) {
    const TwoBodyOrbit orbit(mu, q, escape * std::sqrt(1.0 + de / 2.0));  // e - 1 = de
    SCOPED_TRACE(de);
    ASSERT_NE(orbit.type(), OrbitType::parabolic);
    EXPECT_NEAR(orbit.eccentricity() - 1.0, de, 1e-14);
    EXPECT_NEAR(orbit.time_to_pericenter(3.0) / t_parabolic - 1.0, 0.0, 2.0 * std::abs(de));
    expect_reaches_pericenter(orbit, 3.0);
    const auto start = encounter_start(orbit, 3.0);
    expect_same_state(orbit.state_at_time(-start.time_to_pericenter), start.relative, 1e-12);
  }
}

// The analytic state at any time matches RK4 from the start state, before and after pericenter,
// and over more than one period of an elliptic orbit.
TEST(TwoBodyOrbit, AnalyticStateAtTimeMatchesIntegration) {
  const double mu = 2.0, q = 2.0;
  const TwoBodyOrbit orbits[] = {TwoBodyOrbit(mu, q, 1.2), TwoBodyOrbit(mu, q, std::sqrt(2.0 * mu / q)),
                                 TwoBodyOrbit(1.5, 1.84, 1.60)};
  for (const auto& orbit : orbits) {
    SCOPED_TRACE(orbit_type_name(orbit.type()));
    const auto start = encounter_start(orbit, 3.0);
    expect_same_state(orbit.state_at_time(-start.time_to_pericenter), start.relative, 1e-13);
    const double span = orbit.type() == OrbitType::elliptic ? 1.3 * orbit.period() : 3.0;
    for (double fraction : {0.25, 0.5, 1.0}) {
      const double t = fraction * span;
      const auto numeric = integrate_rk4(start.relative, orbit.mu(), t, 40000);
      expect_same_state(orbit.state_at_time(t - start.time_to_pericenter), numeric, 1e-8);
    }
  }
}

TEST(TwoBodyOrbit, TimeIsOddInTrueAnomaly) {
  const TwoBodyOrbit orbit(2.0, 2.1, 1.61);
  const double f = orbit.true_anomaly_at_distance(3.0, OrbitBranch::outgoing);
  EXPECT_GT(f, 0.0);
  EXPECT_DOUBLE_EQ(orbit.true_anomaly_at_distance(3.0, OrbitBranch::incoming), -f);
  EXPECT_DOUBLE_EQ(orbit.time_from_pericenter(f), -orbit.time_from_pericenter(-f));
  EXPECT_DOUBLE_EQ(orbit.time_to_pericenter(3.0), orbit.time_from_pericenter(f));
  EXPECT_EQ(orbit.time_to_pericenter(2.1), 0.0);
}

TEST(TwoBodyOrbit, RejectsImpossibleDistancesAndParameters) {
  const TwoBodyOrbit hyperbolic(2.0, 2.0, 1.8);
  EXPECT_THROW(hyperbolic.state_at_distance(1.9, OrbitBranch::incoming), InputError);
  EXPECT_THROW(encounter_start(hyperbolic, std::nan("")), InputError);
  const TwoBodyOrbit elliptic(2.0, 2.0, 1.05);  // apocenter 2.46
  try {
    encounter_start(elliptic, 3.0);
    FAIL() << "no error";
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("apocenter"), std::string::npos) << err.what();
  }
  EXPECT_THROW(TwoBodyOrbit(0.0, 2.0, 1.5), InputError);
  EXPECT_THROW(TwoBodyOrbit(2.0, -1.0, 1.5), InputError);
  EXPECT_THROW(TwoBodyOrbit(2.0, 2.0, 0.0), InputError);
  EXPECT_THROW(perturber_orbit(-0.5, 2.0, 1.5), InputError);
}

// The encounters of the paper (Table 4 and the N run), each set up from r = 3 before pericenter.
// All are hyperbolic (e = 1.7-3.2); the time from r = 3 to pericenter is 1.2-2.0 t_grav, so from
// r = 3 in to r = 3 out takes 2.4-3.9 t_grav: the paper's "run for a total time of T ~ 3".
TEST(TwoBodyOrbit, PaperEncountersFromThreeRadii) {
  struct Case {
    const char* name;
    double m2, q, vq;
  };
  const Case cases[] = {
      {"T5", 0.5, 1.84, 1.60}, {"T1", 0.1, 1.47, 1.62}, {"T10", 1.0, 2.10, 1.61},
      {"T10b", 1.0, 2.22, 1.94}, {"N", 1.0, 2.13, 1.84}};
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const auto orbit = perturber_orbit(c.m2, c.q, c.vq);
    EXPECT_EQ(orbit.type(), OrbitType::hyperbolic);
    EXPECT_NEAR(orbit.eccentricity(), c.q * c.vq * c.vq / (1.0 + c.m2) - 1.0, 1e-14);
    const auto start = encounter_start(orbit, 3.0);
    std::printf("  %-5s M2 = %.2f q = %.2f V_q = %.2f: %s, e = %.4f, t(r=3 -> q) = %.4f t_grav\n", c.name,
                c.m2, c.q, c.vq, orbit_type_name(orbit.type()), orbit.eccentricity(), start.time_to_pericenter);
    EXPECT_GT(2.0 * start.time_to_pericenter, 2.0);
    EXPECT_LT(2.0 * start.time_to_pericenter, 4.0);
    expect_reaches_pericenter(orbit, 3.0);
  }
}
