// Diagrams in which many points coincide (ties everywhere, a million copies of one point): the
// transport solved between the distinct points, each standing for its copies, on the complete
// graph of distinct pairs that beat the diagonal, by the network simplex with counts
// (network_simplex.hpp). Exact: copies of one point are interchangeable, so an optimal flow
// between the distinct points, split among the copies, is an optimal matching. Its certificate is
// the simplex's potentials made feasible over every pair and both hubs (each b's potential lowered
// to its least incoming arc), whose LP-dual bound is weighed by the counts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "common/distance/arc_power.hpp"
#include "common/distance/diagram_matching.hpp"
#include "common/distance/essential_convention.hpp"

namespace fnet {

struct DistinctPoints {
  std::vector<PlanePoint> points;      // each distinct point once
  std::vector<std::uint32_t> count;    // how many of the input's points sit there
  std::vector<std::uint32_t> members;  // the input's indices, grouped by distinct point
  std::vector<std::uint32_t> first;    // members[first[k] .. first[k + 1]) sit at points[k]
};
DistinctPoints distinct_points(std::span<const PlanePoint> points);

// How many distinct points there are (a hash count, cheaper than distinct_points' sort).
std::size_t count_distinct(std::span<const PlanePoint> points);

// The distinct solve is taken when the copies at least halve the points and the complete graph
// of distinct pairs has at most kMaxDistinctArcs arcs.
inline constexpr std::size_t kMaxDistinctArcs = std::size_t{1} << 22;
// Both sides non-empty, counted by count_distinct.
bool solve_distinct(std::span<const PlanePoint> a, std::span<const PlanePoint> b);

struct DistinctTransport {
  double cost = 0;  // sum of power(length) over the matching
  double dual = 0;  // its LP-dual lower bound
  std::size_t pivots = 0, pair_arcs = 0;
};
// builder (optional) receives the matching, input indices of both sides.
DistinctTransport distinct_transport(const DistinctPoints& a, const DistinctPoints& b, const ArcPower& power,
                                     MatchingBuilder* builder);

// The bottleneck distance between the same distinct points: the least candidate value r (a
// point's diagonal distance, or a pair's distance below both points' diagonal distances) at which
// every copy is matched by pairs and diagonal moves of length <= r, decided by a maximum flow with
// the counts as capacities (the diagonal as the two hubs above), bisected over the sorted
// candidates. Exact, no tolerance: the value is an input distance.
struct DistinctBottleneck {
  double value = 0;
  std::size_t flows = 0;  // maximum flows computed
};
// builder (optional) receives a matching whose longest term is the value.
DistinctBottleneck distinct_bottleneck(const DistinctPoints& a, const DistinctPoints& b, MatchingBuilder* builder);

}  // namespace fnet
