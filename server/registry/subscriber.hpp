// The registry's side of a subscription, as the Asio chat server keeps the room apart from its
// sessions: the registry knows a subscriber only by this interface. A series subscription of a
// TCP client is one implementation, an ensemble's curve another; a new transport adds its own
// without a change to the registry.
//
// Each subscription has an outbox: the registry queues the points it commits there under its
// lock (a copy, nothing more), and delivers them in commit order after releasing it, so that no
// subscriber's work (building JSON, sending) runs under the lock every run shares. An outbox that
// grows beyond RegistryLimits::max_pending_points (its subscriber does not keep up) ends the
// subscription, with the reason logged; the others are never delayed by it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "common/analysis/frame_analysis.hpp"
#include "common/run/run_frame.hpp"

namespace fnet::server {

struct SeriesPoint {
  std::string run_id;
  FrameHeader header;
  std::optional<std::uint32_t> previous;
  StepDistances distances;
  std::string ensemble;  // the run's, as announced (empty: none, or not announced yet)
};

class Subscriber {
 public:
  virtual ~Subscriber() = default;
  // One committed point of a run the subscription follows, in commit order; called on a registry
  // thread, never under the registry's lock, never twice at once for one subscription. Must not
  // block. Returns false when the subscriber is gone: the subscription ends.
  virtual bool deliver(std::uint64_t subscription, const SeriesPoint& point) = 0;
};

}  // namespace fnet::server
