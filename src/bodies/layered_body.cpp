// A body with a core (issue 12, [core]): nodes fill core and mantle equally densely, so a core
// node is core.density_ratio times heavier, and an interior spring whose midpoint lies in the
// core is core.modulus_ratio times stiffer (docs/material.md).
#include "bodies/body_type.hpp"

namespace tidalcrust {
namespace {

bool inside_core(const Config& config, const Vec3& p) { return p.norm() < *config.core.radius; }

}  // namespace

extern const BodyType layered_body;
const BodyType layered_body{
    .name = "layered",
    .summary = "a denser, stiffer core inside the mantle ([core])",
    .describes = [](const Config& config) { return config.core.present(); },
    .node_mass_weight = [](const Config& config,
                           const Vec3& p) { return inside_core(config, p) ? config.core.density_ratio.value_or(1.0) : 1.0; },
    .spring_stiffness_factor = [](const Config& config,
                                  const Vec3& m) { return inside_core(config, m) ? config.core.modulus_ratio.value_or(1.0) : 1.0; },
    .mantle_inner_radius = [](const Config& config) { return *config.core.radius; },
};

}  // namespace tidalcrust
