// JSON from outside within limits: whatever the text, parse_bounded_json returns nlohmann's DOM or
// throws JsonInputError naming the source and what is wrong; nesting and size are bounded while
// the text is read, so a document of any depth costs no more stack than max_depth levels.
#include "common/codec/bounded_json.hpp"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fnet {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

std::string refusal(const std::string& text, JsonLimits limits = {}) {
  try {
    parse_bounded_json(text, limits, "in.json");
  } catch (const JsonInputError& e) {
    return e.what();
  }
  return "<accepted>";
}

std::string nested(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

TEST(BoundedJson, ReadsWhatNlohmannReads) {
  for (const std::string text :
       {R"({"a": [1, 2.5, -0.0, "x\u00e9"], "b": {"c": null, "d": true}})", "[]", "3", "\"s\""})
    EXPECT_EQ(parse_bounded_json(text, {}, "in.json"), nlohmann::json::parse(text)) << text;
}

TEST(BoundedJson, NestingUpToTheLimitIsReadAndDeeperIsRefused) {
  const JsonLimits limits{1 << 20, 16};
  EXPECT_EQ(parse_bounded_json(nested(16), limits, "in.json"), nlohmann::json::parse(nested(16)));
  EXPECT_THAT(refusal(nested(17), limits), AllOf(StartsWith("in.json: "), HasSubstr("nested deeper than 16")));
  EXPECT_THAT(refusal(R"({"a":{"b":{"c":[[1]]}}})", {1 << 20, 4}), HasSubstr("nested deeper than 4"));
}

// Deep enough to overflow the stack of any recursive reader or writer of the DOM: refused while
// it is read, before any DOM that deep exists.
TEST(BoundedJson, HundredsOfThousandsOfOpenArraysAreRefusedNotAStackOverflow) {
  EXPECT_THAT(refusal(std::string(300'000, '['), {1 << 20, 64}), HasSubstr("nested deeper than 64"));
  EXPECT_THAT(refusal(nested(300'000), {1 << 20, 64}), HasSubstr("nested deeper than 64"));
}

TEST(BoundedJson, ANumberOutsideADoublesRangeIsAnErrorNamingItAndTheByte) {
  EXPECT_THAT(refusal(R"({"x": 1e999})"), AllOf(StartsWith("in.json: "), HasSubstr("1e999"), HasSubstr("at byte 11")));
  EXPECT_THAT(refusal("-1e400"), HasSubstr("-1e400"));
}

TEST(BoundedJson, SyntaxErrorsNameLineAndColumn) {
  EXPECT_THAT(refusal("{\"a\": 1,\n \"b\": tru}"),
              AllOf(StartsWith("in.json: not JSON: parse error at line 2, column"), Not(HasSubstr("json.exception"))));
  EXPECT_THAT(refusal(""), HasSubstr("not JSON"));
  EXPECT_THAT(refusal("[1] x"), HasSubstr("not JSON"));
}

TEST(BoundedJson, TextLongerThanTheLimitIsRefusedUnread) {
  EXPECT_THAT(refusal("[1, 2, 3]", {8, 64}), AllOf(StartsWith("in.json: 9 bytes"), HasSubstr("limit of 8")));
  EXPECT_EQ(parse_bounded_json("[1, 2, 3]", {9, 64}, "in.json"), nlohmann::json::parse("[1, 2, 3]"));
}

}  // namespace
}  // namespace fnet
