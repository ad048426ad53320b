#pragma once
// The kinds of interior a body can have, one row each: how the interior differs from the
// homogeneous random network of paper section 2.2. The row is chosen once, from the
// configuration (body_type); the assembler (build_body.hpp) asks it for node masses and spring
// stiffnesses and knows no kind by name. A new kind of body is one file defining its row plus
// one line in the table (body_type.cpp). Units: G = M = R = 1.
#include <string_view>

#include "base/vec3.hpp"
#include "model/config.hpp"

namespace tidalcrust {

struct BodyType {
  std::string_view name;     ///< e.g. "homogeneous"; printed by `inspect` and in errors
  std::string_view summary;  ///< one line, for the docs
  /// Whether this row describes the configuration; the table is searched in order and its last
  /// row describes every configuration.
  bool (*describes)(const Config& config);
  /// Relative mass of an interior node at position p (R). The interior keeps its total mass
  /// 1 - M_S; a node's mass is (1 - M_S) w(p) / sum w.
  double (*node_mass_weight)(const Config& config, const Vec3& p);
  /// Factor on the mantle's k_I of the interior spring whose midpoint is m (R); 1 in the mantle.
  double (*spring_stiffness_factor)(const Config& config, const Vec3& m);
  /// Inner radius of the mantle (R): a [material] body meets eq. 15 over the interior springs
  /// with midpoints between it and the interior radius. 0: the whole interior is mantle.
  double (*mantle_inner_radius)(const Config& config);
};

/// The row that describes `config` (never null; the homogeneous body is the last row).
const BodyType& body_type(const Config& config);

}  // namespace tidalcrust
