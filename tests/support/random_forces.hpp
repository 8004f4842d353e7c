// Frames from contact graphs: force values drawn to stress ties, zeros and signs, rows shuffled.
#pragma once

#include <cstddef>
#include <random>
#include <vector>

#include "common/topology/frame.hpp"
#include "tests/support/contact_graphs.hpp"

namespace fnet::testing {

struct ForceStyle {
  // Values come from {1, 2, ..., distinct} (many ties) when distinct > 0, else from a continuous range.
  std::size_t distinct = 0;
  double zero_probability = 0;      // each of fn, ft is exactly 0 (so not an edge) with this probability
  double negative_probability = 0;  // fn is negated (tensile) with this probability
  // Each value is moved by up to this many ulps, so that near-ties differ only in the last bits
  // (a sort that looked at fewer bits than the whole double would misorder them).
  int ulp_jitter = 0;
};

// One contact per graph edge with independent fn and ft; rows in random order, each pair
// written (i, j) or (j, i) at random; `rattlers` extra particles without contacts; a particle
// table with positive radii.
Frame frame_from_graph(const Graph& graph, const ForceStyle& style, std::size_t rattlers, std::mt19937_64& rng);

// A style drawn at random among: continuous, tiny tie sets, a single value, near-ties, with zeros,
// with negatives.
ForceStyle random_style(std::mt19937_64& rng);

}  // namespace fnet::testing
