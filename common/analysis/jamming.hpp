// The jamming point of a compression as the paper locates it: the packing fraction where the mean
// contact number Z first reaches 3 (frictional disks; frictionless ones jam later, at larger rho,
// and are compared against rho - rho_J).
#pragma once

#include <optional>
#include <span>

namespace fnet {

inline constexpr double kJammingContactNumber = 3;

// Frames in index order. The rho where Z first reaches z_c, linearly interpolated between that
// frame and the one before it; the first frame's rho when Z already reaches z_c there; none when
// Z never does. Frames with a non-finite rho or Z are passed over. The spans have equal length.
std::optional<double> jamming_density(std::span<const double> rho, std::span<const double> z,
                                      double z_c = kJammingContactNumber);

}  // namespace fnet
