#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "io/json.hpp"

using tidalcrust::Json;
using tidalcrust::json_text;

namespace {
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }
}  // namespace

TEST(Json, DoublesReadBackToTheSameBits) {
  for (const double x : {0.1, 1.0 / 3, 2.0, -0.0, 1e-300, 6.02214076e23, std::numeric_limits<double>::denorm_min(),
                         std::numeric_limits<double>::max(), std::nextafter(1.0, 2.0)}) {
    const Json back = Json::parse(json_text(Json{{"x", x}}));
    EXPECT_TRUE(same_bits(back["x"].get<double>(), x)) << json_text(Json{{"x", x}});
  }
}

TEST(Json, NonFiniteNumbersAreNull) {
  const Json json = {{"nan", std::numeric_limits<double>::quiet_NaN()},
                     {"inf", -std::numeric_limits<double>::infinity()},
                     {"list", {1.5, std::numeric_limits<double>::quiet_NaN()}}};
  const Json back = Json::parse(json_text(json));
  EXPECT_TRUE(back["nan"].is_null());
  EXPECT_TRUE(back["inf"].is_null());
  EXPECT_EQ(back["list"], Json::parse("[1.5, null]"));
}

TEST(Json, TextKeepsKeyOrderEscapesAndEndsInANewline) {
  const Json json = {{"zeta", 1}, {"alpha", "a\"b\n"}, {"inner", {{"ok", true}}}};
  EXPECT_EQ(json_text(json), "{\n  \"zeta\": 1,\n  \"alpha\": \"a\\\"b\\n\",\n  \"inner\": {\n    \"ok\": true\n  }\n}\n");
}

TEST(Json, InvalidUtf8IsReplacedNotThrown) {
  const std::string name = "file\xff.h5";
  std::string text;
  EXPECT_NO_THROW(text = json_text(Json{{"file", name}}));
  EXPECT_NE(text.find("file\xef\xbf\xbd.h5"), std::string::npos) << text;  // U+FFFD
}
