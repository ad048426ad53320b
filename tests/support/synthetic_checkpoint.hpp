#pragma once
// A small hand-made checkpoint that sets every field of the file layout (synthetic_checkpoint).
#include <cmath>

#include "model/checkpoint.hpp"

namespace tidalcrust::test_support {

/// A tetrahedron of shell nodes around one interior node, springs of all three kinds (one
/// failed), hinges, faces, a perturber, failure events, timeseries rows and an encounter record
/// with every kind of field (numbers, counts, a text, a list).
inline Checkpoint synthetic_checkpoint() {
  Checkpoint c;
  EncounterRecord record;
  record.encounter = encounter_of("T5 synthetic \"test\" & <body>", 0.5, 1.84, 1.6);
  record.encounter.failure_strain = 0.002;
  record.failure_strain = 0.002;
  record.failed_stiffness_factor = 0.005;
  record.damping = 0.01;
  record.failure_rule = PaperFailureRule{3};
  record.sample_interval = 10;
  record.start_distance = 3.0;
  record.end_distance = 3.0;
  record.pericenter_time = 3.1;
  record.pericenter_step = 1550;
  record.snapshot_steps = {1050, 1550, 2050};
  record.min_distance = 1.84;
  record.speed_at_min = 1.6;
  record.time_of_min = 2.2;
  record.step_of_min = 1100;
  c.stage.record = record;
  c.stage.complete = false;
  c.stage.clock = {2.0, 1000, 0.002};
  c.stage.end_step = 2500;
  c.stage.parent_hash = "0123456789abcdef0123456789abcdef";
  c.stage.fingerprint = "encounter.damping = 0.01\nintegrator.dt = 0.002\n";
  c.config_toml = "[workflow]\nname = \"synthetic\"\nseed = 7\n\n[interior]\nradius = 0.5\n"
                  "min_separation = 0.1\nspring_distance = 0.3\n";

  Body& b = c.body;
  // Node 0: interior at the centre; nodes 1-4: shell tetrahedron.
  b.mass = {0.5, 0.125, 0.125, 0.125, 0.125};
  b.species = {0, 1, 1, 1, 1};
  b.springs = {{0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 2}, {2, 3}, {3, 1}, {1, 4}, {2, 4}, {3, 4}};
  b.spring_kind = {2, 2, 2, 2, 1, 1, 1, 1, 1, 1};
  b.strength_factor.assign(b.springs.size(), 1.0);  // a uniform crust
  b.hinges = {{3, 4, 1, 2}, {1, 4, 2, 3}, {2, 4, 3, 1}};
  b.faces = {{1, 2, 3}, {1, 4, 2}, {2, 4, 3}, {3, 4, 1}};
  b.softening = 1e-3;

  State& s = c.state;
  s.time = 2.25;
  s.step = 1125;
  const double r = 1.0 / std::sqrt(3.0);
  s.position = {0.0, 0.0, 0.0, r, r, r, r, -r, -r, -r, r, -r, -r, -r, r};
  for (std::size_t i = 0; i < s.position.size(); ++i) s.velocity.push_back(0.01 * std::sin(1.0 + i));
  for (std::size_t k = 0; k < b.springs.size(); ++k) {
    s.springs.rest_length.push_back(0.9 + 0.01 * k);
    s.springs.stiffness.push_back(k < 4 ? 0.005 : 0.06);
    s.springs.failed.push_back(k == 5 ? 1 : 0);
  }
  s.hinges.rest_angle = {0.1, -0.2, 0.3};
  b.hinge_stiffness = {0.0075, 0.0075, 0.0075};
  s.perturber = {true, 0.5, {3.0, -1.0, 0.0}, {-1.2, 0.4, 0.0}};

  c.observables.failures = {{2.1, 1050, 5, 0.0031, {0.0, 0.1, -0.9}}};
  c.observables.timeseries = {{2.0, 0, 0.01, {1e-17, 0, 0}, {0, 0, 0.2}, {3.25, -1.5, 1e-16}},
                              {2.2, 1, 0.011, {0, -1e-17, 0}, {0, 1e-9, 0.2}, {2.9, -0.7, -3e-17}}};
  c.observables.failures[0].released_energy = 2.7e-8;
  // The energy budget's columns: the second row as an encounter fills them, the first left
  // unmeasured (NaN), as the relax stage leaves them.
  TimeseriesSample& measured = c.observables.timeseries[1];
  measured.internal_kinetic_energy = 1.5e-4;
  measured.spring_energy = 3.1e-3;
  measured.hinge_energy = 2.2e-6;
  measured.self_gravity_energy = -0.61;
  measured.perturber_energy = -0.17;
  measured.damping_dissipated = 4e-7;
  measured.failure_released = 2.7e-8;
  measured.hinge_residual_work = -1e-11;
  return c;
}

}  // namespace tidalcrust::test_support
