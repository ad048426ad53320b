#pragma once
// The Keplerian two-body orbit of the perturber relative to the body, fixed by mu = G (M + M2),
// the pericenter distance q and the speed at pericenter V_q (code units: mu = 1 + M2).
//
// Frame of the fracture maps: the orbital plane is the xy plane (the body's equator), the
// pericenter direction is +y (longitude +pi/2, the subsatellite point at pericenter), and at
// pericenter the perturber moves along -x, so the orbital angular momentum points along +z.
// The perturber comes in from +x (true anomaly f < 0) and leaves toward -x (f > 0).
#include "base/vec3.hpp"

namespace tidalcrust {

enum class OrbitType { elliptic, parabolic, hyperbolic };
enum class OrbitBranch { incoming, outgoing };  ///< before / after pericenter

const char* orbit_type_name(OrbitType type);

/// Relative state: perturber minus body.
struct RelativeState {
  Vec3 position;
  Vec3 velocity;
};

class TwoBodyOrbit {
 public:
  /// |e - 1| below this counts as parabolic (Barker's equation). The elliptic and hyperbolic
  /// time formulas below are written without cancellation, so they agree with Barker to about
  /// this relative accuracy at the switch.
  static constexpr double default_parabolic_tolerance = 1e-9;

  /// InputError unless mu, q and V_q are finite and > 0. `portable`: the transcendental
  /// functions from base/portable_math.hpp (the portable mode: the same bits on every CPU).
  TwoBodyOrbit(double mu, double pericenter, double pericenter_speed,
               double parabolic_tolerance = default_parabolic_tolerance, bool portable = false);

  double mu() const { return mu_; }
  double pericenter() const { return q_; }
  double pericenter_speed() const { return vq_; }
  /// e = q V_q^2 / mu - 1.
  double eccentricity() const { return e_; }
  OrbitType type() const { return type_; }
  /// V_q^2/2 - mu/q, as given (not set to 0 for orbits classed parabolic).
  double specific_energy() const { return 0.5 * vq_ * vq_ - mu_ / q_; }
  /// |r x v| = q V_q.
  double specific_angular_momentum() const { return q_ * vq_; }
  /// q (1 + e) / (1 - e) for elliptic orbits, +infinity otherwise.
  double apocenter() const;
  /// 2 pi sqrt(a^3/mu) for elliptic orbits, +infinity otherwise.
  double period() const;

  /// True anomaly where the distance is r, negative on the incoming branch. InputError if
  /// r < q or r beyond the apocenter of an elliptic orbit.
  double true_anomaly_at_distance(double r, OrbitBranch branch) const;
  RelativeState state_at_true_anomaly(double f) const;
  RelativeState state_at_distance(double r, OrbitBranch branch) const;
  /// Signed time from pericenter at true anomaly f (|f| <= pi; negative before pericenter).
  double time_from_pericenter(double f) const;
  /// Time it takes to go from distance r on the incoming branch to pericenter (>= 0).
  double time_to_pericenter(double r) const;
  /// Analytic state at signed time t from pericenter (Kepler, Barker, or hyperbolic Kepler).
  RelativeState state_at_time(double t) const;

 private:
  /// Signed time from pericenter for half-angle tangent D = tan(f/2).
  double time_from_half_tangent(double D) const;
  /// D = tan(f/2) at signed time t from pericenter.
  double half_tangent_at_time(double t) const;

  double mu_, q_, vq_, e_;
  OrbitType type_;
  bool portable_ = false;
};

/// Where an encounter begins: the relative state at distance r_start on the incoming branch,
/// and the time from there to pericenter.
struct EncounterStart {
  RelativeState relative;
  double time_to_pericenter = 0;
};

/// The orbit of a perturber of mass M2 (units of M) about the body: mu = 1 + M2 (G = M = 1).
TwoBodyOrbit perturber_orbit(double perturber_mass, double pericenter, double pericenter_speed,
                             bool portable = false);

/// Relative state and time to pericenter at r_start before pericenter (InputError if r_start < q
/// or beyond an elliptic orbit's apocenter).
EncounterStart encounter_start(const TwoBodyOrbit& orbit, double r_start);

}  // namespace tidalcrust
