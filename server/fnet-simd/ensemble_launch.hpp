// fnet-simd --ensemble NAME --seeds S: plans every realization (all command-line problems, each
// seed's start and any checkpoint against this command's parameters are checked before the first
// child starts), then runs them as child fnet-simd processes (ensemble_runner.hpp).
#pragma once

#include <atomic>

#include "server/fnet-simd/simd_options.hpp"

namespace fnet::sim {

// The exit code: 0, 1 when a realization failed, 130 when stopped.
int run_as_ensemble(const SimdOptions& options, std::atomic<bool>& stop);

}  // namespace fnet::sim
