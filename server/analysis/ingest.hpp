// The DDS side of fnet-server: one thread takes run announcements and frames and hands them to
// the registry. Memory stays bounded: it takes frames only while fewer than max_in_flight are
// being analyzed, and the DDS reader holds at most max_in_flight more (its resource limit), after
// which the simulation's writer waits — back-pressure instead of an unbounded buffer.
#pragma once

#include <atomic>
#include <cstddef>
#include <thread>

#include <dds/dds.h>

#include "server/analysis/run_registry.hpp"

namespace fnet::server {

struct IngestOptions {
  dds_domainid_t domain = DDS_DOMAIN_DEFAULT;
  std::size_t max_in_flight = 64;
};

class Ingest {
 public:
  Ingest(Registry& registry, IngestOptions options);
  ~Ingest();  // stops and joins the thread
  void stop();

 private:
  void run();

  Registry& registry_;
  IngestOptions options_;
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace fnet::server
