// Bottleneck distance between persistence diagrams: L-infinity ground metric, any point may go to
// the diagonal at (birth - death) / 2. Exact by default; optionally a certified relative error.
#pragma once

#include "common/distance/diagram_matching.hpp"
#include "common/distance/distance_result.hpp"
#include "common/distance/essential_convention.hpp"
#include "common/topology/diagram.hpp"

namespace fnet {

struct BottleneckParams {
  EssentialConvention essential = EssentialConvention::floor;
  // 0: exact. e > 0: stop once upper <= (1 + e) * lower; value = upper, the bottleneck of an
  // actual matching.
  double relative_error = 0;
};

// The answer is the smallest r at which a matching covers every point farther than r from the
// diagonal using pairs at distance <= r; it is a candidate value (a pair's distance or a point's
// diagonal distance). Each test of r starts from the matching of the last test (or a sorted sweep
// of the line death = 0) and augments by Hopcroft-Karp phases on 2-d trees with deletion
// (Efrat-Itai-Katz, as in Hera). r is bisected over the bit patterns of doubles until few
// candidates remain in the bracket, then over those candidates, and snapped down to the value of
// each matching found, so the result is an exact input distance with no tolerance anywhere
// (hence exactly scale-invariant under multiplication by powers of two, and to rounding
// otherwise).
//
// matching (optional): receives a matching whose longest term is the value exactly (with a
// relative error, the matching whose bottleneck is the value returned); its `longest` is an
// attaining term. Empty when the distance is infinite.
DistanceResult bottleneck_distance(const Diagram& a, const Diagram& b, const BottleneckParams& params = {},
                                   DiagramMatching* matching = nullptr);

}  // namespace fnet
