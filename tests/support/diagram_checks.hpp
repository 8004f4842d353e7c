// Assertions shared by the persistence tests: fast path vs reference, and diagrams up to a tolerance.
#pragma once

#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "common/topology/diagram.hpp"
#include "common/topology/force_network.hpp"
#include "common/topology/frame.hpp"
#include "common/topology/persistence.hpp"

namespace fnet {
// GoogleTest prints diagrams through this instead of raw bytes.
void PrintTo(const PersistencePoint& point, std::ostream* out);
}  // namespace fnet

namespace fnet::testing {

// The frame as CSV-like text, enough to rebuild a failing case by hand.
std::string describe(const Frame& frame);
std::string describe(const Diagram& diagram);

FrameDiagrams fast_path(const Frame& frame, ForceKind kind);

// The fast path and the reference agree: mean force to 1e-15 relative; then, normalized by the
// same mean, bit-identical diagrams and the same simplex counts.
::testing::AssertionResult matches_reference(const Frame& frame, ForceKind kind);

// Same points, in order, with |a - b| <= tolerance * max(|a|, |b|) per coordinate (-1 deaths exact).
::testing::AssertionResult nearly_equal(const Diagram& a, const Diagram& b, double tolerance);

}  // namespace fnet::testing
