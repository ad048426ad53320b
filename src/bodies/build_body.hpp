#pragma once
// The body a configuration describes, as built (paper sections 2.2, 2.4, 2.5, 2.7), before
// stretching: the random interior of its body type (body_type.hpp), the icosahedral shell with
// one hinge per edge, and the springs that tie them (cross springs within d_C, or the welded
// coupling of cross.coupling = "welded"). Particles: interior nodes, then shell nodes.
#include <cstdint>

#include "model/body.hpp"
#include "model/config.hpp"
#include "model/state.hpp"

namespace tidalcrust {

struct BuiltBody {
  Body body;
  /// Time 0, step 0, at rest; rest lengths the built lengths, stiffnesses as built.
  State state;
  std::int64_t interior_trials = 0;  ///< trial points of the random sequential addition
  double min_spacing = 0;            ///< smallest distance between two particles, R
};

/// Springs are ordered interior, shell (one per icosphere edge), cross; hinges one per shell
/// edge. Node masses and interior stiffnesses follow the body type's row; the constants are
/// the printed ones or, for a [material] body, those its network needs (material_body.hpp).
/// Plummer softening = integrator.softening_fraction times the smallest particle spacing.
/// Throws InputError naming the key for a configuration that cannot give a body (an interior
/// that touches the shell, a shell no spring reaches).
BuiltBody build_body(const Config& config);

}  // namespace tidalcrust
