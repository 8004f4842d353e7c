// Every tuning constant of the Wasserstein solver (diagonal_flow.hpp), with the rule it sets. The
// defaults are the solver's; the measurements behind them are in tests/bench/notes.md. None of
// them decides exactness: an exact solve ends certified over every pair whatever they are.
#pragma once

#include <cstddef>
#include <cstdint>

namespace fnet {

struct DiagonalFlowParams {
  // Which solve. The staged solve (candidates, then certify-and-repair rounds) is taken for q = 1
  // and 2 when n + m <= 2 * staged_max_points, and above that for q = 1 on a common death line
  // only; every other case is solved by the complete-graph searches alone. Other q never stage:
  // their costs are capped (ArcPower::kCap) and potentials near the cap leave the check's
  // tolerance meaningless.
  std::size_t staged_max_points = 8000;
  // The line start is tried (q = 1, 2, any size) when at least this share of all points lies on
  // the death line that most of them share (share_on_common_line).
  double line_share = 0.5;

  // The sorted-birth programme's first half-width, in ranks (sorted_birth_seed.hpp). On a common
  // line it doubles until the programme's path keeps off the band's edges or the band holds every
  // column.
  std::uint32_t band = 32;
  // ... or until the next band would pass this many cells (rows times band width).
  std::size_t max_band_cells = std::size_t{1} << 26;

  // Candidates: each point's this many nearest neighbours on the other side; also the choices the
  // row reduction looks at, so that its tight arcs are candidates.
  std::size_t nearest = 4;

  // The line start's certification rounds: each checks every pair, adds the violated arcs to the
  // candidates and lowers the potentials again. Past this many rounds the line start is given up.
  std::size_t line_rounds = 64;
  // Violated arcs added per violating row in a line round: a line row may need many long-range
  // arcs at once.
  std::size_t line_top_arcs = 16;
  // Label-correcting sweeps per lowering: a lowering that has not settled after this many has met
  // a negative cycle (the band cut the programme's optimum off), and the line start is given up.
  std::size_t max_sweeps = 200;

  // Violated arcs added per violating row in a repair round of the staged solve (the row is then
  // freed and routed again on the candidates).
  std::size_t repair_top_arcs = 3;
  // Past this many certification rounds the staged solve repairs the rows once more and the
  // complete-graph searches finish.
  std::size_t max_rounds = 24;
  // ... as they do once this few violating rows or fewer are left: a round costs a check of every
  // pair, more than complete-graph searches for a couple of rows. The line start repairs its
  // last rows likewise once its lowering stalls on this few.
  std::size_t few_rows = 2;

  // An approximate solve (accept ratio > 1) compares its bounds every 1 + (n + m) / check_spacing
  // augmentations: often enough to stop near the first moment it could, rarely enough that the
  // checks (each a tree query per free row) stay a small part of the solve.
  std::size_t check_spacing = 256;

  // A pair arc counts as violated when its reduced cost is below -violation_tolerance times the
  // size of its terms (cost and both potentials: rounding is relative to them, and costs can be
  // 1e-20 of the potentials); smaller violations are only charged to the dual bound.
  double violation_tolerance = 1e-14;
  // The sweeps ignore improvements below this, relative to the terms (both labels and the arc's
  // cost, whose rounding it is): under q = 1 whole families of cycles cost exactly 0, and their
  // rounded sums would lower labels forever. Below violation_tolerance, so that what the sweeps
  // leave is never flagged by the check.
  double sweep_tolerance = 0x1p-50;
  // The dual bound is void when HA -> HB, unbounded, has a reduced cost below -hub_tolerance times
  // the sum of the hubs' potentials' magnitudes.
  double hub_tolerance = 1e-12;
};

}  // namespace fnet
