// One frame from a LAMMPS per-atom snapshot and the local snapshot of its pair forces (same
// TIMESTEP): grains, grain-grain contacts, contacts with wall atoms, ρ and Z, as fnet-simd's frames
// have them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "common/run/run_frame.hpp"
#include "server/sources/lammps_columns.hpp"
#include "server/sources/lammps_dump.hpp"

namespace fnet::sources {

// Grain indices by atom id: the first frame's atoms that are not walls, sorted by id, numbered
// from 0; every frame uses the same numbering.
struct GrainIds {
  std::vector<std::uint64_t> ids;  // by grain index
  std::unordered_map<std::uint64_t, std::uint32_t> index;
};

// How ρ's area was obtained: the periodic box, the interior the wall atoms enclose, or the box.
enum class DensityRegion { periodic_box, walls, box };
const char* density_region_name(DensityRegion region);

struct LammpsFrame {
  RunFrame run;
  // The force on contact.i of each of run.frame.contacts, and on the grain of each of
  // run.wall_contacts; both empty when the pair dump gives magnitudes only.
  std::vector<std::array<double, 2>> contact_forces, wall_forces;
  DensityRegion region = DensityRegion::box;
  std::string where;  // "ATOMS_FILE:LINE" of the per-atom snapshot
};

// The grain numbering of a first per-atom snapshot. Throws std::runtime_error "FILE:LINE: what".
GrainIds grain_ids(const DumpSnapshot& atoms, const std::vector<int>& wall_types);

// Frame `index` of a run. Atoms: columns id, type (when there are wall types), x y (or xu yu, or
// the scaled xs ys / xsu ysu), radius or diameter; a z column must be constant (2D). Pairs: the
// columns `columns` names. A pair listed twice (LAMMPS with newton off) counts once; pairs of two
// walls are dropped. ρ = Σ π r² of the grains over the region's area: the box on an axis where it
// is periodic, elsewhere the inner surfaces of the wall atoms beyond the grains (the box's bounds
// where there are none). Z = 2 × grain-grain contacts with F_n > 0 / grains. Throws
// std::runtime_error "FILE:LINE: what" for a row at fault: a column missing, a value that is not a
// number, an id not among the grains or walls, a grain of the first frame missing.
LammpsFrame lammps_frame(const DumpSnapshot& atoms, const DumpSnapshot& pairs, const GrainIds& grains,
                         const PairColumns& columns, const std::vector<int>& wall_types, std::uint32_t index);

}  // namespace fnet::sources
