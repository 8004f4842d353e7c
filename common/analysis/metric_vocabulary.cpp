#include "common/analysis/metric_vocabulary.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace fnet {
namespace {

std::string format_q(double q) {
  std::ostringstream s;
  s.precision(17);
  s << q;
  return s.str();
}

}  // namespace

DistanceMetric MetricChoice::distance() const {
  return q ? DistanceMetric::wasserstein(*q) : DistanceMetric::bottleneck();
}

std::string MetricChoice::label() const {
  if (name == "wasserstein" && q) return "wasserstein q=" + format_q(*q);
  return name;
}

MetricChoice parse_metric(std::string_view name, std::optional<double> q) {
  MetricChoice m{std::string(name), q, std::nullopt};
  if (name == "bottleneck") {
    if (q)
      throw std::invalid_argument("q = " + format_q(*q) +
                                  " does not apply to metric 'bottleneck' (it is the limit q = infinity); "
                                  "use metric 'wasserstein' with q");
    m.stored = Metric::bottleneck;
    return m;
  }
  if (name == "wasserstein1" || name == "wasserstein2") {
    const double own = name == "wasserstein1" ? 1 : 2;
    if (q && *q != own)
      throw std::invalid_argument("q = " + format_q(*q) + " contradicts metric '" + m.name + "' (q = " + format_q(own) +
                                  ")");
    m.q = own;
    m.stored = own == 1 ? Metric::wasserstein1 : Metric::wasserstein2;
    return m;
  }
  if (name == "wasserstein") {
    if (!q) throw std::invalid_argument("metric 'wasserstein' needs q, a real number >= 1");
    if (!std::isfinite(*q) || *q < 1)
      throw std::invalid_argument("q must be a finite real number >= 1 (got " + format_q(*q) +
                                  "); q = infinity is metric 'bottleneck'");
    if (*q == 1) m.stored = Metric::wasserstein1;
    if (*q == 2) m.stored = Metric::wasserstein2;
    return m;
  }
  throw std::invalid_argument("unknown metric '" + m.name +
                              "' (expected bottleneck, wasserstein1, wasserstein2 or wasserstein)");
}

int check_dim(long long dim) {
  if (dim != 0 && dim != 1)
    throw std::invalid_argument("dim must be 0 (components) or 1 (loops), got " + std::to_string(dim));
  return static_cast<int>(dim);
}

DistanceResult choice_distance(const Diagram& a, const Diagram& b, const MetricChoice& metric,
                               EssentialConvention essential, double delta) {
  return diagram_distance(a, b, metric.distance(), essential, delta);
}

}  // namespace fnet
