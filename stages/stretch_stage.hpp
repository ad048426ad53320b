#pragma once
// Stage 2 (paper section 2.3): stretch all springs by one common factor so that the mean
// radial acceleration of the surface vanishes, then strengthen springs toward the centre so
// that the spring pressure follows the hydrostatic P(r) = (2/3) pi G rho^2 (R^2 - r^2);
// cross springs start slightly compressed.
#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

/// `built` must be a complete "build" checkpoint (InputError otherwise). Returns the
/// "stretch" checkpoint: same body and positions, new rest lengths and stiffnesses, and
/// a StretchRecord of what was found (stretch factor, residual surface acceleration, ...).
Checkpoint stretch_stage(const Checkpoint& built, const Config& config);

}  // namespace tidalcrust
