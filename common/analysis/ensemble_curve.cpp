#include "common/analysis/ensemble_curve.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace fnet {
namespace {

// Two passes over the bin's samples: the mean first, then the squared deviations from it, which
// keeps the variance accurate when the values are large and close together.
CurveBin summarize(std::span<const CurveSample> samples, const std::vector<std::size_t>& members, double lo,
                   double hi) {
  CurveBin bin;
  bin.rho_lo = lo;
  bin.rho_hi = hi;
  bin.n = members.size();
  double rho = 0, z = 0, value = 0;
  for (const std::size_t k : members) {
    rho += samples[k].rho;
    z += samples[k].z;
    value += samples[k].value;
  }
  const double n = static_cast<double>(bin.n);
  bin.mean_rho = rho / n;
  bin.mean_z = z / n;
  bin.mean = value / n;
  if (bin.n >= 2 && std::isfinite(bin.mean)) {
    double squares = 0;
    for (const std::size_t k : members) squares += (samples[k].value - bin.mean) * (samples[k].value - bin.mean);
    bin.standard_error = std::sqrt(squares / (n - 1)) / std::sqrt(n);
  }
  return bin;
}

}  // namespace

std::vector<CurveBin> bin_curve(std::span<const CurveSample> samples, const RhoBinning& binning) {
  const bool by_width = binning.width > 0 && std::isfinite(binning.width);
  if (by_width == (binning.count > 0) || (binning.width != 0 && !by_width))
    throw std::invalid_argument("give a positive, finite bin width or a positive bin count, not both");
  std::vector<std::size_t> usable;
  for (std::size_t k = 0; k < samples.size(); ++k)
    if (std::isfinite(samples[k].rho) && std::isfinite(samples[k].z) && !std::isnan(samples[k].value))
      usable.push_back(k);
  std::vector<CurveBin> out;
  if (usable.empty()) return out;

  std::map<std::int64_t, std::vector<std::size_t>> bins;
  if (by_width) {
    // Converting a double beyond 64 bits to an integer is undefined: refuse such a width instead.
    constexpr double kIndexLimit = 0x1p62;
    for (const std::size_t k : usable) {
      const double index = std::floor(samples[k].rho / binning.width);
      if (!(std::abs(index) < kIndexLimit))
        throw std::invalid_argument("bin width too fine for the samples: a bin index leaves 64 bits");
      bins[static_cast<std::int64_t>(index)].push_back(k);
    }
    for (const auto& [index, members] : bins)
      out.push_back(summarize(samples, members, static_cast<double>(index) * binning.width,
                              static_cast<double>(index + 1) * binning.width));
    return out;
  }
  const auto [lo_it, hi_it] = std::minmax_element(
      usable.begin(), usable.end(), [&](std::size_t a, std::size_t b) { return samples[a].rho < samples[b].rho; });
  const double lo = samples[*lo_it].rho, hi = samples[*hi_it].rho;
  const double width = (hi - lo) / static_cast<double>(binning.count);
  const auto last = static_cast<std::int64_t>(binning.count) - 1;
  for (const std::size_t k : usable) {
    const std::int64_t index =
        width > 0 ? std::min(last, static_cast<std::int64_t>(std::floor((samples[k].rho - lo) / width))) : 0;
    bins[index].push_back(k);
  }
  for (const auto& [index, members] : bins) {
    const double b_lo = lo + static_cast<double>(index) * width;
    const double b_hi = index == last ? hi : lo + static_cast<double>(index + 1) * width;
    out.push_back(summarize(samples, members, b_lo, b_hi));
  }
  return out;
}

std::vector<CurveBin> ratio_curve(std::span<const CurveBin> numerator, std::span<const CurveBin> denominator) {
  std::vector<CurveBin> out;
  for (const CurveBin& a : numerator) {
    const auto b =
        std::find_if(denominator.begin(), denominator.end(), [&](const CurveBin& d) { return d.rho_lo == a.rho_lo; });
    if (b == denominator.end()) continue;
    CurveBin r = a;
    r.mean = a.mean / b->mean;
    r.standard_error.reset();
    r.n = std::min(a.n, b->n);
    out.push_back(r);
  }
  return out;
}

}  // namespace fnet
