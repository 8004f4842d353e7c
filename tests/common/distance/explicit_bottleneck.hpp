// The bottleneck distance checked from its definition at sizes brute force cannot reach, with
// nothing shared with common/distance but the plane points: the graph of pairs within a
// threshold is built explicitly (a sweep over points sorted by birth) and its matchings found
// by a plain Hopcroft-Karp.
#pragma once

#include <vector>

#include "common/distance/essential_convention.hpp"

namespace fnet::test {

// Is there a matching with every pair at L-infinity distance <= r that leaves unmatched only
// points within r of the diagonal? By Mendelsohn-Dulmage: iff one matching covers the points
// of a farther than r from the diagonal and another those of b.
bool explicit_bottleneck_feasible(const std::vector<PlanePoint>& a, const std::vector<PlanePoint>& b, double r);

// The distance is the smallest candidate value (a pair's L-infinity distance or a point's
// diagonal distance) at which a matching exists.
struct BottleneckCheck {
  bool is_candidate = false;      // value is a candidate
  bool feasible = false;          // a matching exists at value
  bool below_infeasible = false;  // none at the largest candidate below value (true if none)
  double below = -1;              // that candidate, -1 if none
};
BottleneckCheck check_bottleneck(const std::vector<PlanePoint>& a, const std::vector<PlanePoint>& b, double value);

}  // namespace fnet::test
