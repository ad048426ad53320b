// The paper's interior (section 2.2): one material throughout, every node of the same mass and
// every interior spring of the same k_I.
#include "bodies/body_type.hpp"

namespace tidalcrust {

extern const BodyType homogeneous_body;
const BodyType homogeneous_body{
    .name = "homogeneous",
    .summary = "one material throughout the interior (paper section 2.2)",
    .describes = [](const Config&) { return true; },
    .node_mass_weight = [](const Config&, const Vec3&) { return 1.0; },
    .spring_stiffness_factor = [](const Config&, const Vec3&) { return 1.0; },
    .mantle_inner_radius = [](const Config&) { return 0.0; },
};

}  // namespace tidalcrust
