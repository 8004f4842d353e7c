#include "common/distance/diagonal_components.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace fnet {

std::size_t largest_diagonal_component(std::span<const PlanePoint> a, std::span<const PlanePoint> b) {
  std::vector<std::pair<double, double>> intervals;  // [s - 2 l, s + 2 l], by start
  intervals.reserve(a.size() + b.size());
  for (const auto side : {a, b})
    for (const PlanePoint p : side) {
      const double s = p.x + p.y, reach = std::fabs(p.x - p.y);  // 2 l
      intervals.push_back({s - reach, s + reach});
    }
  std::sort(intervals.begin(), intervals.end());
  std::size_t largest = 0, run = 0;
  double end = 0;
  for (const auto& [lo, hi] : intervals) {
    if (run > 0 && lo < end) {
      ++run;
      end = std::max(end, hi);
    } else {
      run = 1;
      end = hi;
    }
    largest = std::max(largest, run);
  }
  return largest;
}

}  // namespace fnet
