// Which points can ever be matched together. A pair (a, b) is in an optimal matching only if it
// beats sending both to the diagonal (c(a, b) < c(a, diagonal) + c(b, diagonal); TTK's rule), and
// under L-infinity c(a, b) >= |s_a - s_b| / 2 with s = birth + death (the position along the
// diagonal) while a point's way to the diagonal has length l = |birth - death| / 2; for every
// q >= 1 a useful pair therefore has |s_a - s_b| < 2 l_a + 2 l_b: the intervals
// [s - 2 l, s + 2 l] of the two points overlap. Points whose intervals chain together form a
// diagonal component; points of different components are never matched together, so each
// component is a problem of its own (diagrams offset or stacked along the diagonal split into
// many; one frame's diagram is mostly one).
#pragma once

#include <cstddef>
#include <span>

#include "common/distance/essential_convention.hpp"

namespace fnet {

// The number of points (of a and b together) in the largest diagonal component.
std::size_t largest_diagonal_component(std::span<const PlanePoint> a, std::span<const PlanePoint> b);

}  // namespace fnet
