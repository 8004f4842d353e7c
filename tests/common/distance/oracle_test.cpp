// Independent oracle on realistic pairs: scipy's assignment solver on the diagonal-augmented
// cost matrix (exact), and the bottleneck by binary search with scipy's bipartite matching.
// Also the command line, end to end.
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/codec/diagram_json.hpp"
#include "distance_support.hpp"
#include "distance_test_util.hpp"

namespace fnet::test {
namespace {

void compare_with_oracle(const Diagram& a, const Diagram& b, EssentialConvention c, const char* what) {
  const std::vector<double> expected = oracle_distances(a, b, c, {"bottleneck", "1", "2"});
  const double q[] = {0, 1, 2};
  for (int k = 0; k < 3; ++k) {
    const DistanceResult r = distance(a, b, q[k], c);
    if (std::isnan(expected[k])) {
      EXPECT_TRUE(r.infinite) << what;
      continue;
    }
    EXPECT_TRUE(close(r.value, expected[k], 1e-12))
        << what << " " << label(q[k], c) << ": fnet " << r.value << " oracle " << expected[k];
  }
}

class DistanceOracle : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!oracle_available()) GTEST_SKIP() << "python3 with scipy not found (FNET_ORACLE_PYTHON)";
  }
};

TEST_F(DistanceOracle, ConsecutiveLammpsFramesNormalForces) {
  const FrameDiagramsPair a = lammps_diagrams(9, false), b = lammps_diagrams(10, false);
  compare_with_oracle(a.pd0, b.pd0, EssentialConvention::floor, "pd0 9->10");
  compare_with_oracle(a.pd1, b.pd1, EssentialConvention::floor, "pd1 9->10");
  compare_with_oracle(a.pd1, b.pd1, EssentialConvention::sentinel, "pd1 9->10");
  compare_with_oracle(a.pd0, b.pd0, EssentialConvention::separate, "pd0 9->10");
}

TEST_F(DistanceOracle, ConsecutiveLammpsFramesTangentialForces) {
  const FrameDiagramsPair a = lammps_diagrams(8, true), b = lammps_diagrams(9, true);
  compare_with_oracle(a.pd0, b.pd0, EssentialConvention::floor, "pd0 8->9 tangential");
  compare_with_oracle(a.pd0, b.pd0, EssentialConvention::sentinel, "pd0 8->9 tangential");
}

TEST_F(DistanceOracle, TinyScaleRealisticPair) {
  // Around 1e-10 the fixed tolerances inside Hera and POT break; the assignment oracle does not.
  const FrameDiagramsPair a = lammps_diagrams(9, false), b = lammps_diagrams(10, false);
  compare_with_oracle(scaled(a.pd0, 1e-10), scaled(b.pd0, 1e-10), EssentialConvention::floor, "pd0 x 1e-10");
}

TEST_F(DistanceOracle, RandomMediumPairs) {
  std::mt19937_64 rng(77);
  for (int trial = 0; trial < 4; ++trial) {
    const Diagram a = random_diagram(rng, 150, 4, trial % 2 == 0);
    const Diagram b = perturbed(rng, a, 0.2);
    compare_with_oracle(a, b, EssentialConvention::floor, "random");
    compare_with_oracle(a, b, EssentialConvention::sentinel, "random");
  }
}

std::string run(const std::string& cmd, int& status) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), pipe.get())) out += buf.data();
  status = pclose(pipe.release());
  return out;
}

TEST(DistanceCli, PrintsValueBoundsAndInfinity) {
  TempDir dir;
  const auto fa = dir.path() / "a.json", fb = dir.path() / "b.json";
  Diagram g = {{3, -1}};
  for (int k = 0; k < 7; ++k) g.push_back({1, 0});
  std::ofstream(fa) << nlohmann::json{{"pd0", to_json(Diagram{{5, -1}})}, {"pd1", to_json(Diagram{{5, -1}})}}.dump();
  std::ofstream(fb) << nlohmann::json{{"pd0", to_json(g)}, {"pd1", to_json(Diagram{{2, 1}})}}.dump();
  std::string base = FNET_ANALYZE;
  base.append(" distance ").append(fa.string()).append(" ").append(fb.string());
  int status = 0;
  nlohmann::json j = nlohmann::json::parse(run(base + " --metric wasserstein1 --dim 0", status));
  EXPECT_EQ(status, 0);
  EXPECT_DOUBLE_EQ(j["value"].get<double>(), 5.5);
  EXPECT_EQ(j["lower"], j["value"]);
  EXPECT_EQ(j["upper"], j["value"]);
  EXPECT_EQ(j["exact"], true);
  EXPECT_TRUE(j["seconds"].is_number());
  j = nlohmann::json::parse(run(base + " --metric wasserstein --q 2 --dim 0", status));
  EXPECT_DOUBLE_EQ(j["value"].get<double>(), std::sqrt(5.75));
  j = nlohmann::json::parse(run(base + " --metric bottleneck --dim 0 --delta 0.5", status));
  EXPECT_LE(j["lower"].get<double>(), 2);
  EXPECT_GE(j["upper"].get<double>(), 2);
  j = nlohmann::json::parse(run(base + " --metric bottleneck --dim 1 --essential separate", status));
  EXPECT_EQ(status, 0);
  EXPECT_TRUE(j["value"].is_null());
  EXPECT_EQ(j["infinite"], true);
  EXPECT_TRUE(j["reason"].is_string());
  run(base + " --metric wasserstein --q 0.5 2>/dev/null", status);
  EXPECT_NE(status, 0);
  run(base + " --metric manhattan 2>/dev/null", status);
  EXPECT_NE(status, 0);
}

// q = 1000 used to print 0.0: the q-th powers of the costs underflowed. In doubles the bottleneck
// of these inputs is 0.9 - 0.8 = 0.09999999999999998, and d_Wq may not go below it.
TEST(DistanceCli, LargeExponentIsNeverBelowTheBottleneck) {
  TempDir dir;
  const auto fa = dir.path() / "a.json", fb = dir.path() / "b.json";
  std::ofstream(fa) << R"({"pd0":[],"pd1":[[1.0,0.8],[2.0,1.5],[3.0,2.97]]})";
  std::ofstream(fb) << R"({"pd0":[],"pd1":[[1.0,0.9],[2.0,1.45]]})";
  std::string base = FNET_ANALYZE;
  base.append(" distance ").append(fa.string()).append(" ").append(fb.string());
  int status = 0;
  const nlohmann::json bottleneck = nlohmann::json::parse(run(base + " --metric bottleneck", status));
  ASSERT_EQ(status, 0);
  const double d_b = bottleneck["value"].get<double>();
  EXPECT_NEAR(d_b, 0.1, 1e-16);
  for (const char* q : {"1000", "1e6", "100", "10"}) {
    const nlohmann::json j = nlohmann::json::parse(run(base + " --metric wasserstein --q " + q, status));
    ASSERT_EQ(status, 0) << q;
    const double value = j["value"].get<double>();
    EXPECT_GE(value, d_b) << "q=" << q;
    EXPECT_LE(value, d_b * std::pow(5.0, 1 / std::stod(q))) << "q=" << q;  // 5 points in all
    EXPECT_EQ(j["lower"], j["value"]);
    EXPECT_EQ(j["upper"], j["value"]);
    EXPECT_EQ(j["exact"], true);
  }
}

}  // namespace
}  // namespace fnet::test
