// How fnetctl prints numbers: exact text for CSV (reads back to the same double), `inf` for an
// infinite distance, and a dash (table) or nothing (CSV) when there is no previous frame.
#include "client/fnetctl/value_text.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

#include <gtest/gtest.h>

namespace fnet::client {
namespace {

TEST(ValueText, ExactNumbersReadBackBitForBit) {
  for (const double v : {0.1, 1.0 / 3.0, 0.6331250000000001, 2.2250738585072014e-308, 4.9406564584124654e-324,
                         1.7976931348623157e308, -0.0, 1e23, 123456789.123456789}) {
    const std::string text = exact_number(v);
    const double back = std::strtod(text.c_str(), nullptr);
    EXPECT_EQ(std::memcmp(&v, &back, sizeof v), 0) << text;
  }
  EXPECT_EQ(exact_number(0.5), "0.5");
  EXPECT_EQ(exact_number(std::numeric_limits<double>::infinity()), "inf");
}

TEST(ValueText, DistanceCells) {
  using json = nlohmann::json;
  EXPECT_EQ(distance_cell(json(nullptr), false, CellStyle::table), "-");
  EXPECT_EQ(distance_cell(json(nullptr), false, CellStyle::csv), "");
  EXPECT_EQ(distance_cell(json(nullptr), true, CellStyle::table), "inf");
  EXPECT_EQ(distance_cell(json(nullptr), true, CellStyle::csv), "inf");
  EXPECT_EQ(distance_cell(json(0.1), false, CellStyle::csv), "0.1");
  EXPECT_EQ(distance_cell(json(1.0 / 3.0), false, CellStyle::csv), "0.3333333333333333");
  EXPECT_EQ(distance_cell(json(1.0 / 3.0), false, CellStyle::table), "0.33333333");
}

}  // namespace
}  // namespace fnet::client
