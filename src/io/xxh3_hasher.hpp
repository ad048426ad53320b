#pragma once
// Streaming XXH3-128 (libxxhash) over canonical little-endian bytes, shared by state_hash and
// the checkpoint content hashes; the digest is printed as 32 lowercase hex digits.
#include <xxhash.h>

#include <bit>
#include <cstdint>
#include <limits>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

namespace tidalcrust {

// The canonical bytes are little endian; on a little-endian machine they are the memory bytes.
static_assert(std::endian::native == std::endian::little,
              "the hashes feed memory bytes as the canonical little-endian form: port before use");
static_assert(sizeof(double) == 8 && std::numeric_limits<double>::is_iec559, "IEEE float64 required");

/// Streams values into XXH3-128 as canonical little-endian bytes.
class Xxh3Hasher {
 public:
  Xxh3Hasher() : state_(XXH3_createState()) {
    if (!state_ || XXH3_128bits_reset(state_) != XXH_OK) throw std::bad_alloc();
  }
  ~Xxh3Hasher() { XXH3_freeState(state_); }
  Xxh3Hasher(const Xxh3Hasher&) = delete;
  Xxh3Hasher& operator=(const Xxh3Hasher&) = delete;

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
  /// Length first, then the characters (same reason).
  void text(std::string_view s) {
    i64(static_cast<std::int64_t>(s.size()));
    bytes(s.data(), s.size());
  }
  /// 32 lowercase hex digits: high 64 bits, then low 64 bits.
  std::string hex() const {
    XXH128_hash_t h = XXH3_128bits_digest(state_);
    return fmt::format("{:016x}{:016x}", h.high64, h.low64);
  }

 private:
  XXH3_state_t* state_;
};

}  // namespace tidalcrust
