#pragma once
// Stage 1 of the pipeline: the body as built from the configuration (paper sections 2.2,
// 2.4, 2.5, 2.7), before stretching. The body itself comes from bodies/build_body.hpp.
#include "model/checkpoint.hpp"
#include "model/config.hpp"

namespace tidalcrust {

/// The "build" checkpoint of build_body(config): state at time 0, step 0, at rest; the clock
/// carries integrator.dt. Records a BuildRecord (model/stage_records.hpp). Throws InputError
/// naming the key for a configuration that cannot give a body (e.g. an interior that touches
/// the shell).
Checkpoint build_stage(const Config& config);

}  // namespace tidalcrust
