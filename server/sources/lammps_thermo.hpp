// A column of the thermo output a LAMMPS log holds, by step: where a run reports a quantity fnet
// takes as it is (ρ, with --rho log:PATH:COLUMN) rather than working it out from the dumps.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

namespace fnet::sources {

// The values of thermo keyword `column` (as the header names it: "v_rho", "Volume") in every
// thermo block of the log, by step: the blocks are the rows between a header line that starts
// with "Step" and the run's "Loop time of"; a step printed twice (the last step of one run, the
// first of the next) keeps its first value. Throws std::runtime_error "LOG:LINE: what" for a
// row that is not numbers or whose step is not a whole number in [0, 2^63), and "LOG: ..." when
// no block holds the column.
std::map<std::uint64_t, double> thermo_column(const std::filesystem::path& log, const std::string& column);

}  // namespace fnet::sources
