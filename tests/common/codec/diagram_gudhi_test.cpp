// The sublevel form GUDHI reads: each point negated, the never-dying at inf or at 0 (floor), in
// the persistence-file layout "DIM BIRTH DEATH".
#include "common/codec/diagram_gudhi.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace fnet {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

FrameDiagrams example() {
  FrameDiagrams d;
  d.pd0 = {{2.5, 1.25}, {1.5, kNeverDies}, {0.0, kNeverDies}};  // a cluster, a component, a rattler
  d.pd1 = {{1.0, kNeverDies}, {0.75, 0.0}, {0.5, 0.125}};       // a defect, a loop filled at 0, one filled at 0.125
  return d;
}

TEST(DiagramGudhi, NegatesEveryPointAndWritesTheNeverDyingAtInf) {
  const Diagram pd0 = gudhi_diagram(example().pd0, GudhiEssential::inf);
  ASSERT_EQ(pd0.size(), 3u);
  EXPECT_EQ(pd0[0], (PersistencePoint{-2.5, -1.25}));
  EXPECT_EQ(pd0[1], (PersistencePoint{-1.5, kInf}));
  EXPECT_EQ(pd0[2], (PersistencePoint{0.0, kInf}));
  EXPECT_FALSE(std::signbit(pd0[2].birth)) << "a birth of 0 stays +0";
  for (const PersistencePoint& p : pd0) EXPECT_LE(p.birth, p.death) << "sublevel: birth <= death";
}

TEST(DiagramGudhi, FloorLetsTheNeverDyingDieAtZeroAndDropsRattlers) {
  const Diagram pd0 = gudhi_diagram(example().pd0, GudhiEssential::floor);
  ASSERT_EQ(pd0.size(), 2u) << "a rattler (0, -1) dies where it is born: on the diagonal, left out";
  EXPECT_EQ(pd0[1], (PersistencePoint{-1.5, 0.0}));
  EXPECT_FALSE(std::signbit(pd0[1].death));
  const Diagram pd1 = gudhi_diagram(example().pd1, GudhiEssential::floor);
  ASSERT_EQ(pd1.size(), 3u);
  EXPECT_EQ(pd1[0], (PersistencePoint{-1.0, 0.0}));
  EXPECT_EQ(pd1[1], (PersistencePoint{-0.75, 0.0}));
}

TEST(DiagramGudhi, PersistenceFileHasOneLinePerPointAfterAComment) {
  EXPECT_EQ(diagram_gudhi_text(example(), GudhiEssential::inf),
            "# fnet diagrams, sublevel form: dim birth death = 0|1 -b -d; never dies: inf\n"
            "0 -2.5 -1.25\n0 -1.5 inf\n0 0 inf\n1 -1 inf\n1 -0.75 0\n1 -0.5 -0.125\n");
  EXPECT_EQ(diagram_gudhi_text(example(), GudhiEssential::floor),
            "# fnet diagrams, sublevel form: dim birth death = 0|1 -b -d; never dies: 0 (floor)\n"
            "0 -2.5 -1.25\n0 -1.5 0\n1 -1 0\n1 -0.75 0\n1 -0.5 -0.125\n");
  EXPECT_EQ(diagram_gudhi_text(FrameDiagrams{}, GudhiEssential::inf).find('\n') + 1,
            diagram_gudhi_text(FrameDiagrams{}, GudhiEssential::inf).size())
      << "empty diagrams: the comment line alone";
}

TEST(DiagramGudhi, NumbersReadBackExactly) {
  FrameDiagrams d;
  d.pd1 = {{0.1 + 0.2, 1.0 / 3.0}};
  const std::string text = diagram_gudhi_text(d, GudhiEssential::inf);
  const std::string line = text.substr(text.find('\n') + 1);
  double birth = 0, death = 0;
  ASSERT_EQ(std::sscanf(line.c_str(), "1 %lf %lf", &birth, &death), 2) << line;
  EXPECT_EQ(birth, -(0.1 + 0.2));
  EXPECT_EQ(death, -(1.0 / 3.0));
}

TEST(DiagramGudhi, ConventionNames) {
  EXPECT_EQ(parse_gudhi_essential("inf"), GudhiEssential::inf);
  EXPECT_EQ(parse_gudhi_essential("floor"), GudhiEssential::floor);
  EXPECT_THROW(parse_gudhi_essential("separate"), std::invalid_argument);
}

}  // namespace
}  // namespace fnet
