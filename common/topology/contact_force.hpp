// A contact's force split along the line of centres: what a frame's contact holds (fn, ft) from
// the force vector an engine or an experiment reports. One place for every reader of vectors: the
// LAMMPS pair dumps (server/sources) and the frame CSV's fx,fy form (common/codec).
#pragma once

#include <array>

namespace fnet {

struct ContactForceParts {
  double fn = 0;  // signed: > 0 pushes grain i away from grain j (compression)
  double ft = 0;  // the magnitude of the rest, >= 0
};

// The force `force` on grain i from grain j, split along the line of centres `offset` = x_i - x_j
// (2D vectors have z = 0): fn = F·n with n = offset / |offset|, ft = |F - fn n|; a part within
// the split's rounding of 0 (16 ε |F|, ε the double's epsilon) is 0. Grains at one place have no
// line of centres: fn = 0 and ft = |F|.
ContactForceParts split_contact_force(const std::array<double, 3>& offset, const std::array<double, 3>& force);

}  // namespace fnet
