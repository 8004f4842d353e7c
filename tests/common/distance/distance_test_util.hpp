// Small shared pieces of the distance tests.
#pragma once

#include <cmath>
#include <string>

#include "common/distance/bottleneck.hpp"
#include "common/distance/wasserstein.hpp"

namespace fnet::test {

// q == 0: bottleneck.
inline DistanceResult distance(const Diagram& a, const Diagram& b, double q, EssentialConvention c, double delta = 0) {
  if (q == 0) return bottleneck_distance(a, b, {.essential = c, .relative_error = delta});
  return wasserstein_distance(a, b, {.q = q, .essential = c, .delta = delta});
}

inline bool close(double x, double y, double rel) {
  if (std::isinf(x) || std::isinf(y)) return x == y;
  return std::fabs(x - y) <= rel * std::max({std::fabs(x), std::fabs(y), 1e-300});
}

inline std::string label(double q, EssentialConvention c) {
  std::string out = q == 0 ? "bottleneck" : "W";
  if (q != 0) out.append(std::to_string(q));
  out.append("/").append(to_string(c));
  return out;
}

}  // namespace fnet::test
