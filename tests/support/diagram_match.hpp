// Comparing two persistence diagrams as multisets of points, up to rounding.
#pragma once

#include <bit>
#include <cstdint>
#include <string>

#include "common/topology/diagram.hpp"

namespace fnet::testing {

// Empty when every point of `a` pairs with its own point of `b` with both coordinates equal
// within `relative` (|x - y| <= relative * max(|x|, |y|)); otherwise a report naming the counts
// and the first unmatched points of each side, for a failure message that can be acted on.
std::string diagram_mismatch(const Diagram& a, const Diagram& b, double relative);

// The same points in the same order, bit for bit (so that -0.0 and 0.0 differ).
inline bool bit_identical(const Diagram& a, const Diagram& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k)
    if (std::bit_cast<std::uint64_t>(a[k].birth) != std::bit_cast<std::uint64_t>(b[k].birth) ||
        std::bit_cast<std::uint64_t>(a[k].death) != std::bit_cast<std::uint64_t>(b[k].death))
      return false;
  return true;
}

}  // namespace fnet::testing
