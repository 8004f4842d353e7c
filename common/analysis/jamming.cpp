#include "common/analysis/jamming.hpp"

#include <cmath>
#include <stdexcept>

namespace fnet {

std::optional<double> jamming_density(std::span<const double> rho, std::span<const double> z, double z_c) {
  if (rho.size() != z.size()) throw std::invalid_argument("jamming_density: rho and z differ in length");
  std::optional<std::size_t> before;  // the last usable frame below z_c
  for (std::size_t k = 0; k < rho.size(); ++k) {
    if (!std::isfinite(rho[k]) || !std::isfinite(z[k])) continue;
    if (z[k] < z_c) {
      before = k;
      continue;
    }
    if (!before) return rho[k];
    const std::size_t b = *before;
    // z[b] < z_c <= z[k]: the denominator is positive.
    return rho[b] + (z_c - z[b]) * (rho[k] - rho[b]) / (z[k] - z[b]);
  }
  return std::nullopt;
}

}  // namespace fnet
