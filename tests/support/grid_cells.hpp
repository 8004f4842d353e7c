// Which contacts of a 3D frame lie in one cell of a k x k x k grid over its spheres' box, worked
// out on its own (not by common/analysis/blocks): the reference that places a planted change.
#pragma once

#include <cstddef>
#include <vector>

#include "common/topology/frame.hpp"

namespace fnet::testing {

// The contacts whose contact point (on the line of centres, r_i from grain i's centre) lies in cell
// (layer, row, col) at least `margin` inside its faces, in contact order.
std::vector<std::size_t> contacts_in_cell(const Frame& frame, int k, int layer, int row, int col, double margin);

// The frame with the forces of the first `count` of `contacts` changed unevenly (fn by 3 to 3.3,
// ft by 2), so that a cell's network is no uniformly scaled copy of itself.
Frame strengthen(const Frame& frame, const std::vector<std::size_t>& contacts, std::size_t count);

}  // namespace fnet::testing
