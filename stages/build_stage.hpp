#pragma once
// Stage 1 of the pipeline: the body as built from the configuration (paper sections 2.2,
// 2.4, 2.5, 2.7), before stretching. Particles: interior nodes, then shell nodes.
#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

/// Builds the random interior, the icosahedral shell with one hinge per edge and the cross
/// springs. Springs are ordered interior, shell (one per icosphere edge), cross; rest lengths
/// are the built lengths. State at time 0, step 0, at rest; the clock carries integrator.dt.
/// Records a BuildRecord (model/stage_records.hpp). Throws InputError naming the key
/// for a configuration that cannot give a body (e.g. an interior that touches the shell).
Checkpoint build_stage(const Config& config);

}  // namespace tidalcrust
