#include "tests/support/diagram_match.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

namespace fnet::testing {
namespace {

bool close(double x, double y, double relative) {
  return std::fabs(x - y) <= relative * std::max(std::fabs(x), std::fabs(y));
}

bool close(const PersistencePoint& p, const PersistencePoint& q, double relative) {
  return close(p.birth, q.birth, relative) && close(p.death, q.death, relative);
}

void describe(std::ostringstream& s, const char* side, const Diagram& points) {
  s << "\n  only in " << side << " (" << points.size() << "):";
  for (std::size_t k = 0; k < points.size() && k < 12; ++k)
    s << " (" << points[k].birth << ", " << points[k].death << ")";
  if (points.size() > 12) s << " ...";
}

}  // namespace

std::string diagram_mismatch(const Diagram& a, const Diagram& b, double relative) {
  Diagram x = a, y = b;
  sort_canonical(x);
  sort_canonical(y);
  if (x.size() == y.size() &&
      std::equal(x.begin(), x.end(), y.begin(), [&](const auto& p, const auto& q) { return close(p, q, relative); }))
    return {};

  // Sorting may interleave points whose births differ by rounding only: match greedily within
  // the births' tolerance window instead.
  std::vector<char> used(y.size(), 0);
  Diagram only_x;
  for (const PersistencePoint& p : x) {
    const double slack = relative * std::fabs(p.birth);
    // y is in birth-descending order: the window starts at the first birth <= p.birth + slack.
    auto it =
        std::partition_point(y.begin(), y.end(), [&](const PersistencePoint& q) { return q.birth > p.birth + slack; });
    bool found = false;
    for (; it != y.end() && it->birth >= p.birth - slack - relative * std::fabs(it->birth); ++it) {
      const auto k = static_cast<std::size_t>(it - y.begin());
      if (!used[k] && close(p, *it, relative)) {
        used[k] = 1;
        found = true;
        break;
      }
    }
    if (!found) only_x.push_back(p);
  }
  Diagram only_y;
  for (std::size_t k = 0; k < y.size(); ++k)
    if (!used[k]) only_y.push_back(y[k]);
  if (only_x.empty() && only_y.empty()) return {};

  std::ostringstream s;
  s.precision(17);
  s << x.size() << " points against " << y.size();
  describe(s, "first", only_x);
  describe(s, "second", only_y);
  return s.str();
}

}  // namespace fnet::testing
