// A run announcement comes from outside (any DDS writer): before the registry records one, its
// names, numbers and parameters are checked; one that fails is refused whole, with a reason naming
// the run, and the run's frames are analyzed as those of a run not announced.
#pragma once

#include <cstddef>
#include <string>

#include "common/run/run_frame.hpp"

namespace fnet::server {

// config_json: at most the IDL's bound (string<4096>) and nested at most this deep, so that
// neither reading it nor serving it (the API writes it out as JSON) costs more than a small
// document does.
inline constexpr std::size_t kMaxConfigBytes = 4096;
inline constexpr std::size_t kMaxConfigDepth = 32;

// Empty when `info` may be recorded: its run id and ensemble are names (run_names.hpp), its
// numbers finite, its config_json empty or one JSON value within the bounds above; else why not.
std::string announcement_problem(const RunInfo& info);

}  // namespace fnet::server
