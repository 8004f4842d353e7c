// A LAMMPS run's dimension, decided once for the run before its first frame is made:
//   1. --dimension 2|3, when given;
//   2. else the `dimension` command the run's log echoes (--lammps-log LOG, a run read after it
//      finished: LAMMPS writes its log behind the dumps, so a run followed live does not use it);
//   3. else the first frame's per-atom dump: 3 when it has a z column whose values differ from atom
//      to atom, 2 when it has none or one value on every row (fix enforce2d keeps z as it was).
// Every frame is then held to it (lammps_frame.hpp): atoms at different z in a 2D run, or a 3D run
// without a z column, stop the command naming the row and what decided the dimension.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "server/sources/lammps_dump.hpp"
#include "server/sources/lammps_frame.hpp"

namespace fnet::sources {

// The value of --dimension: "2" or "3". Throws std::invalid_argument.
RunDimension dimension_flag(const std::string& text);

// The first `dimension N` command a LAMMPS log echoes (a line "dimension 2" or "dimension 3", a
// # comment after it allowed; "dimension ${d}" is followed by the line LAMMPS substituted), origin
// "LOG:LINE"; none when the log holds none (an input echoed with -echo none, or a log not yet
// flushed). Throws std::runtime_error "LOG: ..." for a log that cannot be read.
std::optional<RunDimension> logged_dimension(const std::filesystem::path& log);

// Rule 3 above, for the run's first per-atom snapshot.
RunDimension dimension_of_first_frame(const DumpSnapshot& atoms);

}  // namespace fnet::sources
