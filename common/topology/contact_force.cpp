#include "common/topology/contact_force.hpp"

#include <cmath>
#include <limits>

namespace fnet {

namespace {

// A part this small beside the whole force is the split's rounding (a few ulps of |F|), not a
// force: a purely normal force must give ft = 0, as its magnitudes would, or the contact would
// become an edge of the tangential network.
constexpr double kRounding = 16 * std::numeric_limits<double>::epsilon();

}  // namespace

ContactForceParts split_contact_force(const std::array<double, 3>& offset, const std::array<double, 3>& force) {
  const double magnitude = std::hypot(force[0], force[1], force[2]);
  const double length = std::hypot(offset[0], offset[1], offset[2]);
  if (!(length > 0)) return {0.0, magnitude};
  const std::array<double, 3> n{offset[0] / length, offset[1] / length, offset[2] / length};
  double fn = force[0] * n[0] + force[1] * n[1] + force[2] * n[2];
  double ft = std::hypot(force[0] - fn * n[0], force[1] - fn * n[1], force[2] - fn * n[2]);
  if (std::abs(fn) <= kRounding * magnitude) fn = 0;
  if (ft <= kRounding * magnitude) ft = 0;
  return {fn, ft};
}

}  // namespace fnet
