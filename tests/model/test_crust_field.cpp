// A crust that varies (model/crust_field.hpp, docs/crust.md): the harmonics' values at known
// points, the weak lines' half-width, the map file's grid and interpolation, and every malformed
// input as one line naming the key (or the file and its line).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/errors.hpp"
#include "model/config.hpp"
#include "model/crust_field.hpp"
#include "support/files.hpp"

using namespace tidalcrust;
using namespace tidalcrust::test_support;

namespace {

/// The InputError message of `f()`, "(accepted)" if it throws none.
template <typename F>
std::string error_of(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

const Vec3 north{0, 0, 1}, south{0, 0, -1}, plus_x{1, 0, 0}, plus_y{0, 1, 0};

}  // namespace

TEST(CrustField, ADegreeOneDichotomyGivesOnePlusAndOneMinusItsCoefficientAtItsPoles) {
  CrustField field;
  field.thickness_harmonics = parse_harmonics("c10 = 0.5", "t");
  EXPECT_DOUBLE_EQ(field.thickness_factor(north), 1.5);
  EXPECT_DOUBLE_EQ(field.thickness_factor(south), 0.5);
  EXPECT_DOUBLE_EQ(field.thickness_factor(plus_x), 1.0);
  EXPECT_NEAR(field.thickness_factor(2.0 * direction_at(30, 60)), 1 + 0.5 * std::sin(M_PI / 3), 1e-15);  // any length
  // s11 is y (toward the subsatellite point of the paper's orbit), c11 is x.
  field.strength_harmonics = parse_harmonics("s11 = -0.4, c11=0.2", "f");
  EXPECT_DOUBLE_EQ(field.strength_factor(plus_y), 0.6);
  EXPECT_DOUBLE_EQ(field.strength_factor(-plus_y), 1.4);
  EXPECT_DOUBLE_EQ(field.strength_factor(plus_x), 1.2);
  EXPECT_DOUBLE_EQ(field.strength_factor(north), 1.0);
  EXPECT_FALSE(field.uniform());
  EXPECT_TRUE(CrustField{}.uniform());
  EXPECT_EQ(CrustField{}.thickness_factor(north), 1.0);  // exactly: a uniform crust is built as before
}

TEST(CrustField, HarmonicsAreSchmidtSemiNormalised) {
  const Vec3 u = direction_at(40, 25);
  const double z = u.z(), s2 = 1 - z * z, phi = 40 * M_PI / 180;
  EXPECT_NEAR(harmonic_sum(parse_harmonics("c20 = 1", "h"), u), 0.5 * (3 * z * z - 1), 1e-15);
  EXPECT_NEAR(harmonic_sum(parse_harmonics("c22 = 1", "h"), u), std::sqrt(3.0) / 2 * s2 * std::cos(2 * phi), 1e-15);
  EXPECT_NEAR(harmonic_sum(parse_harmonics("s21 = 1", "h"), u), std::sqrt(3.0) * z * std::sqrt(s2) * std::sin(phi), 1e-15);
  EXPECT_NEAR(harmonic_sum(parse_harmonics("c30 = 1", "h"), u), 0.5 * z * (5 * z * z - 3), 1e-15);
  // At the poles every m > 0 term vanishes.
  EXPECT_EQ(harmonic_sum(parse_harmonics("c11 = 1, s22 = 1", "h"), north), 0.0);
}

TEST(CrustField, AWeakLineHasItsFactorWithinItsHalfWidthAndOneOutside) {
  CrustField field;
  // A great circle through both poles and lon +-90 (pole on +x), 5 degrees half-width.
  field.weak_lines = parse_weak_lines("pole_lon = 0, pole_lat = 0, half_width = 5, factor = 0.3", "w");
  EXPECT_EQ(field.weak_lines.at(0).radius_deg, 90);
  EXPECT_DOUBLE_EQ(field.strength_factor(plus_y), 0.3);
  EXPECT_DOUBLE_EQ(field.strength_factor(north), 0.3);
  EXPECT_DOUBLE_EQ(field.strength_factor(direction_at(94.9, 10)), 0.3);
  EXPECT_DOUBLE_EQ(field.strength_factor(direction_at(95.1, 0)), 1.0);
  EXPECT_DOUBLE_EQ(field.strength_factor(plus_x), 1.0);
  // A small circle of radius 30 deg about the north pole; two lines: the weaker one where they cross.
  field.weak_lines = parse_weak_lines(
      "pole_lon=0, pole_lat=90, radius=30, half_width=2, factor=0.5; pole_lon=0, pole_lat=0, half_width=5, factor=0.3",
      "w");
  ASSERT_EQ(field.weak_lines.size(), 2u);
  EXPECT_DOUBLE_EQ(field.strength_factor(direction_at(45, 61)), 0.5);
  EXPECT_DOUBLE_EQ(field.strength_factor(direction_at(45, 57)), 1.0);
  EXPECT_DOUBLE_EQ(field.strength_factor(direction_at(90, 60)), 0.3);
}

TEST(CrustField, MalformedTermsAreOneLineErrorsNamingTheKey) {
  const std::string where = "w.toml: crust.thickness_harmonics";
  for (const char* bad : {"c10 0.5", "c10 = abc", "x10 = 0.5", "c1 = 0.5", "c00 = 1", "c12 = 0.1", "s10 = 0.2",
                          "c10 = 0.5, c10 = 0.1", "c10 = inf", "c10 = 1e999", "= 0.5"}) {
    const std::string message = error_of([&] { parse_harmonics(bad, where); });
    EXPECT_EQ(message.rfind(where + ": ", 0), 0u) << bad << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_EQ(error_of([] { parse_harmonics("c10 = abc", "k"); }),
            "k: 'c10 = abc': the value is not a finite number (expected terms like \"c10 = 0.5, s11 = -0.1\")");
  EXPECT_TRUE(parse_harmonics("  ", "k").empty());
  for (const char* bad : {"pole_lon = 0, pole_lat = 0, half_width = 5, factor = 0", "pole_lon = 0, pole_lat = 0, half_width = 5, factor = 1.5",
                          "pole_lon = 0, pole_lat = 0, half_width = 5", "pole_lon = 0, pole_lat = 95, half_width = 5, factor = 0.5",
                          "pole_lon = 0, pole_lat = 0, half_width = 0, factor = 0.5", "pole_lon = 0, pole_lat = 0, width = 5, factor = 0.5",
                          "pole_lon = 0, pole_lat = 0, half_width = 5, factor = -0.5"}) {
    const std::string message = error_of([&] { parse_weak_lines(bad, "w.toml: crust.weak_lines"); });
    EXPECT_EQ(message.rfind("w.toml: crust.weak_lines: weak line 1: ", 0), 0u) << bad << ": " << message;
  }
}

TEST(CrustField, ConfigurationRefusesABadCrustNamingTheFileAndKey) {
  const std::string base = "[workflow]\nname = \"c\"\n[crust]\n";
  EXPECT_EQ(error_of([&] { parse_config(base + "strength_harmonics = \"c10 = 0.5x\"\n", "c.toml"); }),
            "c.toml: crust.strength_harmonics: 'c10 = 0.5x': the value is not a finite number (expected terms like "
            "\"c10 = 0.5, s11 = -0.1\")");
  EXPECT_NE(error_of([&] { parse_config(base + "weak_lines = \"pole_lon = 0, pole_lat = 0, half_width = 5, factor = 0\"\n",
                                        "c.toml"); })
                .find("c.toml: crust.weak_lines: weak line 1: factor = 0 must be in (0, 1)"),
            std::string::npos);
  EXPECT_EQ(error_of([&] { parse_config(base + "map_file = \"/nonexistent/map.csv\"\n", "c.toml"); }).rfind(
                "/nonexistent/map.csv: cannot open crust.map_file", 0),
            0u);
  // A uniform crust leaves the configuration and its text as before the table.
  const Config plain = parse_config("[workflow]\nname = \"c\"\n", "c.toml");
  EXPECT_FALSE(plain.crust.given());
  EXPECT_EQ(to_toml(plain).find("harmonics ="), std::string::npos);  // [crust] without a key
  Config dichotomy = parse_config(base + "thickness_harmonics = \"s11 = 0.5\"\n", "c.toml");
  EXPECT_EQ(*dichotomy.crust.thickness_harmonics, "s11 = 0.5");
  EXPECT_EQ(parse_config(to_toml(dichotomy), "again").crust.thickness_harmonics, dichotomy.crust.thickness_harmonics);
  apply_override(dichotomy, "crust.strength_harmonics='s11 = -0.3'");
  EXPECT_EQ(*dichotomy.crust.strength_harmonics, "s11 = -0.3");
}

TEST(CrustField, AMapFileIsARegularGridInterpolatedBilinearlyAndPeriodicInLongitude) {
  const ScratchFolder scratch("crust_map");
  std::string csv = "# a test map\nlon,lat,thickness_factor,strength_factor\n";
  for (int lat = -90; lat <= 90; lat += 90)
    for (int lon = 0; lon < 360; lon += 90)
      csv += std::to_string(lon) + "," + std::to_string(lat) + "," + std::to_string(1 + lon / 90) + ",0.5\n";
  write_file(scratch.path / "map.csv", csv);
  const CrustMap map = read_crust_map(scratch.path / "map.csv");
  EXPECT_EQ(map.lon_deg.size(), 4u);
  EXPECT_EQ(map.lat_deg.size(), 3u);
  EXPECT_NEAR(map.thickness_at(direction_at(45, 0)), 1.5, 1e-12);
  EXPECT_NEAR(map.thickness_at(direction_at(-45, 0)), 2.5, 1e-12);  // between lon 270 (4) and 360 = 0 (1)
  EXPECT_NEAR(map.thickness_at(direction_at(180, 20)), 3.0, 1e-12);
  EXPECT_NEAR(map.strength_at(direction_at(10, 10)), 0.5, 1e-12);
  // The configuration reads it relative to the workflow's folder and records its content.
  write_file(scratch.path / "w.toml", "[workflow]\nname = \"m\"\n[crust]\nmap_file = \"map.csv\"\n");
  const Config config = load_config(scratch.path / "w.toml");
  EXPECT_EQ(*config.crust.map_file, (scratch.path / "map.csv").lexically_normal().string());
  EXPECT_EQ(config.crust.map_digest, crust_map_digest(scratch.path / "map.csv"));
  EXPECT_TRUE(make_crust_field(config.crust, "crust").has_map);
  // A changed file no longer matches the recorded digest: the build refuses it.
  write_file(scratch.path / "map.csv", csv + "\n# changed\n");
  EXPECT_NE(error_of([&] { make_crust_field(config.crust, "crust"); }).find("has changed since the workflow was read"),
            std::string::npos);
}

TEST(CrustField, AMalformedMapFileIsOneLineNamingTheFileAndLine) {
  const ScratchFolder scratch("crust_map_bad");
  const std::string header = "lon,lat,thickness_factor,strength_factor\n";
  const std::string grid = "0,-90,1,1\n180,-90,1,1\n0,90,1,1\n180,90,1,1\n";
  const std::pair<std::string, std::string> cases[] = {
      {"lon,lat,thickness\n" + grid, ":1: the header lacks the column 'thickness_factor'"},
      {header + "0,-90,1,1\n180,-90,x,1\n", ":3: thickness_factor 'x' is not a finite number"},
      {header + "0,-90,1,0\n", ":2: strength_factor = 0 must be > 0"},
      {header + "0,-90,-1,1\n", ":2: thickness_factor = -1 must be > 0"},
      {header + "0,-95,1,1\n", ":2: lat = -95 must be in [-90, 90]"},
      {header + grid + "0,-90,2,2\n", ":6: the point lon = 0, lat = -90 is given twice"},
      {header + "0,-90,1,1\n180,-90,1,1\n0,90,1,1\n", ": 3 points, not a regular grid"},
      {"", ": no header line"}};
  int k = 0;
  for (const auto& [text, expected] : cases) {
    const auto file = scratch.path / ("bad" + std::to_string(k++) + ".csv");
    write_file(file, text);
    const std::string message = error_of([&] { read_crust_map(file); });
    EXPECT_EQ(message.rfind(file.string() + expected, 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}
