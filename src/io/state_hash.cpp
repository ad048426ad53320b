#include "io/state_hash.hpp"

#include <xxhash.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <new>
#include <fmt/format.h>
#include <vector>

namespace tidalcrust {

namespace {

// The canonical bytes are little endian; on a little-endian machine they are the memory bytes.
static_assert(std::endian::native == std::endian::little,
              "state_hash feeds memory bytes as the canonical little-endian form: port before use");
static_assert(sizeof(double) == 8 && std::numeric_limits<double>::is_iec559, "IEEE float64 required");

/// Streams values into XXH3-128 as canonical little-endian bytes.
class Hasher {
 public:
  Hasher() : state_(XXH3_createState()) {
    if (!state_ || XXH3_128bits_reset(state_) != XXH_OK) throw std::bad_alloc();
  }
  ~Hasher() { XXH3_freeState(state_); }
  Hasher(const Hasher&) = delete;
  Hasher& operator=(const Hasher&) = delete;

  void bytes(const void* data, std::size_t size) {
    if (size > 0) XXH3_128bits_update(state_, data, size);
  }
  void u8(std::uint8_t v) { bytes(&v, 1); }
  void i64(std::int64_t v) { bytes(&v, sizeof v); }
  void f64(double v) { bytes(&v, sizeof v); }
  /// The element count first, so that arrays of different lengths never share a byte stream.
  template <typename T>
  void array(const std::vector<T>& values) {
    i64(static_cast<std::int64_t>(values.size()));
    bytes(values.data(), values.size() * sizeof(T));
  }
  std::string hex() const {
    XXH128_hash_t h = XXH3_128bits_digest(state_);
    return fmt::format("{:016x}{:016x}", h.high64, h.low64);
  }

 private:
  XXH3_state_t* state_;
};

}  // namespace

std::string state_hash(const State& state) {
  // Byte stream (each array preceded by its int64 element count), in this order:
  // time f64, step i64, position f64[3N], velocity f64[3N], spring rest_length f64[Ns],
  // spring stiffness f64[Ns], spring failed u8[Ns], hinge rest_angle f64[Nh],
  // perturber present u8, then (if present) mass f64, position f64[3], velocity f64[3].
  Hasher h;
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
  return h.hex();
}

}  // namespace tidalcrust
