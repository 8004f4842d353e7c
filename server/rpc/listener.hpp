// Where a transport of the API listens: an acceptor whose connections are counted and bounded.
// Each accepted connection gets a strand of its own and a slot that it holds while it lives;
// beyond max_connections a connection is sent the transport's refusal and closed. When accepting
// fails (no file descriptor left: EMFILE, ENFILE; no memory) the listener waits before it tries
// again, longer each time up to a second, instead of retrying at once: the connections it serves
// keep the CPU, and it accepts again as soon as a descriptor is free at a retry.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>  // Boost 1.74's asio/awaitable.hpp uses std::exchange without including it

#include <boost/asio.hpp>

#include "server/rpc/connection.hpp"

namespace fnet::rpc {

class Listener {
 public:
  // Takes an accepted connection; the count goes down when the last copy of `slot` is released.
  using Start = std::function<void(boost::asio::ip::tcp::socket socket, Strand strand, std::shared_ptr<void> slot)>;

  // Binds to `address`:`port` (port 0 picks a free one) and starts accepting; throws
  // std::runtime_error naming address:port and the step that failed when it cannot (the port
  // taken, say).
  Listener(boost::asio::io_context& io, const std::string& address, unsigned short port, std::size_t max_connections,
           std::string refusal, Start start);
  unsigned short port() const;
  std::size_t connections() const { return *connections_; }
  void stop();

 private:
  void accept_next();
  void accept_later(const boost::system::error_code& why);

  boost::asio::io_context& io_;
  boost::asio::ip::tcp::acceptor acceptor_;
  const std::size_t max_connections_;
  const std::string refusal_;
  const Start start_;
  boost::asio::steady_timer retry_;
  std::chrono::milliseconds backoff_{0};  // 0 while accepting succeeds
  const std::shared_ptr<std::atomic<std::size_t>> connections_ = std::make_shared<std::atomic<std::size_t>>(0);
};

}  // namespace fnet::rpc
