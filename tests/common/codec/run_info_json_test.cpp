// The run announcement as JSON: both forms round-trip every field, and the keys are the ones
// proto/api.md lists for run.get.
#include "common/codec/run_info_json.hpp"

#include <set>
#include <string>

#include <gtest/gtest.h>

#include "tests/support/doc_names.hpp"
#include "tests/support/run_info_sample.hpp"

namespace fnet {
namespace {

TEST(RunInfoJson, ParsedFormRoundTripsEveryField) {
  const RunInfo sample = testing::distinct_run_info();
  const nlohmann::json json = to_json(sample);
  ASSERT_TRUE(json.at("config").is_object()) << json.dump();
  testing::expect_same_fields(sample, run_info_from_json(nlohmann::json::parse(json.dump())));
}

TEST(RunInfoJson, VerbatimFormRoundTripsEveryField) {
  RunInfo sample = testing::distinct_run_info();
  sample.config_json = "{ \"mu\" : 0.5 }";  // not canonical: only the verbatim form keeps the spaces
  const nlohmann::json json = to_json(sample, JsonText::verbatim);
  EXPECT_FALSE(json.contains("config"));
  testing::expect_same_fields(sample, run_info_from_json(nlohmann::json::parse(json.dump())));
}

// Stores and answers written before version 2 of the announcement have no "ensemble": none.
TEST(RunInfoJson, AnnouncementWithoutTheVersion2FieldReadsAsNoEnsemble) {
  nlohmann::json json = to_json(testing::distinct_run_info(), JsonText::verbatim);
  json.erase("ensemble");
  EXPECT_EQ(run_info_from_json(json).ensemble, "");
  json.erase("seed");  // a field of version 1 stays required
  EXPECT_THROW(run_info_from_json(json), nlohmann::json::exception);
}

TEST(RunInfoJson, ConfigThatIsNotJsonIsServedAsAString) {
  RunInfo sample = testing::distinct_run_info();
  sample.config_json = "mu = 0.5";
  const nlohmann::json json = to_json(sample);
  EXPECT_EQ(json.at("config"), "mu = 0.5");
  testing::expect_same_fields(sample, run_info_from_json(json));
}

// A config nested deeper than any run's (announced over DDS, up to 4 096 bytes) is served as its
// text: no reader or writer of the answer recurses into it.
TEST(RunInfoJson, ConfigNestedPastTheLimitIsServedAsAString) {
  RunInfo sample = testing::distinct_run_info();
  sample.config_json = std::string(2000, '[') + std::string(2000, ']');
  EXPECT_EQ(to_json(sample).at("config"), sample.config_json);
  sample.config_json = "{\"mu\": 1e999}";
  EXPECT_EQ(to_json(sample).at("config"), sample.config_json);
  sample.config_json = R"({"a": [[[1]]]})";
  EXPECT_TRUE(to_json(sample).at("config").is_object());
}

TEST(RunInfoJson, AMissingFieldIsNamed) {
  nlohmann::json json = to_json(testing::distinct_run_info());
  json.erase("kt_over_kn");
  try {
    run_info_from_json(json);
    FAIL() << "read a run announcement without kt_over_kn";
  } catch (const nlohmann::json::exception& e) {
    EXPECT_NE(std::string(e.what()).find("kt_over_kn"), std::string::npos) << e.what();
  }
}

TEST(RunInfoJson, KeysAreTheOnesTheApiDocumentLists) {
  const std::string api = testing::read_text(std::string(FNET_SOURCE_DIR) + "/proto/api.md");
  const std::set<std::string> documented = testing::backticked_between(api, "(the run announcement:", "or null");
  std::set<std::string> keys;
  const nlohmann::json json = to_json(testing::distinct_run_info());
  for (const auto& [key, value] : json.items()) keys.insert(key);
  EXPECT_EQ(keys, documented);
}

}  // namespace
}  // namespace fnet
