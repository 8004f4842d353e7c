// What every diagram distance returns: the value with certified bounds, or +inf with the reason.
#pragma once

#include <string>

namespace fnet {

struct DistanceResult {
  double value = 0;   // the distance; +inf when the diagrams cannot be matched (see reason)
  double lower = 0;   // certified: lower <= true distance <= upper
  double upper = 0;   // value == upper in approximate mode (the cost of an actual matching)
  bool exact = true;  // lower == value == upper
  bool infinite = false;
  std::string reason;  // why the distance is infinite; empty otherwise
};

}  // namespace fnet
