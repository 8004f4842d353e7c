// Checkpoints: the whole state of a run in one binary file (native byte order, this build's
// layout), so that a resumed run continues bit for bit as if never stopped: every kinematic
// level, the forces, the Verlet list with its springs and its build reference, and the clock.
// Written to a temporary file and renamed, so a kill leaves the previous checkpoint intact.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>

#include "server/dem/run_state.hpp"

namespace fnet::sim {

class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `ensemble` is written last, so that checkpoints written before it existed still load (as none).
void save_checkpoint(const Simulation& s, const std::string& run_id, const std::filesystem::path& path,
                     const std::string& ensemble = "");

struct Restored {
  Simulation simulation;
  std::string run_id;
  std::string ensemble;  // empty: none, or a checkpoint from before ensembles
};
Restored load_checkpoint(const std::filesystem::path& path);

}  // namespace fnet::sim
