// Verlet list with a skin, built from a cell grid, carrying the contact history.
//
// A half list in CSR form: the pairs of grain i are [offset[i], offset[i+1]), each with a partner
// j > i (a grain) or j >= n (a wall particle); wall particles own no pairs. A pair is listed when
// its surfaces are closer than `skin`; the list stays valid while no body has moved more than
// skin / 2 since the build. Per pair the list keeps the Cundall–Strack spring ξ and the forces of
// the last evaluation; a rebuild carries ξ over to the pairs that survive.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace fnet::sim {

struct NeighbourList {
  std::vector<std::uint32_t> offset;  // n + 1
  std::vector<std::uint32_t> partner;
  std::vector<double> hx, hy;          // tangential spring ξ (zero while not touching)
  std::vector<double> meff;            // reduced mass m̄ of the pair (fixed; computed at the build)
  std::vector<double> fn, ft2;         // signed normal force and |F_t|² of the last evaluation
  std::vector<std::uint8_t> touching;  // overlap > 0 at the last evaluation

  // The threaded force evaluation (contact_forces.hpp): per pair the force on its grain and the
  // torque term of the last evaluation, and the transposed list (per body, the pairs where it is
  // the partner, in increasing pair order: the order in which the serial loop adds them).
  std::vector<double> cfx, cfy, ctz;
  std::vector<std::uint32_t> in_offset, in_pair;

  std::vector<double> x_build, y_build;  // grain positions at the last build
  double wall_offset_build = 0;
  double skin = 0;
  std::int64_t builds = 0;

  // Cell grid over the whole walled domain (the box only shrinks).
  double grid_lo = 0, cell = 1;
  std::uint32_t cells_per_side = 1;

  // Scratch kept between builds so that a rebuild does not allocate once capacities settle.
  std::vector<std::uint32_t> cell_start, cell_bodies, body_cell;
  std::vector<std::uint32_t> old_offset, old_partner;
  std::vector<double> old_hx, old_hy;
};

// Sets up the grid for bodies within [lo, hi]² whose diameters are at most max_diameter.
void setup_grid(NeighbourList& list, double lo, double hi, double max_diameter, double skin);

// Rebuilds the list from the positions of all bodies (grains first, n of them), keeping ξ of
// pairs present before and after. inv_mass gives m̄ (0 for walls). Throws std::runtime_error if a
// body left the grid or is not finite.
// Derives in_offset and in_pair from offset and partner (rebuild does it; so must whoever loads a
// list saved without them, such as a checkpoint).
void index_partners(NeighbourList& list, std::size_t bodies);

void rebuild(NeighbourList& list, std::span<const double> x, std::span<const double> y, std::span<const double> radius,
             std::span<const double> inv_mass, std::size_t n, double wall_offset);

}  // namespace fnet::sim
