#include "common/distance/arc_power.hpp"

#include <stdexcept>

namespace fnet {

ArcPower::ArcPower(double q, double unit) : q_(q), unit_(unit) {
  if (!std::isfinite(q) || q < 1) throw std::invalid_argument("arc power: q must be finite and >= 1");
  if (!std::isfinite(unit) || !(unit > 0)) throw std::invalid_argument("arc power: unit must be finite and > 0");
  kind_ = unit != 1 ? Kind::general : q == 1 ? Kind::identity : q == 2 ? Kind::square : Kind::general;
}

}  // namespace fnet
