// A crust that varies on the command line (docs/crust.md): every bad [crust] input is one line on
// stderr naming the file and the problem, exit code 2, and nothing is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/cli_runner.hpp"
#include "support/files.hpp"
#include "support/quick_workflow.hpp"

using namespace tidalcrust::test_support;
namespace fs = std::filesystem;

TEST(CrustCli, EveryBadCrustInputIsOneLineAndExitCodeTwo) {
  const ScratchFolder dir("crust_cli_bad");
  write_file(dir.path / "bad-map.csv", "lon,lat,thickness_factor,strength_factor\n0,-90,1,1\n180,-90,1,nan\n");
  const std::pair<std::string, std::string> cases[] = {
      {"thickness_harmonics = \"c10 = 0.5q\"", "bad.toml: crust.thickness_harmonics: 'c10 = 0.5q': the value is not a finite number"},
      {"strength_harmonics = \"y10 = 0.5\"", "bad.toml: crust.strength_harmonics: 'y10 = 0.5': not a term c<l><m> or s<l><m>"},
      {"weak_lines = \"pole_lon = 0, pole_lat = 0, half_width = 5, factor = 0\"",
       "bad.toml: crust.weak_lines: weak line 1: factor = 0 must be in (0, 1)"},
      {"map_file = \"missing.csv\"", (dir.path / "missing.csv").string() + ": cannot open crust.map_file"},
      {"map_file = \"bad-map.csv\"", (dir.path / "bad-map.csv").string() + ":3: strength_factor 'nan' is not a finite number"},
      // Valid terms whose field is not positive everywhere: refused when the body is built.
      {"thickness_harmonics = \"c10 = 1.5\"", "crust.thickness_harmonics (with crust.map_file): the crust's thickness "
                                              "factor is -0."}};
  int k = 0;
  for (const auto& [line, expected] : cases) {
    const fs::path file = dir.path / "bad.toml";
    write_file(file, small_body_toml("bad") + "[crust]\n" + line + "\n");
    const fs::path out = dir.path / ("b" + std::to_string(k++) + ".h5");
    const CliResult r = run_cli("build --config " + quoted(file) + " --out " + quoted(out));
    EXPECT_EQ(r.exit_code, 2) << line << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << line;
  }
}

TEST(CrustCli, ConfigShowsTheCrustAndTheMapsDigest) {
  const ScratchFolder dir("crust_cli_config");
  std::string csv = "lon,lat,thickness_factor,strength_factor\n";
  for (int lat : {-90, 90})
    for (int lon : {0, 120, 240}) csv += std::to_string(lon) + "," + std::to_string(lat) + ",1,0.8\n";
  write_file(dir.path / "map.csv", csv);
  write_file(dir.path / "w.toml", small_body_toml("w") + "[crust]\nmap_file = \"map.csv\"\nstrength_harmonics = \"s11 = -0.2\"\n");
  const CliResult r = run_cli("config " + quoted(dir.path / "w.toml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("[crust]"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("strength_harmonics = 's11 = -0.2'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("map_file = '" + (dir.path / "map.csv").string() + "'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("map_digest = '"), std::string::npos) << r.out;
}
