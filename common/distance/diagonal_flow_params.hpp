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

  // The sorted-birth programme (sorted_birth_seed.hpp): its first half-width in ranks. On a
  // common line it doubles until the programme's path keeps off the band's edges, the band holds
  // every column, or the next band would pass max_band_cells cells (rows times band width).
  std::uint32_t band = 32;
  std::size_t max_band_cells = std::size_t{1} << 26;

  // Candidates: each point's `nearest` nearest neighbours on the other side (also the choices the
  // row reduction looks at, so its tight arcs are candidates).
  std::size_t nearest = 4;

  // The line start's certification: each round checks every pair, adds up to line_top_arcs of the
  // most violated arcs per violating row (a line row may need many long-range arcs at once) and
  // lowers the potentials again by label-correcting sweeps. More than line_rounds rounds, or a
  // lowering that has not settled after max_sweeps sweeps (a negative cycle: the band cut the
  // programme's optimum off), gives the line start up.
  std::size_t line_rounds = 64;
  std::size_t line_top_arcs = 16;
  std::size_t max_sweeps = 200;

  // Repair rounds of the staged solve: each check adds repair_top_arcs of the most violated arcs
  // per violating row, frees those rows and routes them again on the candidates. Past max_rounds
  // rounds, or with few_rows violating rows or fewer left, the rows are repaired once more and the
  // complete-graph searches finish (a round costs a check of every pair, more than complete-graph
  // searches for a couple of rows).
  std::size_t repair_top_arcs = 3;
  std::size_t max_rounds = 24;
  std::size_t few_rows = 2;

  // An approximate solve (accept ratio > 1) compares its bounds every 1 + (n + m) / check_spacing
  // augmentations: often enough to stop near the first moment it could, rarely enough that the
  // checks (each a tree query per free row) stay a small part of the solve.
  std::size_t check_spacing = 256;

  // Rounding. A pair arc counts as violated when its reduced cost is below -violation_tolerance
  // times the size of its terms (cost and both potentials: rounding is relative to them, and costs
  // can be 1e-20 of the potentials); smaller violations are only charged to the dual bound. The
  // sweeps ignore improvements below sweep_tolerance relative to the label (under q = 1 whole
  // families of cycles cost exactly 0, and their rounded sums would lower labels by an ulp
  // forever). The dual bound is void when HA -> HB, unbounded, has a reduced cost below
  // -hub_tolerance times the hubs' potentials.
  double violation_tolerance = 1e-14;
  double sweep_tolerance = 0x1p-50;
  double hub_tolerance = 1e-12;
};

}  // namespace fnet
