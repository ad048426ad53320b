#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "io/json_writer.hpp"

using tidalcrust::JsonWriter;

TEST(JsonWriter, NestedObjectsArraysAndEscapes) {
  JsonWriter json;
  json.begin_object().value("name", "a\"b").value("count", 3).value("x", 0.1);
  json.numbers("v", std::vector<double>{1.5, -2.0});
  json.begin_object("inner").value("ok", true).end_object();
  json.value("bad", std::numeric_limits<double>::quiet_NaN());
  json.end_object();
  EXPECT_EQ(json.str(),
            "{\n  \"name\": \"a\\\"b\",\n  \"count\": 3,\n  \"x\": 0.1,\n  \"v\": [1.5, -2],\n"
            "  \"inner\": {\n    \"ok\": true\n  },\n  \"bad\": null\n}\n");
}
