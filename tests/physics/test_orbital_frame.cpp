#include <gtest/gtest.h>
#include <Eigen/LU>  // determinant()

#include <cmath>

#include "physics/orbital_frame.hpp"

using namespace tidalcrust;

TEST(OrbitalFrame, SubsatellitePointIsAtLongitude90) {
  EXPECT_DOUBLE_EQ(longitude_deg({0, 1, 0}), 90.0);
  EXPECT_DOUBLE_EQ(longitude_deg({1, 0, 0}), 0.0);
  EXPECT_DOUBLE_EQ(longitude_deg({-1, 0, 0}), 180.0);
  EXPECT_DOUBLE_EQ(longitude_deg({0, -1, 0}), -90.0);
  EXPECT_DOUBLE_EQ(latitude_deg({0, 0, 2}), 90.0);
  EXPECT_DOUBLE_EQ(latitude_deg({3, 0, 0}), 0.0);
  EXPECT_DOUBLE_EQ(angle_from_subsatellite_deg({0, 4, 0}), 0.0);
  EXPECT_DOUBLE_EQ(angle_from_subsatellite_deg({0, 0, 1}), 90.0);
  EXPECT_DOUBLE_EQ(angle_from_subsatellite_deg({0, -1, 0}), 180.0);
}

// The paper's orbit is exactly the identity (encounters without orientation keys keep their bits);
// any other is a proper rotation that puts the pericenter where the spherical-astronomy formulas
// do: sin(lat) = sin i sin omega, lon = Omega + atan2(cos i sin omega, cos omega) (Murray & Dermott
// 1999, eqs. 2.122), and the orbit's angular momentum along (sin i sin Omega, -sin i cos Omega, cos i).
TEST(OrbitalFrame, OrbitOrientationRotatesThePapersOrbitOntoItsElements) {
  const Matrix3 identity = orbit_rotation(OrbitOrientation{});
  EXPECT_TRUE(identity == Matrix3::Identity());
  EXPECT_TRUE(subsatellite_direction_of(OrbitOrientation{}) == subsatellite_direction);

  constexpr double deg = 3.14159265358979323846 / 180;
  for (const OrbitOrientation o : {OrbitOrientation{60, 30, 200}, OrbitOrientation{180, 0, 90},
                                   OrbitOrientation{90, -45, 0}, OrbitOrientation{0, 0, 0}}) {
    const Matrix3 r = orbit_rotation(o);
    EXPECT_NEAR((r.transpose() * r - Matrix3::Identity()).norm(), 0, 1e-15);
    EXPECT_NEAR(r.determinant(), 1, 1e-15);
    const Vec3 s = subsatellite_direction_of(o);
    const double i = o.inclination * deg, node = o.ascending_node * deg, w = o.argument_of_pericenter * deg;
    EXPECT_NEAR(latitude_deg(s), std::asin(std::sin(i) * std::sin(w)) / deg, 1e-12);
    if (std::abs(std::cos(i) * std::sin(w)) + std::abs(std::cos(w)) > 1e-9) {
      const double lon = std::remainder(node + std::atan2(std::cos(i) * std::sin(w), std::cos(w)), 2 * 3.14159265358979323846);
      EXPECT_NEAR(std::remainder(longitude_deg(s) * deg - lon, 2 * 3.14159265358979323846), 0, 1e-12);
    }
    const Vec3 normal = r * Vec3::UnitZ();  // the paper's orbit turns about +z
    EXPECT_NEAR((normal - Vec3(std::sin(i) * std::sin(node), -std::sin(i) * std::cos(node), std::cos(i))).norm(), 0, 1e-15);
  }
  // i = 0, omega = 0: the pericenter on +x. Retrograde (i = 180) with omega = 90 puts it on -y;
  // omega = -90 on +y, the paper's pericenter run the other way round (angular momentum along -z).
  EXPECT_NEAR((subsatellite_direction_of({0, 0, 0}) - Vec3::UnitX()).norm(), 0, 1e-16);
  EXPECT_NEAR((subsatellite_direction_of({180, 0, 90}) - Vec3(0, -1, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((subsatellite_direction_of({180, 0, -90}) - Vec3(0, 1, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((orbit_rotation({180, 0, -90}) * Vec3::UnitZ() + Vec3::UnitZ()).norm(), 0, 1e-15);
  EXPECT_NEAR(angle_from_subsatellite_deg({1, 0, 0}, Vec3::UnitX()), 0, 1e-12);
}
