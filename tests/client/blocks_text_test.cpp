// How fnetctl blocks prints a 3D answer: each cell's layer first, the z bounds in the CSV, the
// largest starred in its own layer only; a 2D answer keeps its columns.
#include "client/fnetctl/blocks_text.hpp"

#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace fnet::client {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

// blocks.get's answer for a k = 2 grid: 8 cells layer by layer in 3D, 4 in 2D; cell n's value n / 8.
json answer(int dimension) {
  const int cells = dimension == 3 ? 8 : 4;
  json out = {{"run", "r"},
              {"frame", 1},
              {"other_frame", 2},
              {"k", 2},
              {"dimension", dimension},
              {"metric", "bottleneck"},
              {"dim", 1},
              {"force", "normal"},
              {"essential", "floor"}};
  out["cells"] = json::array();
  for (int n = 0; n < cells; ++n) {
    json bounds = {n % 2, n % 2 + 1, n / 2 % 2, n / 2 % 2 + 1};
    if (dimension == 3) bounds.push_back(n / 4), bounds.push_back(n / 4 + 0.5);
    json cell = {
        {"row", n / 2 % 2},         {"col", n % 2},     {"bounds", {bounds, bounds}}, {"contacts", {n, n + 10}},
        {"points", {2 * n, 3 * n}}, {"value", n / 8.0}, {"infinite", false}};
    if (dimension == 3) cell["layer"] = n / 4;
    out["cells"].push_back(cell);
  }
  out["largest"] = {{"row", 1}, {"col", 0}, {"value", dimension == 3 ? 6 / 8.0 : 2 / 8.0}};
  if (dimension == 3) out["largest"]["layer"] = 1;
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

TEST(BlocksText, A3DCsvRowHasItsLayerAndZBounds) {
  std::ostringstream out;
  write_blocks_csv(out, answer(3));
  const auto lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 9u);
  EXPECT_EQ(lines[0],
            "layer,row,col,x_lo,x_hi,y_lo,y_hi,z_lo,z_hi,other_x_lo,other_x_hi,other_y_lo,other_y_hi,other_z_lo,"
            "other_z_hi,contacts,other_contacts,points,other_points,value");
  // Cell 5: layer 1, row 0, col 1; x 1..2, y 0..1, z 1..1.5.
  EXPECT_EQ(lines[6], "1,0,1,1,2,0,1,1,1.5,1,2,0,1,1,1.5,5,15,10,15,0.625");
  EXPECT_EQ(grid_text(answer(3)), "2 x 2 x 2");
}

TEST(BlocksText, A3DTableStarsTheLargestInItsLayerOnly) {
  std::ostringstream out;
  write_blocks_table(out, answer(3));
  const auto lines = lines_of(out.str());
  ASSERT_EQ(lines.size(), 10u);
  EXPECT_THAT(lines[0], HasSubstr("2 x 2 x 2 blocks"));
  EXPECT_THAT(lines[0], HasSubstr("layer 0 = lowest z"));
  EXPECT_THAT(lines[1], HasSubstr("layer"));
  for (int n = 0; n < 8; ++n) {
    const std::string& line = lines[2 + n];
    EXPECT_THAT(line, ::testing::StartsWith("     " + std::to_string(n / 4))) << line;
    if (n == 6)
      EXPECT_THAT(line, HasSubstr(" *"));
    else
      EXPECT_THAT(line, Not(HasSubstr("*"))) << "cell " << n << " is in row 1, col 0 of the other layer";
  }
}

TEST(BlocksText, A2DAnswerHasNoLayers) {
  std::ostringstream table, csv;
  write_blocks_table(table, answer(2));
  write_blocks_csv(csv, answer(2));
  EXPECT_THAT(table.str(), HasSubstr("2 x 2 blocks"));
  EXPECT_THAT(table.str(), Not(HasSubstr("layer")));
  EXPECT_THAT(lines_of(table.str())[1], ::testing::StartsWith(" row  col"));
  EXPECT_THAT(lines_of(csv.str())[0], ::testing::StartsWith("row,col,x_lo,x_hi,y_lo,y_hi,other_x_lo"));
  EXPECT_EQ(lines_of(csv.str())[2], "0,1,1,2,0,1,1,2,0,1,1,11,2,3,0.125");
}

}  // namespace
}  // namespace fnet::client
