#pragma once
// The evolving state of a run: everything a step reads or writes besides the fixed Body.
// Together with Body and the stage bookkeeping it is the full content of a checkpoint.
#include <array>
#include <cstdint>
#include <vector>

namespace tidalcrust {

/// Per-spring quantities that stages change (relax moves rest lengths, failures cut stiffness).
struct SpringState {
  std::vector<double> rest_length;   ///< [Ns] L_0 in R
  std::vector<double> stiffness;     ///< [Ns] k in G M^2 / R^3
  std::vector<double> damping;       ///< [Ns] gamma, a rate in 1/t_grav (eq. 14, reduced mass)
  std::vector<std::uint8_t> failed;  ///< [Ns] 1 once the spring has failed
};

struct HingeState {
  std::vector<double> rest_angle;  ///< [Nh] theta_rest in radians
  std::vector<double> stiffness;   ///< [Nh] k_e in G M^2 / R^2 (a force)
};

/// The point-mass perturber; it pulls on every particle and is pulled back.
struct Perturber {
  bool present = false;
  double mass = 0.0;                        ///< M2 in M
  std::array<double, 3> position{0, 0, 0};  ///< in R
  std::array<double, 3> velocity{0, 0, 0};  ///< in sqrt(GM/R)
};

struct State {
  double time = 0.0;         ///< in t_grav; always step-derived: start_time + steps * dt
  std::int64_t step = 0;     ///< global step counter, continues across stages
  double dt = 0.0;           ///< time step in t_grav
  std::vector<double> position;  ///< [N*3] in R
  std::vector<double> velocity;  ///< [N*3] in sqrt(GM/R)
  SpringState springs;
  HingeState hinges;
  Perturber perturber;
};

}  // namespace tidalcrust
