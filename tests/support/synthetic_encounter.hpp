#pragma once
// Small in-memory encounter checkpoints for the analysis tests (synthetic_encounter, spring_between).
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "model/checkpoint.hpp"
#include "bodies/icosphere.hpp"
#include "base/vec3.hpp"

namespace tidalcrust::test_support {

/// Encounter checkpoint: particle 0 is an interior particle (mass 0.93) at the origin, then the
/// shell nodes (total mass 0.07); shell springs along every face edge, a cross spring from the
/// centre to each of the first three shell nodes. No spring failed; perturber on +y at 5 R.
inline Checkpoint synthetic_encounter(int level = 2) {
  const Icosphere sphere = make_icosphere(level);
  const auto& nodes = sphere.nodes;
  Checkpoint c;
  EncounterRecord record;
  record.encounter = encounter_of("T5", 0.5, 1.84, 1.6);
  record.pericenter_time = 1.2;
  record.min_distance = 1.85;
  record.speed_at_min = 1.59;
  c.stage.record = record;
  c.stage.clock = {0.0, 0, 0.002};
  c.stage.end_step = 1000;
  Body& b = c.body;
  b.mass.push_back(0.93);
  b.species.push_back(0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    b.mass.push_back(0.07 / static_cast<double>(nodes.size()));
    b.species.push_back(1);
  }
  for (auto t : sphere.faces) {
    for (auto& i : t) i += 1;  // shell nodes follow the interior particle
    b.faces.push_back(t);
  }
  for (const auto& e : sphere.edges) {
    b.springs.push_back({e[0] + 1, e[1] + 1});
    b.spring_kind.push_back(static_cast<std::uint8_t>(SpringKind::shell));
  }
  for (std::int32_t i = 1; i <= 3; ++i) {
    b.springs.push_back({0, i});
    b.spring_kind.push_back(static_cast<std::uint8_t>(SpringKind::cross));
  }
  State& s = c.state;
  s.step = 1000;
  s.time = 2.0;
  s.position.assign(3 * b.particle_count(), 0.0);
  s.velocity.assign(3 * b.particle_count(), 0.0);
  for (std::size_t i = 0; i < nodes.size(); ++i) set_vec3(s.position, i + 1, nodes[i]);
  const std::size_t ns = b.spring_count();
  s.springs.rest_length.assign(ns, 0.1);
  s.springs.stiffness.assign(ns, 0.06);
  s.springs.failed.assign(ns, 0);
  b.strength_factor.assign(ns, 1.0);  // a uniform crust
  s.perturber.present = true;
  s.perturber.mass = 0.5;
  s.perturber.position = {0, 5, 0};
  return c;
}

/// Spring index of the shell edge (a, b), or -1.
inline std::int32_t spring_between(const Body& body, std::int32_t a, std::int32_t b) {
  for (std::size_t s = 0; s < body.spring_count(); ++s)
    if ((body.springs[s][0] == a && body.springs[s][1] == b) || (body.springs[s][0] == b && body.springs[s][1] == a))
      return static_cast<std::int32_t>(s);
  return -1;
}

}  // namespace tidalcrust::test_support
