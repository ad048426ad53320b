#include "io/state_hash.hpp"

#include "io/xxh3_hasher.hpp"

namespace tidalcrust {

std::string state_hash(const State& state) {
  // Byte stream (each array preceded by its int64 element count), in this order:
  // time f64, step i64, position f64[3N], velocity f64[3N], spring rest_length f64[Ns],
  // spring stiffness f64[Ns], spring failed u8[Ns], hinge rest_angle f64[Nh],
  // perturber present u8, then (if present) mass f64, position f64[3], velocity f64[3]; then, only
  // for a body with a liquid layer (so every other state keeps its hash), the liquid rest
  // volumes f64[N].
  Xxh3Hasher h;
  h.f64(state.time);
  h.i64(state.step);
  h.array(state.position);
  h.array(state.velocity);
  h.array(state.springs.rest_length);
  h.array(state.springs.stiffness);
  h.array(state.springs.failed);
  h.array(state.hinges.rest_angle);
  h.u8(state.perturber.present ? 1 : 0);
  if (state.perturber.present) {
    h.f64(state.perturber.mass);
    for (double v : state.perturber.position) h.f64(v);
    for (double v : state.perturber.velocity) h.f64(v);
  }
  if (!state.liquid_rest_volume.empty()) h.array(state.liquid_rest_volume);
  if (!state.liquid_support.empty()) h.array(state.liquid_support);
  return h.hex();
}

}  // namespace tidalcrust
