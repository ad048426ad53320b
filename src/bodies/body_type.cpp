#include "bodies/body_type.hpp"

#include <array>

#include "base/invariant.hpp"

namespace tidalcrust {

// One row per file (bodies/<name>_body.cpp), most specific first.
extern const BodyType layered_body;
extern const BodyType homogeneous_body;

const BodyType& body_type(const Config& config) {
  static const std::array<const BodyType*, 2> table{&layered_body, &homogeneous_body};
  for (const BodyType* row : table)
    if (row->describes(config)) return *row;
  TIDALCRUST_ASSERT(false, "the body-type table ends with a row that describes every configuration");
  return homogeneous_body;
}

}  // namespace tidalcrust
