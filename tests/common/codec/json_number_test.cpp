// JSON numbers without a DOM must be nlohmann's numbers: every double written reads back bit for
// bit (by nlohmann and by read_json_number), looks as dump() writes it, and every token reads to
// the double nlohmann gives; what is not a JSON number is refused.
#include "common/codec/json_number.hpp"

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace fnet {
namespace {

std::string written(double v) {
  char buf[kJsonNumberMaxChars];
  return {buf, write_json_number(buf, v)};
}

std::uint64_t number_bits(double v) { return std::bit_cast<std::uint64_t>(v); }

// Edge cases, then random bit patterns (every exponent alike: subnormals, huge and tiny), then
// random values of everyday size, as a diagram holds them.
std::vector<double> sample_doubles() {
  std::vector<double> out{0.0,
                          -0.0,
                          -1.0,
                          1.0,
                          0.1 + 0.2,
                          1.0 / 3.0,
                          std::numeric_limits<double>::denorm_min(),
                          -std::numeric_limits<double>::denorm_min(),
                          DBL_MIN,
                          std::nextafter(DBL_MIN, 0.0),
                          DBL_MAX,
                          -DBL_MAX,
                          DBL_EPSILON,
                          1e-300,
                          1e300,
                          1e15,
                          1e16,
                          123456789012345.0,
                          1234567890123456.0,
                          9007199254740993.0,
                          0.001,
                          0.0001,
                          0.00001,
                          100000.0,
                          2.5e-7,
                          5e-324};
  std::mt19937_64 rng(20261201);
  for (int k = 0; k < 20000; ++k) {
    const double v = std::bit_cast<double>(rng());
    if (std::isfinite(v)) out.push_back(v);
  }
  std::uniform_real_distribution<double> everyday(0.0, 30.0);
  for (int k = 0; k < 20000; ++k) out.push_back(everyday(rng));
  return out;
}

TEST(JsonNumber, EveryDoubleRoundTripsBitForBit) {
  for (const double v : sample_doubles()) {
    const std::string text = written(v);
    ASSERT_LE(text.size(), kJsonNumberMaxChars);
    const auto ours = read_json_number(text);
    ASSERT_TRUE(ours) << text;
    EXPECT_EQ(ours->length, text.size()) << text;
    EXPECT_EQ(number_bits(ours->value), number_bits(v)) << text;
    const nlohmann::json theirs = nlohmann::json::parse(text);
    ASSERT_TRUE(theirs.is_number_float()) << text << " would read back as an integer";
    EXPECT_EQ(number_bits(theirs.get<double>()), number_bits(v)) << text;
  }
}

// Same layout as dump(): the shortest digits nlohmann's Grisu2 finds for these values.
TEST(JsonNumber, LooksAsDumpWritesIt) {
  for (const double v : {0.0, -0.0, -1.0, 1.5, 0.30000000000000004, 1.0 / 3.0, 1e15, 1e16, 123456789012345.0,
                         1234567890123456.0, 0.0001, 0.00001, 100000.0, 2.5e-7, 5e-324, DBL_MAX, -DBL_MIN, 1e-300})
    EXPECT_EQ(written(v), nlohmann::json(v).dump());
  EXPECT_EQ(written(std::nan("")), "null");
  EXPECT_EQ(written(-INFINITY), "null");
}

// Tokens as other writers spell them read to what nlohmann reads, integers included ("-0" is an
// integer to nlohmann, so 0.0 with no sign).
TEST(JsonNumber, ReadsEveryTokenAsNlohmannDoes) {
  for (const std::string text : {"0", "-0", "-0.0", "7", "-7", "1E5", "1e+5", "2.5E-07", "12345678901234567890",
                                 "-9223372036854775808", "-9223372036854775809", "18446744073709551616",
                                 "123456789012345678901234567890", "1e-310", "0.1e1", "4.9406564584124654e-324"}) {
    const auto ours = read_json_number(text);
    ASSERT_TRUE(ours) << text;
    EXPECT_EQ(ours->length, text.size()) << text;
    EXPECT_EQ(number_bits(ours->value), number_bits(nlohmann::json::parse(text).get<double>())) << text;
  }
}

TEST(JsonNumber, StopsAtTheEndOfTheToken) {
  const auto n = read_json_number("-12.5e3,0]");
  ASSERT_TRUE(n);
  EXPECT_EQ(n->length, 7u);
  EXPECT_EQ(n->value, -12500.0);
}

TEST(JsonNumber, RefusesWhatIsNotAJsonNumber) {
  for (const std::string text : {"",    "-",   "+1",  ".5",       "1.",   "1.e5", "01",    "-01",    "1e", "1e+",
                                 "nan", "NaN", "inf", "Infinity", "-inf", "0x10", "1e400", "-1e400", " 1", "e5"}) {
    const auto n = read_json_number(text);
    // A prefix may be a number ("01" is "0" then "1"): it must then stop before the bad part.
    if (n) {
      EXPECT_LT(n->length, text.size()) << text;
    }
  }
  EXPECT_FALSE(read_json_number("1e400")) << "out of range of a finite double";
  EXPECT_FALSE(read_json_number("1."));
  EXPECT_FALSE(read_json_number("nan"));
}

}  // namespace
}  // namespace fnet
