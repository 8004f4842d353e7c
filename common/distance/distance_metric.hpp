// Which diagram distance to compute: the bottleneck distance d_B (the limit of d_Wq as q grows) or
// the Wasserstein distance d_Wq for a real q >= 1. A value of the maths only: names, parsing and
// keys belong to the interfaces that build one.
#pragma once

#include <cmath>
#include <limits>
#include <stdexcept>

namespace fnet {

struct DistanceMetric {
  enum class Kind { bottleneck, wasserstein };
  Kind kind = Kind::bottleneck;
  double q = std::numeric_limits<double>::infinity();  // the exponent; +inf for the bottleneck

  static constexpr DistanceMetric bottleneck() { return {}; }
  // Throws std::invalid_argument unless q is finite and >= 1 (the bottleneck is q = infinity).
  static DistanceMetric wasserstein(double q) {
    if (!std::isfinite(q) || q < 1)
      throw std::invalid_argument("Wasserstein exponent q must be a finite number >= 1 (the bottleneck is q = inf)");
    return {Kind::wasserstein, q};
  }

  bool is_bottleneck() const { return kind == Kind::bottleneck; }
  bool operator==(const DistanceMetric&) const = default;
};

}  // namespace fnet
