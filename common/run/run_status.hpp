// What fnet-server tells the publishers of a run about its store (DDS topic fnet_RunStatus,
// proto/fnet.idl): how far the run is settled in the store, and why the store does not take
// writes when it does not.
#pragma once

#include <cstdint>
#include <string>

namespace fnet {

struct RunStatus {
  std::string run_id;
  std::string server;                 // which fnet-server: host, process id and data directory
  std::uint32_t settled_through = 0;  // every frame index below it is in the store (or was skipped)
  std::uint32_t stored = 0;           // frames the store holds
  std::string store_fault;            // empty while the store takes writes
  bool operator==(const RunStatus&) const = default;
};

}  // namespace fnet
