// Changes to a frame that must not change its diagrams (or change them by a known scale).
#pragma once

#include <random>

#include "common/topology/frame.hpp"

namespace fnet::testing {

Frame shuffled_rows(Frame frame, std::mt19937_64& rng);
Frame reversed_pairs(Frame frame);                    // every contact (i, j) written as (j, i)
Frame relabelled(Frame frame, std::mt19937_64& rng);  // particles renamed by a random permutation
Frame scaled(Frame frame, double factor);             // fn and ft multiplied by factor

}  // namespace fnet::testing
