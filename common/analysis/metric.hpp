// The distances fnet stores for every pair of consecutive frames, and the two force networks.
#pragma once

#include <array>
#include <string_view>

#include "common/topology/force_network.hpp"

namespace fnet {

enum class Metric { bottleneck, wasserstein1, wasserstein2 };
inline constexpr std::array<Metric, 3> kMetrics{Metric::bottleneck, Metric::wasserstein1, Metric::wasserstein2};
inline constexpr std::array<ForceKind, 2> kForces{ForceKind::normal, ForceKind::tangential};

std::string_view to_string(Metric metric);

}  // namespace fnet
