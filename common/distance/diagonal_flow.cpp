#include "common/distance/diagonal_flow.hpp"

#include <algorithm>
#include <stdexcept>

#include "common/distance/approximate_stop.hpp"
#include "common/distance/greedy_start.hpp"
#include "common/distance/line_start.hpp"
#include "common/distance/work_deadline.hpp"

namespace fnet {

DiagonalFlow::DiagonalFlow(std::span<const PlanePoint> a, std::span<const PlanePoint> b, ArcPower power,
                           const DiagonalFlowParams& params)
    : params_(params),
      flow_(a, b, power),
      hubs_(flow_),
      oracle_(flow_),
      candidates_(flow_.n),
      certificate_(params_),
      paths_(flow_, hubs_, oracle_, candidates_) {}

void DiagonalFlow::start_greedy() {
  started_ = true;
  greedy_start(flow_, hubs_, oracle_, params_.nearest);
}

void DiagonalFlow::solve_complete(double accept_ratio) {
  if (!started_) start_greedy();
  paths_.set_sparse(false);
  completed_ = true;
  oracle_.recompute_all();
  augment_all(accept_ratio);
}

void DiagonalFlow::solve(double accept_ratio) {
  // Which stages run: the rule is DiagonalFlowParams's (staged_max_points, line_share).
  const std::uint32_t n = flow_.n, m = flow_.m;
  const ArcPower& power = flow_.power;
  const bool small = n + m <= 2 * params_.staged_max_points;
  const double line_share = n == 0 || m == 0 ? 0 : share_on_common_line(flow_.a, flow_.b);
  const bool on_line = power.is_plain() && line_share >= params_.line_share;
  const bool staged = power.is_plain() && (small || (power.is_identity() && on_line));
  if (n == 0 || m == 0 || !(staged || on_line)) {
    solve_complete();
    return;
  }
  const LineAlignment alignment = align_sorted_births(on_line);
  build_candidates(alignment, on_line);
  paths_.set_sparse(true);
  // A band that stopped growing before its path kept off its edges may still hold the optimum
  // (under q = 1 equal-cost paths abound): line_start() finds out.
  if (on_line && line_start(alignment, params_, flow_, hubs_, oracle_, candidates_, certificate_)) {
    started_ = on_line_ = true;
    // Certified over every pair: the off-line points, all that is left, are routed by searches on
    // the complete graph, which keep the certificate (the sparse searches would lose it on the
    // arcs into their flat-cost windows, and repair rounds would reroute many rows).
    certificate_.pairs_feasible();
    // Approximate: the line's points are matched optimally among themselves already; with the
    // loose points matched apart, optimally too, the matching may already be within the ratio.
    if (accept_ratio > 1 && finished_within(accept_ratio, [this](double target) {
          return match_free_points_apart(flow_, params_, target);
        }))
      return;
    solve_complete(accept_ratio);
    return;
  }
  if (!staged) {
    solve_complete();
    return;
  }
  if (on_line) add_nearest_candidates(std::nullopt);  // the line start failed: the line's points need them too
  start_greedy();
  augment_all();
  repair_rounds(accept_ratio);
}

LineAlignment DiagonalFlow::align_sorted_births(bool on_line) const {
  const std::uint32_t size = std::max(flow_.n, flow_.m);
  for (std::uint32_t width = params_.band;; width *= 2) {
    LineAlignment alignment = sorted_birth_alignment(
        flow_.a, flow_.b, flow_.da, flow_.db, [this](std::uint32_t i, std::uint32_t j) { return flow_.cost(i, j); },
        width);
    const std::size_t cells = static_cast<std::size_t>(size) * (4 * std::size_t{width} + 1);
    if (alignment.optimal || !on_line || width >= size || cells > params_.max_band_cells) return alignment;
  }
}

void DiagonalFlow::repair_rounds(double accept_ratio) {
  for (;;) {
    check_work_deadline_now();
    oracle_.recompute_all();
    certificate_.check_pairs(flow_, oracle_, params_.repair_top_arcs);
    if (certificate_.violations().empty()) break;  // certified on every pair
    // The pair penalty now counts every violation: dual_bound() is a valid lower bound.
    if (accept_ratio > 1 && dual_bound() > 0 && primal_cost() <= accept_ratio * dual_bound()) break;
    if (certificate_.rounds() > params_.max_rounds || certificate_.violations().size() <= params_.few_rows) {
      certificate_.repair(flow_, hubs_);
      certificate_.pairs_feasible();
      solve_complete();
      return;
    }
    candidates_.add(certificate_.violated_arcs());
    certificate_.repair(flow_, hubs_);
    augment_all();
  }
  paths_.set_sparse(false);
}

bool DiagonalFlow::augment_all(double accept_ratio) {
  // With accept_ratio > 1, every few augmentations: the flow with its free points sent to the
  // diagonal is a matching (primal_cost() counts them so), the potentials a dual bound.
  const std::size_t stride = 1 + (flow_.n + flow_.m) / params_.check_spacing;
  std::size_t since = 0;
  const auto good_enough = [&] {
    if (accept_ratio <= 1 || ++since < stride) return false;
    since = 0;
    return finished_within(accept_ratio,
                           [this](double target) { return complete_free_rows(flow_, candidates_, target); });
  };
  while (flow_.diagonal_supply_left() > 0) {
    if (!paths_.route(flow_.ha)) throw std::logic_error("diagonal flow: no augmenting path from the diagonal");
    if (good_enough()) return true;
  }
  for (std::uint32_t i = 0; i < flow_.n; ++i) {
    if (flow_.mate_a[i] != kNone) continue;
    if (!paths_.route(i)) throw std::logic_error("diagonal flow: no augmenting path");
    if (good_enough()) return true;
  }
  return false;
}

bool DiagonalFlow::finished_within(double accept_ratio, const std::function<bool(double)>& finish) {
  lower_free_rows(flow_, oracle_);
  const double lower = dual_bound();
  return lower > 0 && finish(accept_ratio * lower);
}

void DiagonalFlow::build_candidates(const LineAlignment& alignment, bool off_line_only) {
  candidates_ = CandidateArcs(flow_.n);
  candidates_.add(alignment_candidates(alignment));
  add_nearest_candidates(off_line_only ? std::optional<double>(alignment.line) : std::nullopt);
}

void DiagonalFlow::add_nearest_candidates(std::optional<double> skip_line) {
  // Each point's nearest neighbours on the other side, and again with that side brought to the
  // diagrams' scale (quantile_scale). The line start needs them for the off-line points only (its
  // line points have the programme's pairs, and the certification adds whatever else its
  // potentials need).
  PairArcs arcs = nearest_arcs(flow_.a, flow_.b, oracle_.tree_a(), oracle_.tree_b(), params_.nearest, 1, skip_line);
  if (!skip_line) {
    if (const double f = quantile_scale(flow_.a, flow_.b); f != 1) {
      const PairArcs scaled =
          nearest_arcs(flow_.a, flow_.b, oracle_.tree_a(), oracle_.tree_b(), params_.nearest, f, std::nullopt);
      arcs.insert(arcs.end(), scaled.begin(), scaled.end());
    }
  }
  candidates_.add(arcs);
}

}  // namespace fnet
