// The names offered when a run is unknown: the edit distance against a brute-force recursion, and
// the choice of close names on the names of an ensemble's runs.
#include "server/api/close_names.hpp"

#include <functional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace fnet::server {
namespace {

// The textbook recursion, exponential: only for short strings.
std::size_t slow_distance(const std::string& a, const std::string& b) {
  if (a.empty()) return b.size();
  if (b.empty()) return a.size();
  const std::string ra = a.substr(1), rb = b.substr(1);
  return std::min({slow_distance(ra, b) + 1, slow_distance(a, rb) + 1, slow_distance(ra, rb) + (a[0] != b[0])});
}

TEST(CloseNames, EditDistanceIsLevenshtein) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> length(0, 6), letter(0, 2);
  for (int k = 0; k < 500; ++k) {
    std::string a, b;
    for (int n = length(rng); n > 0; --n) a += static_cast<char>('a' + letter(rng));
    for (int n = length(rng); n > 0; --n) b += static_cast<char>('a' + letter(rng));
    EXPECT_EQ(edit_distance(a, b), slow_distance(a, b)) << a << " " << b;
  }
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
}

TEST(CloseNames, OffersTheRealizationsOfAMistypedName) {
  const std::vector<std::string> runs = {"mu05-s1", "mu05-s2", "mu05-s10", "mu0-s1", "demo", "lammps-777"};
  EXPECT_EQ(close_names(runs, "mu05-s11"), (std::vector<std::string>{"mu05-s1", "mu05-s10", "mu0-s1", "mu05-s2"}));
  EXPECT_EQ(close_names(runs, "lammps"), (std::vector<std::string>{"lammps-777"}));  // contained
  EXPECT_EQ(close_names(runs, "dmeo"), (std::vector<std::string>{"demo"}));
  EXPECT_TRUE(close_names(runs, "something-else").empty());
  EXPECT_TRUE(close_names({}, "x").empty());
  EXPECT_EQ(close_names(runs, "mu05-s11", 2).size(), 2u);
}

}  // namespace
}  // namespace fnet::server
