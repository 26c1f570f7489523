#include "cosim/analysis/json.h"

#include <gtest/gtest.h>

#include <cmath>

using cosim::analysis::Json;

TEST(Json, WritesNestedObjectsInInsertionOrderAndEscapes) {
  Json j = Json::object();
  j["b"] = 1.5;
  j["a"] = "x\"y\n";
  j["list"] = Json(std::vector<double>{1, 2});
  j["nan"] = std::nan("");
  j["flag"] = true;
  EXPECT_EQ(j.dump(-1), "{\"b\":1.5,\"a\":\"x\\\"y\\n\",\"list\":[1, 2],\"nan\":null,\"flag\":true}");
}

TEST(Json, NumbersRoundTripAtFullPrecision) {
  const double x = 0.1 + 0.2;
  Json j = Json::array();
  j.push(x);
  const std::string s = j.dump(-1);
  EXPECT_EQ(std::stod(s.substr(1, s.size() - 2)), x);
}

TEST(Json, ParsesWhatItWritesAndReportsErrors) {
  Json j = Json::object();
  j["name"] = "a \"b\"\n\u00e9";
  j["x"] = -1.25e-7;
  j["list"] = Json(std::vector<double>{1, 2.5});
  j["nested"]["flag"] = false;
  j["nothing"] = Json();
  const Json back = Json::parse(j.dump(2));
  EXPECT_EQ(back.dump(-1), j.dump(-1));
  ASSERT_NE(back.find("x"), nullptr);
  EXPECT_EQ(*back.find("x")->number(), -1.25e-7);
  EXPECT_EQ(*back.find("name")->string(), "a \"b\"\n\u00e9");
  EXPECT_EQ(back.find("missing"), nullptr);
  EXPECT_EQ(*Json::parse("\"\\u00e9\"").string(), "\u00e9");
  try {
    Json::parse("{\"a\": [1, 2}");
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("expected ',' or ']' at offset 11"), std::string::npos) << e.what();
  }
}
