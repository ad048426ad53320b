#pragma once
// One encounter (paper Table 4): the perturber's mass and its two-body orbit, named. The same type
// is a [[encounters]] table of the configuration, what an encounter checkpoint records
// (stage_records.hpp), and the input of the impulse estimates (physics/encounter_estimates.hpp).
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace tidalcrust {

/// V_q of a parabolic orbit (zero energy) with pericenter q about the body of mass M = 1:
/// sqrt(2 (1 + M2) / q), sqrt(GM/R). The one default speed: an [[encounters]] table, a [sweep]
/// and `encounter --m2 --q` without a speed all fly the perturber on this orbit.
inline double parabolic_speed(double perturber_mass, double pericenter) {
  return std::sqrt(2.0 * (1.0 + perturber_mass) / pericenter);
}

struct Encounter {
  std::string name;                      ///< folder and label of the encounter
  double perturber_mass = 0.5;           ///< M2, M
  double pericenter = 1.84;              ///< q, R (distance of closest approach on the two-body orbit)
  /// V_q, sqrt(GM/R) (relative speed at pericenter); an [[encounters]] table without it gets
  /// parabolic_speed of its own M2 and q (parse_config), this default is that of the defaults.
  double pericenter_speed = parabolic_speed(0.5, 1.84);
  std::optional<double> failure_strain;  ///< eps_S for this encounter (T1 uses 0.002); none: shell.failure_strain
  /// Relaxation interval of the local failure rule for this encounter (L_S/V_SP); none:
  /// encounter.relaxation_crossings.
  std::optional<double> relaxation_crossings;
  /// Seed of the body this encounter branches from (workflow.seed of its own body chain, in the
  /// output folder's body-seed<N>/); none: the workflow's body (body/, workflow.seed). An
  /// [ensemble] that varies the body sets it for its members (docs/ensembles.md).
  std::optional<std::uint64_t> body_seed;
  /// The encounter whose final state this one begins from (an encounter history, issue 25:
  /// failed springs stay failed, the perturber of that pass is replaced by this one's); none:
  /// the relaxed body. Its body is that encounter's (body_seed follows the chain).
  std::optional<std::string> after;
  /// Orientation of the orbit in the body's frame (the frame of the maps, physics/orbital_frame.hpp:
  /// xy the reference plane, +x the reference direction), standard orbital elements in degrees:
  /// inclination i (0: prograde in the xy plane, 180: retrograde), longitude of the ascending node
  /// Omega, argument of pericenter omega. None: i = 0, Omega = 0, omega = 90 deg, the orbit of the
  /// paper's maps (pericenter on +y, angular momentum along +z). orbit_orientation resolves them.
  std::optional<double> inclination;
  std::optional<double> ascending_node;
  std::optional<double> argument_of_pericenter;
  bool operator==(const Encounter&) const = default;
};

/// An encounter of this name, M2, q and V_q, every optional key unset.
inline Encounter encounter_of(std::string name, double perturber_mass, double pericenter, double pericenter_speed) {
  Encounter e;
  e.name = std::move(name);
  e.perturber_mass = perturber_mass;
  e.pericenter = pericenter;
  e.pericenter_speed = pericenter_speed;
  return e;
}

/// The orientation of an encounter's orbit in the body's frame, degrees (Encounter::inclination,
/// ascending_node, argument_of_pericenter with their defaults filled in).
struct OrbitOrientation {
  double inclination = 0;              ///< i, deg
  double ascending_node = 0;           ///< Omega, deg
  double argument_of_pericenter = 90;  ///< omega, deg
  /// True for the paper's orbit (0, 0, 90): begin_encounter then rotates nothing, so encounters
  /// without the keys keep their bits.
  bool is_default() const { return inclination == 0 && ascending_node == 0 && argument_of_pericenter == 90; }
  bool operator==(const OrbitOrientation&) const = default;
};

inline OrbitOrientation orbit_orientation(const Encounter& e) {
  const OrbitOrientation d;
  return {e.inclination.value_or(d.inclination), e.ascending_node.value_or(d.ascending_node),
          e.argument_of_pericenter.value_or(d.argument_of_pericenter)};
}

}  // namespace tidalcrust
