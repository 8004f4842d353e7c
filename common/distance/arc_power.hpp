// The cost of a Wasserstein-q arc from its L-infinity length: the one place the q-th power is taken.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace fnet {

// The cost of an arc of L-infinity length d: (d / unit)^q. Costs above kCap are capped: the caller
// picks the unit so that every arc of an optimal matching costs far less (wasserstein.cpp), so a
// capped arc is in no optimal matching, and the cap keeps the potentials, keys and bounds of the
// searches finite whatever q.
class ArcPower {
 public:
  static constexpr double kCap = 0x1p900;

  // q >= 1 and unit > 0, both finite.
  explicit ArcPower(double q, double unit = 1);

  double operator()(double length) const {
    if (kind_ == Kind::identity) return length;
    if (kind_ == Kind::square) return length * length;
    return std::min(kCap, std::pow(length / unit_, q_));
  }
  bool is_identity() const { return kind_ == Kind::identity; }  // the cost is the length itself
  bool is_plain() const { return kind_ != Kind::general; }      // q = 1 or 2 in unit 1: never capped

 private:
  // q = 1 and q = 2 in unit 1, the hot path, need neither the division nor the cap: their costs
  // never exceed the squared coordinate range.
  enum class Kind : std::uint8_t { identity, square, general };
  double q_, unit_;
  Kind kind_;
};

}  // namespace fnet
