#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "stages/build_stage.hpp"
#include "physics/crust_relaxation.hpp"
#include "model/derived_quantities.hpp"
#include "base/errors.hpp"
#include "forces/force_field.hpp"
#include "physics/hydrostatic_pressure.hpp"
#include "integrate/leapfrog.hpp"
#include "io/state_hash.hpp"
#include "stages/step_loop.hpp"
#include "stages/stretch_stage.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

/// Mean a . r_hat over the shell nodes, recomputed independently of the stage.
double mean_radial_shell_acceleration(const Checkpoint& c, const Config& config) {
  ForceField forces(c.body, force_options(config, 0.0));
  Accelerations acc;
  forces.compute(c.state, acc);
  Vec3 centre = Vec3::Zero();
  for (std::size_t i = 0; i < c.body.particle_count(); ++i) centre += c.body.mass[i] * vec3_at(c.state.position, i);
  double sum = 0;
  int count = 0;
  for (std::size_t i = 0; i < c.body.particle_count(); ++i) {
    if (c.body.species[i] != static_cast<std::uint8_t>(Species::shell)) continue;
    sum += vec3_at(acc.body, i).dot((vec3_at(c.state.position, i) - centre).normalized());
    ++count;
  }
  return sum / count;
}

/// max - min of the mean shell radius over `duration` at damping gamma (a nearly free body).
double radius_excursion(const Checkpoint& start, const Config& config, double gamma, double duration) {
  State state = start.state;
  const double dt = config.integrator.dt;
  ForceField forces(start.body, force_options(config, gamma));
  Leapfrog leapfrog(forces, StepClock{state.time, state.step, dt});
  double low = mean_shell_radius(start.body, state), high = low;
  for (std::int64_t k = 0; k < steps_for_duration(duration, dt); ++k) {
    leapfrog.step(state);
    const double r = mean_shell_radius(start.body, state);
    low = std::min(low, r);
    high = std::max(high, r);
  }
  return high - low;
}

std::string error_of(const Checkpoint& c, const Config& config) {
  try {
    stretch_stage(c, config);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(StretchStage, ZeroesTheMeanRadialSurfaceAcceleration) {
  const Config config = quick_config();
  const Checkpoint& built = quick_built();
  const Checkpoint& s = quick_stretched();
  // Built at rest, gravity pulls the surface in by about g = 1.
  EXPECT_LT(mean_radial_shell_acceleration(built, config), -0.5);
  EXPECT_LT(std::abs(mean_radial_shell_acceleration(s, config)), config.stretch.tolerance);
  const StretchRecord& sc = s.stage.as<StretchRecord>();
  EXPECT_LT(std::abs(sc.residual_surface_acceleration), config.stretch.tolerance);
  EXPECT_GT(sc.stretch_factor, 1.0);
  EXPECT_LT(sc.stretch_factor, 1.05);
  EXPECT_LE(sc.iterations, config.stretch.max_iterations);
  // The strengthened core must not break the time step bound.
  EXPECT_GT(sc.dt_max, config.integrator.dt);
}

TEST(StretchStage, RestLengthsStiffnessesAndBookkeeping) {
  const Config config = quick_config();
  const Checkpoint& built = quick_built();
  const Checkpoint& s = quick_stretched();
  const double f = s.stage.as<StretchRecord>().stretch_factor;
  const double p_uniform = s.stage.as<StretchRecord>().uniform_pressure;
  ASSERT_GT(p_uniform, 0);
  Vec3 centre = Vec3::Zero();
  for (std::size_t i = 0; i < built.body.particle_count(); ++i) centre += built.body.mass[i] * vec3_at(built.state.position, i);
  double largest = 1, outermost_strengthened = 0;
  for (std::size_t n = 0; n < s.body.spring_count(); ++n) {
    const auto kind = static_cast<SpringKind>(s.body.spring_kind[n]);
    const double L = built.state.springs.rest_length[n], k = built.state.springs.stiffness[n];
    if (kind == SpringKind::cross) {
      EXPECT_DOUBLE_EQ(s.state.springs.rest_length[n], f * L * (1 + config.stretch.cross_compression));
      EXPECT_EQ(s.state.springs.stiffness[n], k);
    } else if (kind == SpringKind::shell) {
      EXPECT_DOUBLE_EQ(s.state.springs.rest_length[n], f * L);
      EXPECT_EQ(s.state.springs.stiffness[n], k);
    } else {
      EXPECT_DOUBLE_EQ(s.state.springs.rest_length[n], f * L);
      const auto i = static_cast<std::size_t>(s.body.springs[n][0]), j = static_cast<std::size_t>(s.body.springs[n][1]);
      const double r = (0.5 * (vec3_at(built.state.position, i) + vec3_at(built.state.position, j)) - centre).norm();
      const double multiplier = std::max(1.0, hydrostatic_pressure(r) / p_uniform);
      EXPECT_NEAR(s.state.springs.stiffness[n], k * multiplier, 1e-12 * k) << "spring " << n << " r " << r;
      largest = std::max(largest, s.state.springs.stiffness[n] / k);
      if (s.state.springs.stiffness[n] > k) outermost_strengthened = std::max(outermost_strengthened, r);
    }
  }
  EXPECT_NEAR(s.stage.as<StretchRecord>().strengthening_max, largest, 1e-9);
  EXPECT_GT(largest, 1.2);  // the core really is strengthened
  EXPECT_LE(outermost_strengthened, s.stage.as<StretchRecord>().strengthening_radius + 1e-3);
  // P_uniform is the virial pressure of the uniformly compressed network, 2 E_I (f - 1).
  const double E_I = derive_quantities(built.body, built.state, config.interior.radius).E_I;
  EXPECT_NEAR(p_uniform, 2 * E_I * (f - 1), 1e-14);
  // With a shell the surface nodes carry no interior springs: strengthening leaves f alone.
  EXPECT_EQ(s.stage.as<StretchRecord>().stretch_factor_unstrengthened, f);
  // Geometry, hinges, bookkeeping.
  EXPECT_EQ(s.state.position, built.state.position);
  EXPECT_EQ(s.state.velocity, built.state.velocity);
  EXPECT_EQ(s.state.hinges.rest_angle, built.state.hinges.rest_angle);
  EXPECT_STREQ(s.stage.name(), "stretch");
  EXPECT_TRUE(s.stage.complete);
  EXPECT_EQ(s.stage.parent_hash, state_hash(built.state));
  EXPECT_EQ(s.stage.clock.start_step, built.state.step);
  EXPECT_EQ(s.stage.end_step, built.state.step);
  EXPECT_EQ(s.config_toml, to_toml(config));
}

TEST(StretchStage, UnstretchedBodyShrinksAndRingsTheStretchedOneDoesNot) {
  Config config = quick_config();
  const double gamma = 0.1, duration = 1.0;
  const double stretched = radius_excursion(quick_stretched(), config, gamma, duration);
  config.stretch.enabled = false;
  const Checkpoint plain = stretch_stage(quick_built(), config);
  EXPECT_EQ(plain.stage.as<StretchRecord>().stretch_factor, 1.0);
  EXPECT_EQ(plain.state.springs.rest_length, quick_built().state.springs.rest_length);
  EXPECT_EQ(plain.state.springs.stiffness, quick_built().state.springs.stiffness);
  const double unstretched = radius_excursion(plain, config, gamma, duration);
  EXPECT_GT(unstretched, 0.01);  // it visibly shrinks (by ~2 %) and bounces
  EXPECT_LT(5 * stretched, unstretched) << "stretched " << stretched << " unstretched " << unstretched;
}

TEST(StretchStage, BodyWithoutShellBalancesItsOuterInteriorNodes) {
  const Config config = interior_only_config();
  const Checkpoint built = build_stage(config);
  const Checkpoint s = stretch_stage(built, config);
  EXPECT_LT(std::abs(s.stage.as<StretchRecord>().residual_surface_acceleration), config.stretch.tolerance);
  EXPECT_GT(s.stage.as<StretchRecord>().stretch_factor, 1.0);
  EXPECT_GT(s.stage.as<StretchRecord>().strengthening_max, 1.0);
  // The strengthened outer interior pushes the surface out: less stretch is needed.
  EXPECT_LT(s.stage.as<StretchRecord>().stretch_factor, s.stage.as<StretchRecord>().stretch_factor_unstrengthened);
}

TEST(StretchStage, RefusesAnythingButACompleteBuildCheckpoint) {
  const Config config = quick_config();
  Checkpoint c = quick_stretched();
  c.stage.record = RelaxRecord{};
  std::string msg = error_of(c, config);
  EXPECT_NE(msg.find("stretch"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'build'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'relax'"), std::string::npos) << msg;
  c = quick_built();
  c.stage.complete = false;
  msg = error_of(c, config);
  EXPECT_NE(msg.find("incomplete"), std::string::npos) << msg;
}

TEST(StretchStage, SpringsTooWeakForSelfGravityAreAnInputError) {
  Config config = quick_config();
  config.shell.spring_constant = 1e-6;
  config.cross.spring_constant = 1e-6;
  const Checkpoint built = build_stage(config);
  const std::string msg = error_of(built, config);
  EXPECT_NE(msg.find("cannot hold the body"), std::string::npos) << msg;
}

TEST(StretchStage, CompressionCarriesTheParticlePressureAtTheBuiltStiffness) {
  Config config = quick_config();
  config.stretch.hydrostatic_support = HydrostaticSupport::compress;
  const Checkpoint& built = quick_built();
  const Checkpoint s = stretch_stage(built, config);
  const StretchRecord& record = s.stage.as<StretchRecord>();
  EXPECT_LT(std::abs(mean_radial_shell_acceleration(s, config)), config.stretch.tolerance);
  EXPECT_EQ(record.strengthening_max, 1.0);
  EXPECT_EQ(record.uniform_pressure, 0.0);
  EXPECT_EQ(s.state.springs.stiffness, built.state.springs.stiffness);  // every stiffness as built
  const double f = record.stretch_factor;
  EXPECT_GT(f, 1.0);
  // Interior spring n: L0 = L_built (1 + P(r_mid) / (2 E_I)) with the particle pressure profile.
  Vec3 centre = Vec3::Zero();
  for (std::size_t i = 0; i < built.body.particle_count(); ++i) centre += built.body.mass[i] * vec3_at(built.state.position, i);
  std::vector<double> radius(built.body.particle_count());
  for (std::size_t i = 0; i < radius.size(); ++i) radius[i] = (vec3_at(built.state.position, i) - centre).norm();
  const ParticleHydrostaticPressure pressure(radius, built.body.mass);
  const double E_I = derive_quantities(built.body, built.state, config.interior.radius).E_I;
  double central_strain = 0;
  for (std::size_t n = 0; n < s.body.spring_count(); ++n) {
    const auto kind = static_cast<SpringKind>(s.body.spring_kind[n]);
    const double L = built.state.springs.rest_length[n];
    if (kind == SpringKind::cross) {
      EXPECT_DOUBLE_EQ(s.state.springs.rest_length[n], f * L * (1 + config.stretch.cross_compression));
    } else if (kind == SpringKind::shell) {
      EXPECT_DOUBLE_EQ(s.state.springs.rest_length[n], f * L);
    } else {
      const auto i = static_cast<std::size_t>(s.body.springs[n][0]), j = static_cast<std::size_t>(s.body.springs[n][1]);
      const double r = (0.5 * (vec3_at(built.state.position, i) + vec3_at(built.state.position, j)) - centre).norm();
      const double factor = 1 + pressure(r) / (2 * E_I);
      EXPECT_NEAR(s.state.springs.rest_length[n], factor * L, 1e-14 * L) << "spring " << n << " r " << r;
      central_strain = std::max(central_strain, factor - 1);
    }
  }
  // The centre carries the weight of the whole body: close to the uniform sphere's 3/(8 pi) e_g.
  EXPECT_NEAR(pressure(0) / hydrostatic_pressure(0), 1.0, 0.35);
  EXPECT_NEAR(central_strain, pressure(0) / (2 * E_I), 0.1 * central_strain);
}

TEST(StretchStage, CompressionOfABodyWithoutShellNeedsNoCommonFactor) {
  Config config = interior_only_config();
  config.stretch.hydrostatic_support = HydrostaticSupport::compress;
  const Checkpoint built = build_stage(config);
  const Checkpoint s = stretch_stage(built, config);
  EXPECT_EQ(s.stage.as<StretchRecord>().stretch_factor, 1.0);
  EXPECT_EQ(s.stage.as<StretchRecord>().iterations, 0);
  EXPECT_EQ(s.state.springs.stiffness, built.state.springs.stiffness);
  // Every interior spring is compressed (rest length longer than built), the outermost least.
  for (std::size_t n = 0; n < s.body.spring_count(); ++n)
    EXPECT_GE(s.state.springs.rest_length[n], built.state.springs.rest_length[n]) << "spring " << n;
}
