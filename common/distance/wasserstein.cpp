#include "common/distance/wasserstein.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/distance/bottleneck.hpp"
#include "common/distance/diagonal_components.hpp"
#include "common/distance/diagonal_flow.hpp"
#include "common/distance/infinity.hpp"
#include "common/distance/repeated_points.hpp"
#include "common/distance/simplex_transport.hpp"
#include "common/distance/sorted_birth_seed.hpp"

namespace fnet {

namespace {

// q = 1 and 2 solve in coordinates rescaled by a power of two at or above the largest half
// persistence: the arcs that can matter then cost at most 2, nothing overflows, and the sum of an
// optimal matching is >= (d_B / scale)^q. Only when that sum falls below this could terms that
// underflowed (each off by < 2^-1022) count; then they are solved again like every other q.
constexpr double kSmallestSafeSum = 0x1p-900;

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

// From the sums of an exact or an accepted approximate solve: the value is the cost of the
// matching found (upper), the lower bound its certificate; exact when the two meet.
DistanceResult bounded_result(double upper, double lower, bool exact) {
  if (exact) return exact_result(upper);
  DistanceResult r;
  r.value = r.upper = upper;
  r.lower = std::min(lower, upper);
  r.exact = r.lower == r.upper;
  return r;
}

bool same_points(std::vector<PlanePoint> a, std::vector<PlanePoint> b) {
  if (a.size() != b.size()) return false;
  const auto less = [](PlanePoint p, PlanePoint r) { return p.x != r.x ? p.x < r.x : p.y < r.y; };
  std::sort(a.begin(), a.end(), less);
  std::sort(b.begin(), b.end(), less);
  return a == b;
}

// Sums of power(length) over an optimal matching of the two views, coordinates multiplied by
// `factor` first (a power of two: exact), and the dual bound on that sum.
struct Sums {
  double cost = 0, dual = 0;
};

// builder (optional) receives the matching found.
// accept_ratio >= 1: the solve may stop once its cost is within that ratio of its dual bound.
// Which solver for q = 1 and 2 (plain powers: never capped), measured (tests/bench/notes.md):
// - exact W1: the simplex (faster on every real diagram measured), except where at least
//   kLineOnlyShare of the points lie on one death line: there the simplex's start from the line's
//   matching pivots the line's long chains one link at a time (every point on the line, 100 000 a
//   side: 181 s against 0.45 s; 1 % off the line, 50 000: 23 s against 2.6 s), while real PD1s
//   (88-95 % on the line) stay faster on the simplex;
// - where at least half the points lie on one death line (floor PD1s), W2 and the approximate
//   mode: the shortest paths' line start (a long line's matching shifts along chains that one
//   augmenting path moves at once and the simplex only pivot by pivot);
// - elsewhere W2 and the approximate mode: the simplex while the largest diagonal component
//   (diagonal_components.hpp: the points that can ever be matched together) is at most
//   kSimplexComponent points, the shortest paths above (one frame's PD0 of 55 000 points: the
//   simplex over 60 s against 34 s; diagrams stacked along the diagonal: the simplex 1.7 s
//   against over 300 s).
constexpr std::size_t kSimplexComponent = 20000;
constexpr double kLineOnlyShare = 0.98;
// The relative gap between the simplex's matching and its dual bound beyond which an exact answer
// is taken from the shortest paths instead.
constexpr double kSimplexGap = 1e-11;

bool use_simplex(WassersteinSolver solver, std::span<const PlanePoint> a, std::span<const PlanePoint> b,
                 const ArcPower& power, double accept_ratio) {
  if (!power.is_plain() || solver == WassersteinSolver::shortest_paths) return false;
  if (solver == WassersteinSolver::network_simplex) return true;
  const double on_line = share_on_common_line(a, b);
  if (power.is_identity() && accept_ratio == 1) return on_line < kLineOnlyShare;
  if (on_line >= DiagonalFlowParams{}.line_share) return false;
  return largest_diagonal_component(a, b) <= kSimplexComponent;
}

// The matching a solved flow holds, into builder (if any): each point paired or sent to the diagonal.
void build_matching(const FlowState& flow, MatchingBuilder* builder) {
  if (!builder) return;
  for (std::uint32_t i = 0; i < flow.n; ++i) {
    if (flow.mate_a[i] >= 0)
      builder->pair(i, static_cast<std::uint32_t>(flow.mate_a[i]));
    else
      builder->a_to_diagonal(i);
  }
  for (std::uint32_t j = 0; j < flow.m; ++j)
    if (flow.mate_b[j] < 0) builder->b_to_diagonal(j);
}

Sums solve(const ConventionView& va, const ConventionView& vb, double factor, const ArcPower& power,
           double accept_ratio, WassersteinSolver solver, WassersteinStats& st, MatchingBuilder* builder) {
  if (builder) builder->essentials();
  double essential_cost = 0;
  for (std::size_t k = 0; k < va.essential_births.size(); ++k)
    essential_cost += power(std::fabs(va.essential_births[k] - vb.essential_births[k]) * factor);

  std::vector<PlanePoint> pa, pb;
  for (const PlanePoint p : va.points) pa.push_back({p.x * factor, p.y * factor});
  for (const PlanePoint p : vb.points) pb.push_back({p.x * factor, p.y * factor});
  if (pa.empty() || pb.empty()) {
    double cost = essential_cost;
    for (const auto* side : {&pa, &pb})
      for (const PlanePoint p : *side) cost += power(std::fabs(p.x - p.y) / 2);
    if (builder) builder->all_to_diagonal();
    return {cost, cost};  // the only matching there is
  }

  // Copies of points (ties everywhere): the transport between the distinct points, exact.
  if (power.is_plain() && solver != WassersteinSolver::shortest_paths && solve_distinct(pa, pb)) {
    const DistinctTransport t = distinct_transport(distinct_points(pa), distinct_points(pb), power, builder);
    st.network_simplex = true;
    st.pivots = t.pivots;
    st.candidate_arcs = t.pair_arcs;
    return {t.cost + essential_cost, std::max(0.0, t.dual + essential_cost)};
  }

  if (use_simplex(solver, pa, pb, power, accept_ratio)) {
    FlowState flow(pa, pb, power);
    PairOracle oracle(flow);
    const DiagonalFlowParams params;
    DualCertificate certificate(params);
    SimplexTransportStats sst;
    solve_by_simplex(flow, oracle, certificate, accept_ratio, {}, sst);
    // An exact solve not certified (the safety net of rounds hit), or certified only to rounding
    // that hides the problem (pair costs below the ulps of the potentials: a sentinel -1 beside
    // coordinates of 1e-10), has its answer from the shortest paths instead.
    const double primal = flow.primal_cost(), dual = certificate.dual_bound(flow);
    // A dual bound above the matching's cost is rounding too, in either mode.
    const bool sound = dual <= primal * (1 + kSimplexGap);
    if (sound &&
        (accept_ratio > 1 ? primal <= accept_ratio * dual : sst.certified && primal - dual <= kSimplexGap * primal)) {
      st.network_simplex = true;
      st.pivots = sst.pivots;
      st.pricing_rounds = sst.rounds;
      st.certify_rounds = sst.rounds;
      st.candidate_arcs = sst.pair_arcs;
      build_matching(flow, builder);
      return {primal + essential_cost, std::max(0.0, dual + essential_cost)};
    }
  }

  DiagonalFlow flow(pa, pb, power);
  // delta > 0: the matching in hand is the upper bound and the dual the lower; the solve stops
  // as soon as they are close enough (diagonal_flow.hpp).
  flow.solve(accept_ratio);
  st.augmentations = flow.augmentations();
  st.settled = flow.settled();
  st.boxes_opened = flow.boxes_opened();
  st.candidate_arcs = flow.candidate_arcs();
  st.certify_rounds = flow.certify_rounds();
  st.repaired_rows = flow.repaired_rows();
  st.completed = flow.finished_on_complete_graph();
  st.line_start = flow.started_on_line();
  build_matching(flow.state(), builder);
  return {flow.primal_cost() + essential_cost, std::max(0.0, flow.dual_bound() + essential_cost)};
}

}  // namespace

DistanceResult wasserstein_distance(const Diagram& a, const Diagram& b, const WassersteinParams& params,
                                    WassersteinStats* stats, DiagramMatching* matching) {
  if (!std::isfinite(params.q) || params.q < 1)
    throw std::invalid_argument("wasserstein: q must be finite and >= 1 (use the bottleneck for q = inf)");
  if (!std::isfinite(params.delta) || params.delta < 0)
    throw std::invalid_argument("wasserstein: delta must be finite and >= 0");
  WassersteinStats local_stats;
  WassersteinStats& st = stats ? *stats : local_stats;
  st = {};
  if (matching) *matching = {};
  ViewSources sa, sb;
  const ConventionView va = view_for(a, params.essential, matching ? &sa : nullptr),
                       vb = view_for(b, params.essential, matching ? &sb : nullptr);
  if (params.essential == EssentialConvention::separate) {
    if (std::string why = essential_count_mismatch(va, vb); !why.empty()) return infinite_result(std::move(why));
  }
  // A fresh builder per solve: the last solve's matching is the answer's.
  std::optional<MatchingBuilder> builder;
  const auto new_builder = [&]() -> MatchingBuilder* {
    if (!matching) return nullptr;
    builder.emplace(va, sa, a.size(), vb, sb, b.size());
    return &*builder;
  };
  const auto answer = [&](DistanceResult r) {
    if (matching) *matching = builder->finish();
    return r;
  };

  double top = 0;
  for (const auto* v : {&va, &vb})
    for (const PlanePoint p : v->points) top = std::max(top, std::fabs(p.x - p.y) / 2);
  for (std::size_t k = 0; k < va.essential_births.size(); ++k)
    top = std::max(top, std::fabs(va.essential_births[k] - vb.essential_births[k]));
  if (top == 0) {  // every point on the diagonal, equal essential births
    if (MatchingBuilder* m = new_builder()) m->essentials();
    return answer(exact_result(0));
  }
  if (va.essential_births == vb.essential_births && same_points(va.points, vb.points)) {
    if (matching) *matching = identity_matching(a, b, params.essential);
    return exact_result(0);
  }
  const double q = params.q;
  // upper <= (1 + delta) lower on the distances is cost <= (1 + delta)^q dual on the sums.
  const double accept = params.delta > 0 ? std::pow(1 + params.delta, q) : 1;
  // A sum of costs back to a distance, in the unit of length the costs were taken in.
  const auto root = [q](double sum, double unit) { return std::pow(sum, 1 / q) * unit; };

  if (q == 1 || q == 2) {  // the hot path (every frame's W1 and W2)
    int exponent = 0;
    std::frexp(top, &exponent);
    const double scale = std::ldexp(1.0, exponent), inverse = std::ldexp(1.0, -exponent);
    const Sums sums = solve(va, vb, inverse, ArcPower(q), accept, params.solver, st, new_builder());
    if (sums.cost >= kSmallestSafeSum) {
      st.dual_lower = root(sums.dual, scale);
      return answer(bounded_result(root(sums.cost, scale), st.dual_lower, params.delta == 0));
    }
  }
  // Lengths in units of the bottleneck distance d_B: every matching has a term >= 1 (d_B is the
  // least largest length over all matchings, computed from the same doubles), so the optimal sum
  // S is >= 1 and d_Wq = d_B S^(1/q) >= d_B exactly; the bottleneck matching's sum is at most its
  // number of terms N, so every term of an optimal matching is <= N and nothing it holds
  // overflows, while terms that underflow are below 1e-300 of S. Arcs longer than N^(1/q) d_B
  // are in no optimal matching, and ArcPower caps their costs.
  const double bottleneck = bottleneck_distance(a, b, {.essential = params.essential}).value;
  if (bottleneck == 0) {  // equal diagrams, caught above; no unit of length
    if (matching) *matching = identity_matching(a, b, params.essential);
    return exact_result(0);
  }
  const Sums sums = solve(va, vb, 1, ArcPower(q, bottleneck), accept, params.solver, st, new_builder());
  st.dual_lower = root(sums.dual, bottleneck);
  return answer(bounded_result(root(sums.cost, bottleneck), st.dual_lower, params.delta == 0));
}

}  // namespace fnet
