#pragma once
// The evolving state of a run: exactly what the steps change. What stays fixed is in Body; the
// time step and the stage's damping rate are stage parameters (StageInfo, stage_records.hpp).
#include <array>
#include <cstdint>
#include <vector>

namespace tidalcrust {

/// Per-spring quantities that stages change (relax moves rest lengths, failures cut stiffness).
struct SpringState {
  std::vector<double> rest_length;   ///< [Ns] L_0 in R
  std::vector<double> stiffness;     ///< [Ns] k in G M^2 / R^3
  std::vector<std::uint8_t> failed;  ///< [Ns] 1 once the spring has failed
};

/// Per-hinge quantities that stages change (relax resets rest angles).
struct HingeState {
  std::vector<double> rest_angle;  ///< [Nh] theta_rest in radians
};

/// The point-mass perturber; it pulls on every particle and is pulled back.
struct Perturber {
  bool present = false;
  double mass = 0.0;                        ///< M2 in M
  std::array<double, 3> position{0, 0, 0};  ///< in R
  std::array<double, 3> velocity{0, 0, 0};  ///< in sqrt(GM/R)
};

struct State {
  double time = 0.0;         ///< in t_grav; always step-derived: StepClock::time_at(step)
  std::int64_t step = 0;     ///< global step counter, continues across stages
  std::vector<double> position;  ///< [N*3] in R
  std::vector<double> velocity;  ///< [N*3] in sqrt(GM/R)
  SpringState springs;
  HingeState hinges;
  Perturber perturber;
  /// [N] V0_a in R^3: each liquid particle's volume at zero pressure (0 for the other particles);
  /// the stretch stage sets it so that the layer starts at its hydrostatic pressure. Empty for a
  /// body without a liquid layer (Body::liquid).
  std::vector<double> liquid_rest_volume;
  /// [N*3] in G M^2/R^2: a Maxwell liquid's support (LiquidLayer::maxwell_time > 0): the force its
  /// springs exerted on each particle when the relaxation ended (then their rest lengths became
  /// their lengths), a constant force from then on, so the relaxed body stays in its equilibrium
  /// while the springs' shear relaxes (docs/ocean.md). Empty before that and for any other body.
  std::vector<double> liquid_support;
};

}  // namespace tidalcrust
