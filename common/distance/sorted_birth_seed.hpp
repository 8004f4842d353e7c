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

// The programme's answer over the points of the common line: a monotone alignment, as moves from
// (0, 0) to (|order_a|, |order_b|) in ranks of the line's points by birth.
struct LineAlignment {
  enum class Step : std::uint8_t { pair, delete_a, delete_b };
  struct Move {
    Step step;
    // pair: the two ranks matched; delete_a: the rank of A sent to the diagonal and the count of B's
    // ranks consumed before it; delete_b: the count of A's ranks consumed and the rank of B.
    std::uint32_t rank_a, rank_b;
  };
  double line = 0;                              // the common death value
  std::vector<std::uint32_t> order_a, order_b;  // indices into a and b of the line's points, by birth
  std::vector<Move> moves;
  // The band held the programme's optimum, which for q >= 1 is the optimal matching of the line's
  // points alone (its pairs may still cost more than sending both to the diagonal: the caller checks).
  bool optimal = false;
};

// half_width: the band, in ranks either side of the quantile line (widened by |n - m|); the solver
// passes DiagonalFlowParams::band. cost(i, j) is the pair's cost, da/db the costs to the diagonal.
LineAlignment sorted_birth_alignment(std::span<const PlanePoint> a, std::span<const PlanePoint> b,
                                     std::span<const double> da, std::span<const double> db,
                                     const std::function<double(std::uint32_t, std::uint32_t)>& cost,
                                     std::uint32_t half_width);

// Candidate pairs (i, j), i indexing a, j indexing b, possibly repeated: each matched pair and its
// neighbours in rank.
std::vector<std::pair<std::uint32_t, std::uint32_t>> alignment_candidates(const LineAlignment& alignment);

// The two above in one call.
std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted_birth_candidates(
    std::span<const PlanePoint> a, std::span<const PlanePoint> b, std::span<const double> da,
    std::span<const double> db, const std::function<double(std::uint32_t, std::uint32_t)>& cost,
    std::uint32_t half_width);

// The scale between two diagrams (forces are in units of their frame's mean, which moves from
// frame to frame): the median ratio of births at equal quantiles, 1 when there is none.
double quantile_scale(std::span<const PlanePoint> a, std::span<const PlanePoint> b);

// The share of all points of a and b lying on the line death = y that most of them share: what
// the programme can order (floor PD1s of force networks: ~0.9; random diagrams: little).
double share_on_common_line(std::span<const PlanePoint> a, std::span<const PlanePoint> b);

}  // namespace fnet
