#include "common/analysis/explain.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "common/distance/bottleneck.hpp"
#include "common/distance/diagram_matching.hpp"
#include "common/distance/wasserstein.hpp"
#include "common/topology/persistence.hpp"

namespace fnet {
namespace {

ExplainedSimplex grains_of(const Simplex& s, const Frame& frame) {
  ExplainedSimplex out;
  out.dimension = frame.dimension;
  for (std::size_t k = 0; k < s.size; ++k) {
    const std::uint32_t v = s.vertices[k];
    out.grains.push_back(v);
    if (!frame.particles.empty()) {
      const Particle& p = frame.particles[v];
      out.positions.push_back({p.x, p.y, p.z});
    }
  }
  return out;
}

std::optional<ExplainedPoint> point_of(std::int64_t index, const Diagram& diagram,
                                       const std::vector<PointSimplices>& simplices, const Frame& frame) {
  if (index < 0) return std::nullopt;
  const auto k = static_cast<std::size_t>(index);
  ExplainedPoint p{diagram[k], grains_of(simplices[k].birth, frame), std::nullopt};
  if (simplices[k].death.size > 0) p.death_simplex = grains_of(simplices[k].death, frame);
  return p;
}

}  // namespace

Explanation explain(const Frame& a, const Frame& b, const ExplainRequest& request) {
  if (request.dim != 0 && request.dim != 1) throw std::invalid_argument("explain: dim must be 0 or 1");
  if (request.k < 1) throw std::invalid_argument("explain: k must be at least 1");
  validate(a);
  validate(b);
  const PairedDiagrams pa = compute_persistence_pairs(build_network(a, request.force));
  const PairedDiagrams pb = compute_persistence_pairs(build_network(b, request.force));
  const Diagram& da = request.dim == 0 ? pa.diagrams.pd0 : pa.diagrams.pd1;
  const Diagram& db = request.dim == 0 ? pb.diagrams.pd0 : pb.diagrams.pd1;
  const auto& sa = request.dim == 0 ? pa.pd0 : pa.pd1;
  const auto& sb = request.dim == 0 ? pb.pd0 : pb.pd1;

  Explanation out;
  DiagramMatching matching;
  out.distance =
      request.metric.is_bottleneck()
          ? bottleneck_distance(da, db, {.essential = request.essential}, &matching)
          : wasserstein_distance(da, db, {.q = request.metric.q, .essential = request.essential}, nullptr, &matching);
  // Longest first; the attaining term of d_B ahead of any other of the same length.
  std::vector<std::size_t> order(matching.pairs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    const double lx = matching.pairs[x].length, ly = matching.pairs[y].length;
    if (lx != ly) return lx > ly;
    return x == matching.longest && y != matching.longest;
  });
  for (const std::size_t t : order) {
    const MatchedPair& term = matching.pairs[t];
    if (out.terms.size() == request.k || !(term.length > 0)) break;
    out.terms.push_back({out.terms.size() + 1, term.length, point_of(term.a, da, sa, a), point_of(term.b, db, sb, b)});
  }
  return out;
}

}  // namespace fnet
