// The registry's side of a subscription, as the Asio chat server keeps the room apart from its
// sessions: the registry knows a subscriber only by this interface. A series subscription of a
// TCP client is one implementation, an ensemble's curve another; a new transport adds its own
// without a change to the registry.
//
// The registry delivers the points it commits after releasing its lock, so that no subscriber's
// work (building JSON, sending) runs under the lock every run shares; it reads them from the
// committed frames a page at a time, as fast as the subscriber has room (ready), so a subscriber
// that does not keep up costs no memory and never delays the others.
#pragma once

#include <cstdint>
#include <functional>
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
  // Whether it has room for a page of points now; if not, it calls `resume` (from any thread, off
  // the registry's lock) once it has, and the delivery goes on from where it stopped.
  virtual bool ready(const std::function<void()>& resume) {
    (void)resume;
    return true;
  }
};

}  // namespace fnet::server
