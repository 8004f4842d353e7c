// The DDS side of fnet-server: one thread takes run announcements and frames and hands them to
// the registry. Memory stays bounded in frames and in bytes: it takes frames only while fewer than
// max_in_flight, holding less than max_in_flight_bytes, are being analyzed (the frame that reaches
// the bytes is the last taken), and the DDS reader holds at most reader_frames() more (its
// resource limit), after which the simulation's writer waits — back-pressure instead of an
// unbounded buffer. A frame above max_frame_bytes is refused unread, rejected in its run.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include <dds/dds.h>

#include "common/transport/frame_transport.hpp"
#include "server/registry/run_registry.hpp"

namespace fnet::server {

struct IngestOptions {
  dds_domainid_t domain = DDS_DOMAIN_DEFAULT;
  std::size_t max_in_flight = 64;
  std::size_t max_in_flight_bytes = std::size_t{512} << 20;
  std::size_t max_frame_bytes = std::size_t{64} << 20;
};

// The DDS reader's limit: as many of the largest frames as max_in_flight_bytes holds (at least
// one), at most max_in_flight. So the reader holds at most about max_in_flight_bytes too.
std::size_t reader_frames(const IngestOptions& options);

class Ingest {
 public:
  // Creates the DDS participant and readers here, on the caller's thread, so that a server that
  // cannot subscribe (a broken CYCLONEDDS_URI, say) fails at start instead of serving nothing;
  // throws std::runtime_error naming the DDS problem.
  Ingest(Registry& registry, IngestOptions options);
  ~Ingest();  // stops and joins the thread
  void stop();

  // "running", or "stopped: <reason>" once the thread ended on an error (server.status shows it).
  std::string state() const;
  // Tells the run's publishers how far it is in the store (fnet_RunStatus); thread-safe.
  void publish_status(const RunStatus& status) { subscriber_->publish(status); }

 private:
  void run();

  Registry& registry_;
  IngestOptions options_;
  std::unique_ptr<dds::FrameSubscriber> subscriber_;
  std::atomic<bool> stopping_{false};
  mutable std::mutex mutex_;
  std::string state_ = "running";
  std::thread thread_;
};

}  // namespace fnet::server
