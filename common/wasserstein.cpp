#include "common/wasserstein.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/diagonal_flow.hpp"
#include "common/linf_kdtree.hpp"

namespace fnet {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxRounds = 12;  // then every pair that can help is added: bounded time
constexpr std::size_t kViolationsPerRow = 8;

struct Power {
  double q;
  double operator()(double x) const { return q == 1 ? x : q == 2 ? x * x : std::pow(x, q); }
};

// For each node of the tree, the max over its points of value[point].
std::vector<double> node_maxima(const LinfKdTree& tree, const std::vector<double>& value) {
  const auto nodes = tree.nodes();
  const auto order = tree.order();
  std::vector<double> out(nodes.size(), -kInf);
  for (std::size_t k = nodes.size(); k-- > 0;) {
    const auto& node = nodes[k];
    if (node.left < 0) {
      for (std::uint32_t s = node.begin; s < node.end; ++s) out[k] = std::max(out[k], value[order[s]]);
    } else {
      out[k] = std::max(out[node.left], out[node.right]);
    }
  }
  return out;
}

// Visits every point j of the tree for which visit may matter: nodes are skipped when
// power(box distance) >= bound[node] - offset.
template <class Visit>
void pruned_search(const LinfKdTree& tree, const std::vector<double>& bound, PlanePoint q, double offset,
                   Power power, std::vector<std::int32_t>& stack, Visit visit) {
  const auto nodes = tree.nodes();
  const auto order = tree.order();
  if (nodes.empty()) return;
  stack.clear();
  stack.push_back(0);
  while (!stack.empty()) {
    const std::int32_t id = stack.back();
    stack.pop_back();
    const double room = bound[id] - offset;
    if (!(room > 0)) continue;
    const auto& node = nodes[id];
    if (power(tree.box_distance(node, q)) >= room) continue;
    if (node.left >= 0) {
      stack.push_back(node.right);
      stack.push_back(node.left);
      continue;
    }
    for (std::uint32_t s = node.begin; s < node.end; ++s) visit(order[s]);
  }
}

DistanceResult infinite_result(std::string reason) {
  DistanceResult r;
  r.value = r.lower = r.upper = kInf;
  r.infinite = true;
  r.reason = std::move(reason);
  return r;
}

DistanceResult exact_result(double value) {
  DistanceResult r;
  r.value = r.lower = r.upper = value;
  return r;
}

bool same_points(std::vector<PlanePoint> a, std::vector<PlanePoint> b) {
  if (a.size() != b.size()) return false;
  const auto less = [](PlanePoint p, PlanePoint r) { return p.x != r.x ? p.x < r.x : p.y < r.y; };
  std::sort(a.begin(), a.end(), less);
  std::sort(b.begin(), b.end(), less);
  return a == b;
}

}  // namespace

DistanceResult wasserstein_distance(const Diagram& a, const Diagram& b, const WassersteinParams& params,
                                    WassersteinStats* stats) {
  if (!std::isfinite(params.q) || params.q < 1)
    throw std::invalid_argument("wasserstein: q must be finite and >= 1 (use the bottleneck for q = inf)");
  if (!std::isfinite(params.delta) || params.delta < 0)
    throw std::invalid_argument("wasserstein: delta must be finite and >= 0");
  WassersteinStats local_stats;
  WassersteinStats& st = stats ? *stats : local_stats;
  st = {};
  const ConventionView va = apply_convention(a, params.essential), vb = apply_convention(b, params.essential);
  if (params.essential == EssentialConvention::separate) {
    if (std::string why = essential_count_mismatch(va, vb); !why.empty()) return infinite_result(std::move(why));
  }

  // Rescale by a power of two at or above the largest distance that can matter, so that the
  // q-th powers of the relevant costs lie in [0, 2] whatever the units.
  double top = 0;
  for (const auto* v : {&va, &vb})
    for (const PlanePoint p : v->points) top = std::max(top, std::fabs(p.x - p.y) / 2);
  for (std::size_t k = 0; k < va.essential_births.size(); ++k)
    top = std::max(top, std::fabs(va.essential_births[k] - vb.essential_births[k]));
  if (top == 0) return exact_result(0);
  if (va.essential_births == vb.essential_births && same_points(va.points, vb.points)) return exact_result(0);
  int exponent = 0;
  std::frexp(top, &exponent);
  const double scale = std::ldexp(1.0, exponent), inverse = std::ldexp(1.0, -exponent);
  const Power power{params.q};

  double essential_cost = 0;
  for (std::size_t k = 0; k < va.essential_births.size(); ++k)
    essential_cost += power(std::fabs(va.essential_births[k] - vb.essential_births[k]) * inverse);

  std::vector<PlanePoint> pa, pb;
  std::vector<double> da, db;
  for (const PlanePoint p : va.points) pa.push_back({p.x * inverse, p.y * inverse});
  for (const PlanePoint p : vb.points) pb.push_back({p.x * inverse, p.y * inverse});
  for (const PlanePoint p : pa) da.push_back(power(std::fabs(p.x - p.y) / 2));
  for (const PlanePoint p : pb) db.push_back(power(std::fabs(p.x - p.y) / 2));
  const auto finish = [&](double cost) { return std::pow(cost, 1 / params.q) * scale; };

  if (pa.empty() || pb.empty()) {
    double cost = essential_cost;
    for (const double d : da) cost += d;
    for (const double d : db) cost += d;
    return exact_result(finish(cost));
  }

  const LinfKdTree tree_a(pa), tree_b(pb);
  const std::size_t k = params.neighbours ? params.neighbours : (params.delta > 0 ? 3 : 6);
  std::vector<DiagonalFlow::Arc> arcs;
  std::vector<std::uint32_t> nn;
  const auto candidate = [&](std::uint32_t i, std::uint32_t j) {
    const double c = power(linf_distance(pa[i], pb[j]));
    if (c < da[i] + db[j]) arcs.push_back({i, j, c});  // other pairs never beat both going to the diagonal
  };
  for (std::uint32_t i = 0; i < pa.size(); ++i) {
    tree_b.nearest(pa[i], k, nn, i);
    for (const std::uint32_t j : nn) candidate(i, j);
  }
  for (std::uint32_t j = 0; j < pb.size(); ++j) {
    tree_a.nearest(pb[j], k, nn, 0x100000000ULL + j);
    for (const std::uint32_t i : nn) candidate(i, j);
  }
  st.arcs = arcs.size();
  DiagonalFlow flow(da, db, std::move(arcs));

  std::vector<std::int32_t> stack;
  DistanceResult result;
  for (std::size_t round = 0;; ++round) {
    flow.solve();
    st.certificate_rounds = round + 1;
    const auto pi = flow.potentials();
    const std::size_t n = pa.size(), m = pb.size();
    std::vector<double> pi_b(pi.begin() + static_cast<std::ptrdiff_t>(n), pi.begin() + static_cast<std::ptrdiff_t>(n + m));
    const std::vector<double> bound = node_maxima(tree_b, pi_b);
    // A pair (a_i, b_j) violates optimality when c_ij + pi(a_i) - pi(b_j) < 0; every negative
    // reduced cost also lowers the dual bound by its size (arc capacity 1).
    std::vector<DiagonalFlow::Arc> violations;
    std::vector<std::pair<double, DiagonalFlow::Arc>> row_violations;
    double negative = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const double p = pi[i];
      pruned_search(tree_b, bound, pa[i], p, power, stack, [&](std::uint32_t j) {
        const double c = power(linf_distance(pa[i], pb[j]));
        const double rc = c + p - pi_b[j];
        if (!(rc < 0)) return;
        negative -= rc;
        const double tolerance = 64 * DBL_EPSILON * (c + std::fabs(p) + std::fabs(pi_b[j]));
        if (rc < -tolerance && !flow.has_arc(i, j)) row_violations.push_back({rc, {i, j, c}});
      });
      // Only the worst few per row: the others mostly vanish once the row is re-solved, and
      // adding all of them floods degenerate (near one-dimensional) diagrams with arcs.
      const std::size_t keep = std::min(row_violations.size(), kViolationsPerRow);
      std::partial_sort(row_violations.begin(), row_violations.begin() + static_cast<std::ptrdiff_t>(keep),
                        row_violations.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (std::size_t v = 0; v < keep; ++v) violations.push_back(row_violations[v].second);
      row_violations.clear();
    }
    const double primal = flow.primal_cost() + essential_cost;
    if (violations.empty()) {
      result = exact_result(finish(primal));
      break;
    }
    if (params.delta > 0) {
      double magnitude = 0;
      for (const double v : pi) magnitude += std::fabs(v);
      magnitude += static_cast<double>(n) * std::fabs(pi[n + m + 1]) + static_cast<double>(m) * std::fabs(pi[n + m]);
      const double dual = flow.dual_without_pairs() - negative + essential_cost - 64 * DBL_EPSILON * magnitude;
      const double lower = dual > 0 ? finish(std::min(dual, primal)) : 0, upper = finish(primal);
      if (upper - lower <= params.delta * lower) {
        result.value = result.upper = upper;
        result.lower = lower;
        result.exact = false;
        break;
      }
    }
    if (round + 1 >= kMaxRounds) {
      // Give up on sparsity: every pair that can beat the diagonal, then one last exact solve.
      std::vector<double> db_max = node_maxima(tree_b, db);
      for (std::uint32_t i = 0; i < n; ++i)
        pruned_search(tree_b, db_max, pa[i], -da[i], power, stack, [&](std::uint32_t j) {
          const double c = power(linf_distance(pa[i], pb[j]));
          if (c < da[i] + db[j]) violations.push_back({i, j, c});
        });
      st.arcs_added += violations.size();
      flow.add_arcs(std::move(violations));
      flow.solve();
      result = exact_result(finish(flow.primal_cost() + essential_cost));
      break;
    }
    st.arcs_added += violations.size();
    flow.add_arcs(std::move(violations));
  }
  st.augmentations = flow.augmentations();
  return result;
}

}  // namespace fnet
