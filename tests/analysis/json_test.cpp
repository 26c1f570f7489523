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
