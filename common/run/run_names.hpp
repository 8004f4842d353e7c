// The names a run and an ensemble may take (they name files: RUN.h5 in a data directory). fnet-simd
// checks them before it announces a run; fnet-server and fnet-analyze before they store one.
#pragma once

#include <string>

namespace fnet {

// Empty when `name` is acceptable as a run id or ensemble name ([A-Za-z0-9._-]{1,64}, not . or
// ..), else why not, calling it `what`.
std::string name_problem(const std::string& name, const std::string& what);
std::string run_id_problem(const std::string& run_id);

}  // namespace fnet
