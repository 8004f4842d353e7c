#include "tests/support/random_forces.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace fnet::testing {
namespace {

double jitter(double value, int ulps, std::mt19937_64& rng) {
  const int steps = std::uniform_int_distribution<int>(-ulps, ulps)(rng);
  for (int k = 0; k < std::abs(steps); ++k) value = std::nextafter(value, steps > 0 ? 1e300 : 0.0);
  return value;
}

double draw_force(const ForceStyle& style, std::mt19937_64& rng) {
  if (std::bernoulli_distribution(style.zero_probability)(rng)) return 0.0;
  double value = 0;
  if (style.distinct > 0)
    value = static_cast<double>(std::uniform_int_distribution<std::size_t>(1, style.distinct)(rng));
  else  // spread over three decades, like contact forces around and after jamming
    value = std::exp(std::uniform_real_distribution<double>(-3.0, 4.0)(rng));
  return jitter(value, style.ulp_jitter, rng);
}

}  // namespace

Frame frame_from_graph(const Graph& graph, const ForceStyle& style, std::size_t rattlers, std::mt19937_64& rng) {
  Frame frame;
  frame.label = "random frame";
  frame.particle_count = graph.vertex_count + rattlers;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (std::size_t k = 0; k < frame.particle_count; ++k)
    frame.particles.push_back({10 * unit(rng), 10 * unit(rng), 0.4 + 0.2 * unit(rng)});
  for (const auto& [u, v] : graph.edges) {
    Contact c{u, v, draw_force(style, rng), draw_force(style, rng)};
    if (std::bernoulli_distribution(style.negative_probability)(rng)) c.fn = -c.fn;
    if (std::bernoulli_distribution(0.5)(rng)) std::swap(c.i, c.j);
    frame.contacts.push_back(c);
  }
  std::shuffle(frame.contacts.begin(), frame.contacts.end(), rng);
  return frame;
}

ForceStyle random_style(std::mt19937_64& rng) {
  switch (std::uniform_int_distribution<int>(0, 6)(rng)) {
    case 0:
      return {};
    case 1:
      return {2, 0, 0, 0};
    case 2:
      return {3, 0.1, 0.2, 0};
    case 3:
      return {1, 0, 0, 0};  // a single distinct value
    case 4:
      return {0, 0.3, 0, 0};
    case 5:
      return {2, 0, 0, 2};  // near-ties
    default:
      return {0, 0.05, 0.4, 0};
  }
}

}  // namespace fnet::testing
