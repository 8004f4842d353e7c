// One frame from a LAMMPS per-atom snapshot and the local snapshot of its pair forces (same
// TIMESTEP): grains, grain-grain contacts, contacts with wall atoms, ρ and Z, as fnet-simd's frames
// have them; disks in 2D, spheres in 3D.
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

// A run's dimension, decided once for the run (lammps_input.hpp: how), and what decided it, which
// the messages about a frame that does not fit it name.
struct RunDimension {
  int value = 2;       // 2 or 3
  std::string origin;  // "--dimension", "LOG:LINE", "the first frame's z"
};

// Whether the snapshot has a z column (z, zu, zs or zsu) whose values differ from atom to atom (by
// more than 1e-9 of the box's largest side): the atoms of a 2D run (fix enforce2d) share one z.
bool z_varies(const DumpSnapshot& atoms);

// How ρ's region was obtained: the periodic box, the interior the wall atoms enclose, or the box.
enum class DensityRegion { periodic_box, walls, box };
const char* density_region_name(DensityRegion region);

struct LammpsFrame {
  RunFrame run;
  // The force on contact.i of each of run.frame.contacts, and on the grain of each of
  // run.wall_contacts; both empty when the pair dump gives magnitudes only.
  // In 2D, z is 0.
  std::vector<std::array<double, 3>> contact_forces, wall_forces;
  DensityRegion region = DensityRegion::box;
  std::string where;  // "ATOMS_FILE:LINE" of the per-atom snapshot
};

// The grain numbering of a first per-atom snapshot. Throws std::runtime_error "FILE:LINE: what".
GrainIds grain_ids(const DumpSnapshot& atoms, const std::vector<int>& wall_types);

// Frame `index` of a run of `dimension`. Atoms: columns id, type (when there are wall types), x y
// (or xu yu, or the scaled xs ys / xsu ysu), and z (zu, zs, zsu) in 3D, radius or diameter; in 2D a
// z column must hold one value (z_varies) and every grain's z is 0. Pairs: the columns `columns`
// names. A pair listed twice (LAMMPS with newton off) counts once; pairs of two walls are dropped.
// The line of centres is taken to the nearest image across a periodic side. ρ = the grains' area
// (Σ π r²) over the region's area in 2D, their volume (Σ 4/3 π r³) over the region's volume in 3D;
// on each axis of the region, the box where it is periodic, elsewhere the inner surfaces of the
// wall atoms beyond the grains and level with them (within the grains' extent on the other axes),
// the box's bounds where there are none. Z = 2 × grain-grain contacts with F_n > 0 / grains.
// Throws std::runtime_error "FILE:LINE: what" for a row at fault: a column missing, a value that
// is not a number, an id not among the grains or walls, a grain of the first frame missing, atoms
// at different z in a 2D run.
LammpsFrame lammps_frame(const DumpSnapshot& atoms, const DumpSnapshot& pairs, const GrainIds& grains,
                         const PairColumns& columns, const std::vector<int>& wall_types, const RunDimension& dimension,
                         std::uint32_t index);

}  // namespace fnet::sources
