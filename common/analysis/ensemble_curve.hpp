// Ensemble curves as the paper plots them (its Figs. 6-10): the distances between consecutive
// frames of many realizations, binned in the packing fraction, per bin the mean, its standard
// error, the number of values and the mean contact number Z; and the ratio curves d_B/d_W1,
// d_B/d_W2 as the ratio of the bin means.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace fnet {

// One frame of one realization: where it sits (rho, or rho - rho_J for curves against the jamming
// point) and the value measured there.
struct CurveSample {
  double rho = 0;
  double z = 0;
  double value = 0;  // +inf allowed (an infinite distance); NaN samples are passed over
};

// Bins of fixed width aligned on multiples of the width, so that a bin keeps its place while
// realizations go on adding frames; or `count` bins spanning the samples' range.
struct RhoBinning {
  double width = 0;       // > 0: fixed width
  std::size_t count = 0;  // > 0 (and width 0): that many bins over [min rho, max rho]
};

struct CurveBin {
  double rho_lo = 0, rho_hi = 0;         // [rho_lo, rho_hi); the last bin of a count binning is closed
  double mean_rho = 0;                   // of the samples in the bin
  double mean = 0;                       // of their values (+inf if any is)
  std::optional<double> standard_error;  // sample standard deviation / sqrt(n); none for n < 2 or inf
  std::size_t n = 0;
  double mean_z = 0;
};

// Bins holding at least one sample, in increasing rho. Throws std::invalid_argument unless exactly
// one of width, count is positive (and finite), or when a width is so fine that a sample's bin
// index does not fit 62 bits.
std::vector<CurveBin> bin_curve(std::span<const CurveSample> samples, const RhoBinning& binning);

// numerator / denominator bin by bin, for the bins both have (matched by their rho_lo): the ratio
// of the bin means, with n the smaller of the two counts and no standard error. A denominator
// mean of 0 gives +inf (or NaN for 0/0).
std::vector<CurveBin> ratio_curve(std::span<const CurveBin> numerator, std::span<const CurveBin> denominator);

}  // namespace fnet
