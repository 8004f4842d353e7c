// fnet-simd as one run: the start (or the checkpoint it resumes), the sinks its options select,
// the protocol, and the end (subscribers served, the checkpoint of a stopped run).
#pragma once

#include <atomic>

#include "server/fnet-simd/simd_options.hpp"

namespace fnet::sim {

// The exit code: 0; 3 when DDS was the only output and no subscriber took a frame; 130 stopped.
int run_single(SimdOptions options, const std::atomic<bool>& stop);

}  // namespace fnet::sim
