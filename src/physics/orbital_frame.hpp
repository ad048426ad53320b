#pragma once
// The frame of the fracture maps: the orbital plane is the equator (xy), longitude is measured
// in the xy-plane from +x, latitude from the equator toward +z, and the subsatellite point
// (direction of the perturber at pericenter) lies on +y, longitude +90 deg. Surface points are
// taken relative to the body's centre of mass, because the body moves.
#include "base/vec3.hpp"
#include "model/center_of_mass.hpp"  // the frame's origin: body_center_of_mass
#include "model/encounter.hpp"

namespace tidalcrust {

/// Direction of the perturber at pericenter, seen from the body's centre of mass, for the paper's
/// orbit (an encounter without orientation keys): subsatellite_direction_of gives it for any orbit.
inline const Vec3 subsatellite_direction{0.0, 1.0, 0.0};
/// Its longitude in the orbital frame, degrees.
inline constexpr double subsatellite_longitude_deg = 90;

/// The rotation that carries the paper's orbit (pericenter on +y, motion at pericenter along -x,
/// angular momentum along +z; physics/two_body_orbit.hpp) onto the orbit of orientation `o` in the
/// body's frame: Rz(Omega) Rx(i) Rz(omega - 90 deg), the standard perifocal-to-reference rotation
/// Rz(Omega) Rx(i) Rz(omega) (e.g. Murray & Dermott 1999, eq. 2.122) after the paper's orbit is
/// turned back to perifocal axes (pericenter on +x). Exactly the identity for the default (0, 0, 90).
Matrix3 orbit_rotation(const OrbitOrientation& o);

/// Direction of the perturber at pericenter for an orbit of orientation `o`: orbit_rotation(o) (+y);
/// exactly subsatellite_direction for the default orientation.
Vec3 subsatellite_direction_of(const OrbitOrientation& o);

/// Longitude in degrees, (-180, 180], of a point r relative to the centre of mass; +y is +90.
double longitude_deg(const Vec3& r);

/// Latitude in degrees, [-90, 90], of r relative to the centre of mass; +z is +90.
double latitude_deg(const Vec3& r);

/// The planetocentric longitude of the maps of a moon (docs/moon.md, "Output in SI"), degrees in
/// (-180, 180]: east-positive (right-handed about +z, the orbit normal, which is north) from the
/// subsatellite point at pericenter, so orbital-frame longitude - subsatellite_longitude_deg.
/// Latitude is the orbital frame's.
double planetocentric_longitude_deg(double orbital_longitude_deg);

/// Angle in degrees, [0, 180], between r and the subsatellite direction `subsatellite` (a unit vector).
double angle_from_subsatellite_deg(const Vec3& r, const Vec3& subsatellite = subsatellite_direction);

}  // namespace tidalcrust
