#pragma once
// The frame of the fracture maps: the orbital plane is the equator (xy), longitude is measured
// in the xy-plane from +x, latitude from the equator toward +z, and the subsatellite point
// (direction of the perturber at pericenter) lies on +y, longitude +90 deg. Surface points are
// taken relative to the body's centre of mass, because the body moves.
#include "base/vec3.hpp"
#include "model/center_of_mass.hpp"  // the frame's origin: body_center_of_mass

namespace tidalcrust {

/// Direction of the perturber at pericenter, seen from the body's centre of mass.
inline const Vec3 subsatellite_direction{0.0, 1.0, 0.0};

/// Longitude in degrees, (-180, 180], of a point r relative to the centre of mass; +y is +90.
double longitude_deg(const Vec3& r);

/// Latitude in degrees, [-90, 90], of r relative to the centre of mass; +z is +90.
double latitude_deg(const Vec3& r);

/// Angle in degrees, [0, 180], between r and the subsatellite direction.
double angle_from_subsatellite_deg(const Vec3& r);

}  // namespace tidalcrust
