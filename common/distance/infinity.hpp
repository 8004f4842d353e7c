// +infinity: the cost of a pair no search may take, a distance no matching attains.
#pragma once

#include <limits>

namespace fnet {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace fnet
