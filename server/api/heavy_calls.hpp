// The heavy calls of each connection on their way to the analysis threads: at most
// `per_connection` of one connection's run at once and the rest wait, in order, in that
// connection's own queue, so that one client's batch of heavy calls holds at most that many of
// the threads the frames' analysis and every other client share.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>

namespace fnet::server {

class HeavyCalls : public std::enable_shared_from_this<HeavyCalls> {
 public:
  using Offload = std::function<void(std::function<void()>)>;
  HeavyCalls(Offload offload, std::size_t per_connection);

  // Runs `work` through the offload now, or once one of the connection's heavy calls has ended.
  void submit(std::uint64_t connection, std::function<void()> work);
  // Heavy calls waiting (not yet handed to the offload), over every connection.
  std::size_t waiting() const;

 private:
  void start(std::uint64_t connection, std::function<void()> work);
  void ended(std::uint64_t connection);

  struct Queue {
    std::size_t running = 0;
    std::deque<std::function<void()>> waiting;
  };
  const Offload offload_;
  const std::size_t per_connection_;
  mutable std::mutex mutex_;
  std::map<std::uint64_t, Queue> queues_;  // connections with a heavy call running or waiting
  std::size_t waiting_ = 0;
};

}  // namespace fnet::server
