// Ensemble curves as the paper plots them (its Figs. 6-10): the distances between consecutive
// frames of many realizations, binned in the packing fraction, averaged over the realizations:
// per bin each realization's mean first, then the mean over the realizations and its standard
// error across them, the counts of realizations and of values, and the mean contact number Z; and
// the ratio curves d_B/d_W1, d_B/d_W2 as the ratio of the bin means.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace fnet {

// One frame of one realization: where it sits (rho, or rho - rho_J for curves against the jamming
// point), the value measured there, and the realization (run) it belongs to.
struct CurveSample {
  double rho = 0;
  double z = 0;
  double value = 0;     // +inf allowed (an infinite distance); NaN samples are passed over
  std::size_t run = 0;  // the realization: samples with the same index are one run's frames
};

// Bins of fixed width aligned on multiples of the width, so that a bin keeps its place while
// realizations go on adding frames; or `count` bins spanning the samples' range.
struct RhoBinning {
  double width = 0;       // > 0: fixed width
  std::size_t count = 0;  // > 0 (and width 0): that many bins over [min rho, max rho]
};

// A bin's numbers are means over its realizations of each realization's own mean over its samples
// in the bin, so that the consecutive, correlated frames of one run count once. Summation order,
// fixed so that a bin is the same number for the same samples: within a run its samples in the
// order given, then the runs in increasing run index.
struct CurveBin {
  double rho_lo = 0, rho_hi = 0;         // [rho_lo, rho_hi); the last bin of a count binning is closed
  double mean_rho = 0;                   // over the runs, of each run's mean rho in the bin
  double mean = 0;                       // over the runs, of each run's mean value (+inf if any run's is)
  std::optional<double> standard_error;  // sample standard deviation of the run means / sqrt(runs);
                                         // none for runs < 2 or an infinite mean
  std::size_t runs = 0;                  // realizations with a sample in the bin
  std::size_t n = 0;                     // samples in the bin
  double mean_z = 0;                     // over the runs, of each run's mean Z in the bin
};

// Bins holding at least one sample, in increasing rho. Throws std::invalid_argument unless exactly
// one of width, count is positive (and finite), or when a width is so fine that a sample's bin
// index does not fit 62 bits.
std::vector<CurveBin> bin_curve(std::span<const CurveSample> samples, const RhoBinning& binning);

// numerator / denominator bin by bin, for the bins both have (matched by their rho_lo): the ratio
// of the bin means, with runs and n the smaller of the two counts and no standard error. A
// denominator mean of 0 gives +inf (or NaN for 0/0).
std::vector<CurveBin> ratio_curve(std::span<const CurveBin> numerator, std::span<const CurveBin> denominator);

}  // namespace fnet
