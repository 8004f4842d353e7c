// What a run announcement must be before the registry records it, and the reason given when it
// is not: names, finite numbers, and parameters that are one JSON value within its bounds.
#include "server/registry/announcement_check.hpp"

#include <limits>

#include <gtest/gtest.h>

namespace fnet::server {
namespace {

RunInfo good() {
  RunInfo info;
  info.run_id = "run-1";
  info.particles = 2000;
  info.friction = 0.5;
  info.config_json = R"({"particles":2000,"walls":{"speed":[0.001,0.001]}})";
  info.ensemble = "mu05";
  return info;
}

std::string nested(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

TEST(AnnouncementCheck, AcceptsWhatThePublishersSend) {
  EXPECT_EQ(announcement_problem(good()), "");
  RunInfo info = good();
  info.config_json = "";  // no parameters
  info.ensemble = "";     // no ensemble
  EXPECT_EQ(announcement_problem(info), "");
  info.config_json = nested(kMaxConfigDepth);
  EXPECT_EQ(announcement_problem(info), "");
}

TEST(AnnouncementCheck, RefusesWithAReasonNamingTheRun) {
  const auto problem = [](auto&& edit) {
    RunInfo info = good();
    edit(info);
    return announcement_problem(info);
  };
  EXPECT_EQ(problem([](RunInfo& i) { i.config_json = nested(kMaxConfigDepth + 1); }),
            "run run-1: config_json is nested deeper than 32 levels");
  EXPECT_EQ(problem([](RunInfo& i) { i.config_json = nested(2000); }),
            "run run-1: config_json is nested deeper than 32 levels");
  EXPECT_EQ(problem([](RunInfo& i) { i.config_json = std::string(kMaxConfigBytes + 1, ' '); }),
            "run run-1: config_json is 4097 bytes, above 4096");
  EXPECT_EQ(problem([](RunInfo& i) { i.config_json = "mu = 0.5"; }).rfind("run run-1: config_json is not JSON (", 0),
            0u);
  // A number beyond a double's range, which nlohmann reports as out of range.
  EXPECT_EQ(
      problem([](RunInfo& i) { i.config_json = R"({"k_n": 1e999})"; }).rfind("run run-1: config_json is not JSON", 0),
      0u);
  EXPECT_EQ(
      problem([](RunInfo& i) { i.config_json = "{\"a\": 1} trailing"; }).rfind("run run-1: config_json is not JSON", 0),
      0u);
  EXPECT_EQ(problem([](RunInfo& i) { i.friction = std::numeric_limits<double>::quiet_NaN(); }),
            "run run-1: friction = nan is not a finite number");
  EXPECT_EQ(problem([](RunInfo& i) { i.dt = std::numeric_limits<double>::infinity(); }),
            "run run-1: dt = inf is not a finite number");
  EXPECT_NE(problem([](RunInfo& i) { i.ensemble = "../x"; }).find("run run-1: "), std::string::npos);
  EXPECT_FALSE(problem([](RunInfo& i) { i.run_id = "../x"; }).empty());
}

}  // namespace
}  // namespace fnet::server
