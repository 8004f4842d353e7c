#include "common/analysis/ensemble_curve.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace fnet {
namespace {

// One run's samples in a bin, summed in the order given.
struct RunSums {
  double rho = 0, z = 0, value = 0;
  std::size_t n = 0;
};

// Each run's means first (the map keeps the runs in increasing index), then their mean and, in a
// second pass over the run means, their squared deviations, which keeps the variance accurate
// when the means are large and close together.
CurveBin summarize(std::span<const CurveSample> samples, const std::vector<std::size_t>& members, double lo,
                   double hi) {
  std::map<std::size_t, RunSums> by_run;
  for (const std::size_t k : members) {
    RunSums& r = by_run[samples[k].run];
    r.rho += samples[k].rho;
    r.z += samples[k].z;
    r.value += samples[k].value;
    ++r.n;
  }
  CurveBin bin;
  bin.rho_lo = lo;
  bin.rho_hi = hi;
  bin.n = members.size();
  bin.runs = by_run.size();
  std::vector<double> means;
  means.reserve(by_run.size());
  double rho = 0, z = 0, value = 0;
  for (const auto& [run, r] : by_run) {
    const double n = static_cast<double>(r.n);
    rho += r.rho / n;
    z += r.z / n;
    means.push_back(r.value / n);
    value += means.back();
  }
  const double runs = static_cast<double>(bin.runs);
  bin.mean_rho = rho / runs;
  bin.mean_z = z / runs;
  bin.mean = value / runs;
  if (bin.runs >= 2 && std::isfinite(bin.mean)) {
    double squares = 0;
    for (const double m : means) squares += (m - bin.mean) * (m - bin.mean);
    bin.standard_error = std::sqrt(squares / (runs - 1)) / std::sqrt(runs);
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
    const auto edge = [&](std::int64_t index) { return static_cast<double>(index) * binning.width; };
    for (const std::size_t k : usable) {
      const double rho = samples[k].rho;
      const double guess = std::floor(rho / binning.width);
      if (!(std::abs(guess) < kIndexLimit))
        throw std::invalid_argument("bin width too fine for the samples: a bin index leaves 64 bits");
      // rho / width is rounded: near a multiple of the width the floor can be one off. The bin is
      // the one whose reported edges hold rho, edge(index) <= rho < edge(index + 1).
      auto index = static_cast<std::int64_t>(guess);
      if (rho < edge(index)) --index;
      if (rho >= edge(index + 1)) ++index;
      bins[index].push_back(k);
    }
    for (const auto& [index, members] : bins) out.push_back(summarize(samples, members, edge(index), edge(index + 1)));
    return out;
  }
  const auto [lo_it, hi_it] = std::minmax_element(
      usable.begin(), usable.end(), [&](std::size_t a, std::size_t b) { return samples[a].rho < samples[b].rho; });
  const double lo = samples[*lo_it].rho, hi = samples[*hi_it].rho;
  const double width = (hi - lo) / static_cast<double>(binning.count);
  const auto last = static_cast<std::int64_t>(binning.count) - 1;
  const auto edge = [&](std::int64_t index) { return index > last ? hi : lo + static_cast<double>(index) * width; };
  for (const std::size_t k : usable) {
    const double rho = samples[k].rho;
    std::int64_t index = 0;  // all samples at one rho (width 0): one bin
    if (width > 0) {
      index = std::min(last, static_cast<std::int64_t>(std::floor((rho - lo) / width)));
      // As for a width: the bin whose reported edges hold rho (the last one closed at hi).
      if (index > 0 && rho < edge(index)) --index;
      if (index < last && rho >= edge(index + 1)) ++index;
    }
    bins[index].push_back(k);
  }
  for (const auto& [index, members] : bins) out.push_back(summarize(samples, members, edge(index), edge(index + 1)));
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
    r.runs = std::min(a.runs, b->runs);
    r.n = std::min(a.n, b->n);
    out.push_back(r);
  }
  return out;
}

}  // namespace fnet
