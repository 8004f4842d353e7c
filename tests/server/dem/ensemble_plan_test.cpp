// The seeds of --seeds and the per-realization paths of an ensemble.
#include "server/dem/ensemble_plan.hpp"

#include <stdexcept>

#include <gtest/gtest.h>

namespace fnet::sim {
namespace {

using Seeds = std::vector<std::uint64_t>;

TEST(EnsemblePlan, SeedListsTakeSeedsAndRangesInTheOrderGiven) {
  EXPECT_EQ(parse_seed_list("7"), Seeds({7}));
  EXPECT_EQ(parse_seed_list("1-4"), Seeds({1, 2, 3, 4}));
  EXPECT_EQ(parse_seed_list("1,3,5-7"), Seeds({1, 3, 5, 6, 7}));
  EXPECT_EQ(parse_seed_list("11-12,0,4-4"), Seeds({11, 12, 0, 4}));
  EXPECT_EQ(parse_seed_list("18446744073709551615"), Seeds({18446744073709551615ull}));
  EXPECT_EQ(parse_seed_list("1-20").size(), 20u);
}

TEST(EnsemblePlan, BadSeedListsSayWhatIsWrong) {
  const auto problem = [](const char* spec) {
    try {
      parse_seed_list(spec);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(problem("").find("empty"), std::string::npos);
  EXPECT_NE(problem("1,,2").find("empty item"), std::string::npos);
  EXPECT_NE(problem("1,").find("empty item"), std::string::npos);
  EXPECT_NE(problem("5-3").find("reversed"), std::string::npos);
  EXPECT_NE(problem("1,2,1").find("seed 1 is listed twice"), std::string::npos);
  EXPECT_NE(problem("1-5,3-4").find("seed 3 is listed twice"), std::string::npos);
  for (const char* bad : {"a", "1-b", "-1", "1-", "1-2-3", " 1", "1.5", "+2", "18446744073709551616"})
    EXPECT_NE(problem(bad).find("is not a seed"), std::string::npos) << bad;
  EXPECT_NE(problem("0-10000").find("more than 10000"), std::string::npos);
  EXPECT_EQ(problem("0-9999"), "accepted");
  EXPECT_NE(problem("0-9999,10000").find("more than 10000"), std::string::npos);
}

TEST(EnsemblePlan, PathTemplatesNameEachRealization) {
  EXPECT_TRUE(names_each_realization("runs/{run}.h5"));
  EXPECT_TRUE(names_each_realization("s{seed}"));
  EXPECT_FALSE(names_each_realization("runs/run.h5"));
  EXPECT_FALSE(names_each_realization("{runs}"));
  EXPECT_EQ(realization_run_id("mu05", 12), "mu05-s12");
  EXPECT_EQ(expand_path_template("out/{run}/{run}-{seed}.h5", "mu05-s12", 12), "out/mu05-s12/mu05-s12-12.h5");
  EXPECT_EQ(expand_path_template("plain", "mu05-s12", 12), "plain");
}

}  // namespace
}  // namespace fnet::sim
