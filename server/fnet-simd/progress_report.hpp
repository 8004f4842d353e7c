// What fnet-simd writes on stderr while it runs: progress lines and the relaxation's outcome.
#pragma once

#include "server/dem/protocol.hpp"

namespace fnet::sim {

void print_progress(const Progress& p);
// Once per run, also with --quiet.
void print_relaxation(const Relaxation& r);

}  // namespace fnet::sim
