// Comparing two persistence diagrams as multisets of points, up to rounding.
#pragma once

#include <string>

#include "common/topology/diagram.hpp"

namespace fnet::testing {

// Empty when every point of `a` pairs with its own point of `b` with both coordinates equal
// within `relative` (|x - y| <= relative * max(|x|, |y|)); otherwise a report naming the counts
// and the first unmatched points of each side, for a failure message that can be acted on.
std::string diagram_mismatch(const Diagram& a, const Diagram& b, double relative);

}  // namespace fnet::testing
