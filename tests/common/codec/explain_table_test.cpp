// The explain table's "where" column says whose position it gives: the first frame's point (a),
// the second's (b), one place when both agree, both when they differ.
#include "common/codec/explain_table.hpp"

#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fnet {
namespace {

using nlohmann::json;

json point(double birth, std::vector<std::pair<double, double>> positions) {
  json p = {{"birth", birth}, {"death", -1.0}, {"death_simplex", nullptr}};
  json grains = json::array(), xy = json::array();
  for (std::size_t k = 0; k < positions.size(); ++k) {
    grains.push_back(k);
    xy.push_back({positions[k].first, positions[k].second});
  }
  p["birth_simplex"] = {{"grains", grains}, {"positions", xy}};
  return p;
}

TEST(ExplainTable, WhereNamesWhosePositionItIs) {
  const json a = point(5, {{1, 2}, {3, 4}}), b = point(3, {{10, 20}});
  EXPECT_EQ(explain_where({{"a", a}, {"b", nullptr}}), "a (2, 3)");
  EXPECT_EQ(explain_where({{"a", nullptr}, {"b", b}}), "b (10, 20)");
  EXPECT_EQ(explain_where({{"a", a}, {"b", b}}), "a (2, 3) b (10, 20)");
  EXPECT_EQ(explain_where({{"a", a}, {"b", point(4, {{3, 4}, {1, 2}})}}), "a = b (2, 3)");
  json bare = a;
  bare["birth_simplex"].erase("positions");
  EXPECT_EQ(explain_where({{"a", bare}, {"b", nullptr}}), "-");
}

TEST(ExplainTable, TheTableSaysWhatAAndBAre) {
  const json answer = {
      {"dim", 0},
      {"force", "normal"},
      {"essential", "floor"},
      {"value", 2.0},
      {"explain", {{{"rank", 1}, {"cost", 2.0}, {"a", point(5, {{1, 2}})}, {"b", point(3, {{1, 2}})}}}}};
  std::ostringstream out;
  write_explain_table(out, answer, "bottleneck");
  EXPECT_THAT(out.str(), ::testing::AllOf(::testing::HasSubstr("a: the first frame's point, b: the second's"),
                                          ::testing::HasSubstr("where (x, y)"), ::testing::HasSubstr("a = b (1, 2)")));
}

// In a 3D frame each position has its z: "where" is the centre in x, y and z, and the header says so.
TEST(ExplainTable, A3DFramesCentreHasItsZ) {
  json a = point(5, {}), b = point(3, {});
  a["birth_simplex"] = {{"grains", {4, 9, 11}}, {"positions", {{0, 0, 0}, {3, 0, 1}, {0, 3, 5}}}};
  b["birth_simplex"] = {{"grains", {7}}, {"positions", {{1, 1, 2}}}};
  EXPECT_EQ(explain_where({{"a", a}, {"b", b}}), "a = b (1, 1, 2)");
  EXPECT_EQ(explain_where({{"a", nullptr}, {"b", a}}), "b (1, 1, 2)");
  b["birth_simplex"]["positions"] = {{1, 1, 2.5}};
  EXPECT_EQ(explain_where({{"a", a}, {"b", b}}), "a (1, 1, 2) b (1, 1, 2.5)");
  const json answer = {{"dim", 1},
                       {"force", "normal"},
                       {"essential", "floor"},
                       {"value", 2.0},
                       {"explain", {{{"rank", 1}, {"cost", 2.0}, {"a", nullptr}, {"b", a}}}}};
  std::ostringstream out;
  write_explain_table(out, answer, "bottleneck");
  EXPECT_THAT(out.str(), ::testing::AllOf(::testing::HasSubstr("where (x, y, z)"), ::testing::HasSubstr("4-9-11"),
                                          ::testing::HasSubstr("b (1, 1, 2)")));
}

}  // namespace
}  // namespace fnet
