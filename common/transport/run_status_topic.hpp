// The fnet_RunStatus topic: fnet-server's answer to the publishers of a run (proto/fnet.idl).
// Each server writes one instance per run it serves; a publisher reads the instances of its run
// written by the servers that read its frames, and ends only when each has the run's frames in
// its store, or has said why it cannot store them.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <dds/dds.h>

#include "common/run/run_status.hpp"

namespace fnet::dds {

inline constexpr const char* kRunStatusTopic = "fnet_RunStatus";

// fnet-server's side: reliable, transient-local, keep-last 1 per instance (a publisher that
// joins late reads the latest status of its run).
class RunStatusWriter {
 public:
  explicit RunStatusWriter(dds_entity_t participant);
  void write(const RunStatus& status);

 private:
  dds_entity_t writer_ = 0;
};

// One fnet-server that reads a publisher's frames, with its latest status of the publisher's run
// (none while it has not written one).
struct ServerStore {
  std::optional<RunStatus> status;
};

// The publisher's side.
class RunStatusReader {
 public:
  explicit RunStatusReader(dds_entity_t participant);
  // The servers among the readers matched with `frame_writer` (a reader whose participant also
  // writes fnet_RunStatus is a fnet-server's), each with its latest status of `run_id`. One run
  // per reader: the statuses of other runs are taken and dropped.
  std::vector<ServerStore> servers(dds_entity_t frame_writer, const std::string& run_id);

 private:
  dds_entity_t reader_ = 0;
  std::map<dds_instance_handle_t, RunStatus> latest_;  // of the run, by the writer that wrote it
};

// How a run's frames ended up in the stores of the servers that read them.
struct StoreOutcome {
  std::vector<std::string> faults;       // "fnet-server S: <reason> (it holds N frames of the run)"
  std::vector<std::string> unconfirmed;  // servers that had not stored the frames in time
};

// Polls `servers` (a RunStatusReader::servers call) until each server has settled every frame
// below `through` in its store, or reports a store fault, or `timeout` has passed. A server that
// reports a fault ends the wait: the fault is the answer while it lasts.
StoreOutcome wait_for_stores(const std::function<std::vector<ServerStore>()>& servers, const std::string& run_id,
                             std::uint32_t through, double timeout_seconds);

}  // namespace fnet::dds
