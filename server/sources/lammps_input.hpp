// What every reading of LAMMPS dumps shares, whether the run is read whole, followed while it is
// written, or one frame picked from it: the flags' values, the snapshots of a pattern, the
// pairing of per-atom and pair snapshots by TIMESTEP, and a frame made and checked.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "server/sources/lammps_dimension.hpp"
#include "server/sources/lammps_frame.hpp"
#include "server/sources/source_kind.hpp"

namespace fnet::sources {

struct LammpsOptions {
  std::string atoms, pairs;  // the patterns
  std::vector<int> wall_types;
  PairColumns columns;
  double balance_tolerance = 0;  // 0: no force-balance check
  // --rho log:PATH:COLUMN: ρ of each frame is COLUMN of the log's thermo row of its TIMESTEP
  // (lammps_thermo.hpp); --rho column:NAME: the per-atom dump's column NAME, one value on every
  // row; empty: ρ from the dumps (lammps_frame.hpp).
  std::string rho;
  std::map<std::uint64_t, double> rho_by_step;
  std::string rho_column;
  // --dimension, or the dimension the log (--lammps-log) names; none: the first frame decides
  // (lammps_dimension.hpp).
  std::optional<RunDimension> dimension;
};

// The flags of every kind that reads LAMMPS dumps: --lammps-atoms and --lammps-pairs, whose values
// are called `value_name` in the usage line, --wall-types, --columns, --check-balance, --rho,
// --dimension, --lammps-log.
std::vector<SourceFlag> lammps_flags(const std::string& value_name);

// The flags --lammps-atoms, --lammps-pairs, --wall-types, --columns, --check-balance, --rho and
// --dimension as given (the log --rho names is read here, and so is --lammps-log's for the
// dimension unless the run is followed); usage errors (boost::program_options::error) name the
// flag.
LammpsOptions lammps_options(const SourceArguments& given);

// The value of an optional flag, empty when not given.
std::string flag_value(const SourceArguments& given, const std::string& name);

// Every snapshot the pattern's files hold, by TIMESTEP; a TIMESTEP twice is an error naming both.
std::vector<DumpSnapshot> snapshots(const std::string& pattern, DumpKind kind);

// Throws when a snapshot of one kind has no partner of the same TIMESTEP in the other; both
// sorted by TIMESTEP.
void require_paired(const std::vector<DumpSnapshot>& atoms, const std::vector<DumpSnapshot>& pairs,
                    const LammpsOptions& options);

// The run's dimension: the options' when they know it, else the first per-atom snapshot's
// (lammps_dimension.hpp).
RunDimension run_dimension(const LammpsOptions& options, const DumpSnapshot& first_atoms);

// Frame `index` of a run, with the force-balance check the options ask for, and ρ from the log
// where they name one (a TIMESTEP without its thermo row throws).
LammpsFrame checked_frame(const DumpSnapshot& atoms, const DumpSnapshot& pairs, const GrainIds& grains,
                          const RunDimension& dimension, const LammpsOptions& options, std::uint32_t index);

// The announcement's config_json: the dumps, the dimension and how ρ's region was obtained.
std::string lammps_config(const LammpsOptions& options, const RunDimension& dimension, DensityRegion region);

}  // namespace fnet::sources
