#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <cstring>

#include "base/errors.hpp"
#include "base/invariant.hpp"
#include "forces/force_field.hpp"
#include "support/force_test_bodies.hpp"
#include "integrate/textbook_step.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST(ForceField, ZeroForceAtRestWithoutGravity) {
  // The built body has L = L0 on every spring and every hinge at its rest angle.
  const Checkpoint c = small_body();
  ForceOptions options;
  options.self_gravity = false;
  ForceField field(c.body, options);
  Accelerations a;
  const ForceAlarms alarms = field.compute(c.state, a);
  EXPECT_FALSE(alarms.any());
  ASSERT_EQ(a.body.size(), c.state.position.size());
  EXPECT_LT(max_abs(a.body), 1e-12);
  // For scale: the same body shaken a little feels forces of order k dx / m.
  State shaken = c.state;
  shake(shaken, 1e-3, 0.0, 1);
  field.compute(shaken, a);
  EXPECT_GT(max_abs(a.body), 1e-3);
}

TEST(ForceField, AgreesWithTheTextbookStep) {
  const Checkpoint c = every_law_body(2);
  const ForceOptions options = every_law_options();
  ForceField field(c.body, options);
  Accelerations a;
  EXPECT_FALSE(field.compute(c.state, a).any());
  TextbookStep textbook(c.body, c.state, options);
  textbook.compute_accelerations(c.state.springs, c.state.hinges);
  const double scale = max_abs(a.body);
  for (std::size_t i = 0; i < c.body.particle_count(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(a.body[3 * i + k], textbook.particles()[i].a[k], 1e-12 * scale) << "particle " << i;
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(a.perturber[k], textbook.perturber_acceleration()[k], 1e-13 * std::abs(a.perturber[k]));
}

TEST(ForceField, NonlinearCrossLawSoftensStretchedCrossSpringsOnly) {
  const Checkpoint c = small_body();
  ForceOptions linear, nonlinear;
  linear.self_gravity = nonlinear.self_gravity = false;
  nonlinear.cross_nonlinear = true;
  nonlinear.cross_strain_scale = 0.03;
  nonlinear.cross_min_force_factor = 0.1;
  State stretched = c.state;
  for (double& x : stretched.position) x *= 1.01;  // every spring at strain 0.01
  ForceField a(c.body, linear), b(c.body, nonlinear);
  a.compute_spring_forces(stretched.position.data(), stretched.velocity.data(), stretched.springs);
  b.compute_spring_forces(stretched.position.data(), stretched.velocity.data(), stretched.springs);
  std::size_t cross = 0;
  for (std::size_t s = 0; s < c.body.spring_count(); ++s) {
    const bool is_cross = c.body.spring_kind[s] == static_cast<std::uint8_t>(SpringKind::cross);
    cross += is_cross;
    const double expected = is_cross ? 1.0 - 0.01 / 0.03 : 1.0;
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(b.spring_forces()[3 * s + k], expected * a.spring_forces()[3 * s + k],
                  1e-12 * std::abs(a.spring_forces()[3 * s + k]) + 1e-18);
  }
  EXPECT_GT(cross, 100u);
}

TEST(ForceField, BitwiseIndependentOfTheThreadCount) {
  // Both gravity methods: the tree's pass runs its moment tasks among the spring and hinge
  // chunks and gathers each chunk of groups where it is walked.
  Checkpoint c = quick_body();
  shake(c.state, 5e-3, 0.05, 3);
  c.state.perturber = {true, 1.0, {0.0, 2.5, 0.0}, {1.0, 0.0, 0.0}};
  const int threads = omp_get_max_threads();
  for (const GravityMethod method : {GravityMethod::direct, GravityMethod::tree}) {
    ForceOptions options = damped(1.0);
    options.min_parallel_items = 1;  // every loop threaded
    options.gravity_method = method;
    ForceField field(c.body, options);
    Accelerations one, other;
    omp_set_num_threads(1);
    field.compute(c.state, one);
    for (int t : {2, 3, 5}) {
      omp_set_num_threads(t);
      field.compute(c.state, other);
      EXPECT_EQ(std::memcmp(one.body.data(), other.body.data(), one.body.size() * sizeof(double)), 0)
          << choice_name(method) << " " << t;
      EXPECT_EQ(std::memcmp(one.perturber.data(), other.perturber.data(), 3 * sizeof(double)), 0) << t;
    }
  }
  omp_set_num_threads(threads);
}

TEST(ForceField, ChangedRestAnglesAreUsedOnTheNextPass) {
  // The half-angle table is cached per rest angle; a relax-style reset must take effect.
  const Checkpoint c = small_body();
  ForceOptions options;
  options.self_gravity = false;
  ForceField field(c.body, options);
  Accelerations a;
  field.compute(c.state, a);
  EXPECT_LT(max_abs(a.body), 1e-12);
  State bent = c.state;
  bent.hinges.rest_angle[5] += 0.1;
  field.compute(bent, a);
  EXPECT_GT(max_abs(a.body), 1e-4);
  field.compute(c.state, a);
  EXPECT_LT(max_abs(a.body), 1e-12);
}

TEST(ForceField, ReportsCollapsedHingesAndNonFiniteAccelerations) {
  Checkpoint c = small_body();
  ForceField field(c.body);
  Accelerations a;
  State bad = c.state;
  const auto& h = c.body.hinges[7];
  // Put wing 1 of hinge 7 on the midpoint of its edge.
  for (int k = 0; k < 3; ++k)
    bad.position[3 * h[0] + k] = 0.5 * (bad.position[3 * h[2] + k] + bad.position[3 * h[3] + k]);
  ForceAlarms alarms = field.compute(bad, a);
  EXPECT_GE(alarms.collapsed_hinge, 0);
  EXPECT_LE(alarms.collapsed_hinge, 7);
  const std::string message = field.describe(alarms, bad.position.data());
  EXPECT_NE(message.find("hinge"), std::string::npos) << message;
  EXPECT_NE(message.find("collapsed"), std::string::npos) << message;

  bad = c.state;
  bad.position[3 * 10] = std::nan("");
  alarms = field.compute(bad, a);
  EXPECT_GE(alarms.nonfinite_particle, 0);
  EXPECT_LE(alarms.nonfinite_particle, 10);
}

TEST(ForceField, RejectsAStateThatDoesNotMatchTheBody) {
  Checkpoint c = small_body();
  ForceField field(c.body);
  Accelerations a;
  c.state.springs.rest_length.pop_back();
  EXPECT_THROW(field.compute(c.state, a), InternalError);  // the checkpoint reader checks shapes first
}
