#pragma once
// The textbook version of one integration step, the speed baseline of `tidalcrust bench` and
// an independent reference for the tests: one thread, an array of particle structs, gravity
// as a double loop over half the pairs (Newton's third law), spring and hinge forces added
// straight into both particles. Its loops are its own, but the force laws are THE SAME
// evaluators ForceField uses (SpringEvaluator with damping and eq. 26, HingeEvaluator,
// PlummerPairEvaluator for self-gravity and the perturber), with the same drift-kick-drift;
// results agree with ForceField/Leapfrog to rounding, not bit for bit (other summation order,
// and ForceField's gravity is the SIMD kernel).
#include <array>
#include <vector>

#include "model/body.hpp"
#include "forces/force_field.hpp"
#include "model/state.hpp"

namespace tidalcrust {

struct TextbookParticle {
  double x[3], v[3], a[3], m;
};

class TextbookStep {
 public:
  /// Copies positions, velocities and masses of `state` into particle structs.
  TextbookStep(const Body& body, const State& state, ForceOptions options = {});

  /// Accelerations of every particle (into TextbookParticle::a) and of the perturber, at the
  /// current positions and velocities.
  void compute_accelerations(const SpringState& springs, const HingeState& hinges);
  /// x += v dt/2; accelerations; v += a dt; x += v dt/2 (perturber the same way).
  void step(const SpringState& springs, const HingeState& hinges, double dt);

  const std::vector<TextbookParticle>& particles() const { return particles_; }
  const Perturber& perturber() const { return perturber_; }
  const std::array<double, 3>& perturber_acceleration() const { return perturber_acceleration_; }

 private:
  const Body& body_;
  ForceOptions options_;
  std::vector<TextbookParticle> particles_;
  Perturber perturber_;
  std::array<double, 3> perturber_acceleration_{0, 0, 0};
};

}  // namespace tidalcrust
