// Candidate pairs for the Wasserstein solver from the structure of force-network diagrams: under
// `floor` most of PD1's points are never-dying loops on one line death = floor, where the problem
// is one-dimensional and, for q >= 1, an optimal matching pairs points in sorted order. An
// edit-distance dynamic programme over both diagrams' points sorted by birth (match a_i with b_j at
// cost c_ij, or send either to the diagonal) finds that matching; off the line it is only a guess.
// It is banded around the quantile alignment (rank i of A against rank i m / n of B), which
// follows a whole diagram shifting or stretching, what defeats nearest-neighbour guesses. Its
// matched pairs and their neighbours in rank are the candidates; exactness never depends on
// them (the solver checks every pair afterwards).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

#include "common/distance/linf_kdtree.hpp"

namespace fnet {

// Pairs (i, j), i indexing a, j indexing b, possibly repeated. cost(i, j) is the pair's cost,
// da/db the costs to the diagonal. half_width: the band, in ranks either side of the quantile line
// (widened by |n - m|).
std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted_birth_candidates(
    std::span<const PlanePoint> a, std::span<const PlanePoint> b, std::span<const double> da,
    std::span<const double> db, const std::function<double(std::uint32_t, std::uint32_t)>& cost,
    std::uint32_t half_width = 32);

// The scale between two diagrams (forces are in units of their frame's mean, which moves from
// frame to frame): the median ratio of births at equal quantiles, 1 when there is none.
double quantile_scale(std::span<const PlanePoint> a, std::span<const PlanePoint> b);

// The share of all points of a and b lying on the line death = y that most of them share: what
// the programme can order (floor PD1s of force networks: ~0.9; random diagrams: little).
double share_on_common_line(std::span<const PlanePoint> a, std::span<const PlanePoint> b);

}  // namespace fnet
