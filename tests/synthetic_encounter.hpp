#pragma once
// Small in-memory encounter checkpoints for the analysis tests: an icosphere shell (own tiny
// subdivision, independent of the builder) around one heavy interior particle at the centre.
#include <Eigen/Geometry>  // cross()
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "checkpoint.hpp"
#include "recorded_encounter.hpp"
#include "vec3.hpp"

namespace tidalcrust::testing {

/// Icosphere of the given subdivision level and radius 1: vertices, outward CCW faces.
inline std::pair<std::vector<Vec3>, std::vector<std::array<std::int32_t, 3>>> icosphere(int level) {
  const double phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0}, {0, -1, phi}, {0, 1, phi},
                         {0, -1, -phi}, {0, 1, -phi}, {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (auto& p : v) p.normalize();
  std::vector<std::array<std::int32_t, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                                {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                                {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                                {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = static_cast<int>(v.size() - 1);
    };
    std::vector<std::array<std::int32_t, 3>> next;
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({t[1], bc, ab});
      next.push_back({t[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  for (auto& t : f)  // outward counter-clockwise
    if ((v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).dot(v[t[0]]) < 0) std::swap(t[1], t[2]);
  return {v, f};
}

/// Encounter checkpoint: particle 0 is an interior particle (mass 0.93) at the origin, then the
/// shell nodes (total mass 0.07); shell springs along every face edge, a cross spring from the
/// centre to each of the first three shell nodes. No spring failed; perturber on +y at 5 R.
inline Checkpoint synthetic_encounter(int level = 2) {
  const auto [nodes, faces] = icosphere(level);
  Checkpoint c;
  c.stage.stage = "encounter";
  c.stage.start_step = 0;
  c.stage.end_step = 1000;
  c.stage.scalars = {{encounter_keys::perturber_mass, 0.5},  {encounter_keys::pericenter, 1.84},
                     {encounter_keys::pericenter_speed, 1.6}, {encounter_keys::pericenter_time, 1.2},
                     {encounter_keys::perturber_min_distance, 1.85}, {encounter_keys::perturber_speed_at_min, 1.59}};
  c.stage.labels = {{encounter_keys::name_label, "T5"}};
  Body& b = c.body;
  b.mass.push_back(0.93);
  b.species.push_back(0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    b.mass.push_back(0.07 / static_cast<double>(nodes.size()));
    b.species.push_back(1);
  }
  std::map<std::pair<int, int>, bool> seen;
  for (auto t : faces) {
    for (auto& i : t) i += 1;  // shell nodes follow the interior particle
    b.faces.push_back(t);
    for (int k = 0; k < 3; ++k) {
      const auto key = std::minmax(t[k], t[(k + 1) % 3]);
      if (seen[key]) continue;
      seen[key] = true;
      b.springs.push_back({key.first, key.second});
      b.spring_kind.push_back(static_cast<std::uint8_t>(SpringKind::shell));
    }
  }
  for (std::int32_t i = 1; i <= 3; ++i) {
    b.springs.push_back({0, i});
    b.spring_kind.push_back(static_cast<std::uint8_t>(SpringKind::cross));
  }
  State& s = c.state;
  s.dt = 0.002;
  s.step = 1000;
  s.time = 2.0;
  s.position.assign(3 * b.particle_count(), 0.0);
  s.velocity.assign(3 * b.particle_count(), 0.0);
  for (std::size_t i = 0; i < nodes.size(); ++i) set_vec3(s.position, i + 1, nodes[i]);
  const std::size_t ns = b.spring_count();
  s.springs.rest_length.assign(ns, 0.1);
  s.springs.stiffness.assign(ns, 0.06);
  s.springs.damping.assign(ns, 0.01);
  s.springs.failed.assign(ns, 0);
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

}  // namespace tidalcrust::testing
