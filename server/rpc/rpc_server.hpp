// Newline-delimited JSON-RPC 2.0 over TCP (Boost.Asio). One request per line, one response per
// line, matched by id (a heavy call may be answered after later ones); handlers may also push
// notifications to their session at any time, from any thread.
// Everything a client can make the server hold is bounded: line length, connections, bytes
// queued for a client that does not read (that client is dropped).
#pragma once

// Boost 1.74's asio/awaitable.hpp uses std::exchange without including <utility> (C++20).
#include <atomic>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <boost/asio.hpp>

#include "proto/json_rpc.hpp"
#include "server/rpc/peer.hpp"

namespace fnet::rpc {

struct ServerLimits {
  std::size_t max_line_bytes = 1 << 20;     // a longer request gets an error and the connection closes
  std::size_t max_connections = 256;        // beyond: an error line, then close
  std::size_t max_queued_bytes = 16 << 20;  // unread output beyond this drops the client
  std::size_t max_pending_calls = 32;       // calls of one connection unanswered at once; beyond, its input waits
};

// One TCP connection: newline-delimited requests in, responses and notifications out.
class Session final : public Peer, public std::enable_shared_from_this<Session> {
 public:
  Session(boost::asio::ip::tcp::socket socket, const ServerLimits& limits, const Handler& handler,
          std::function<void()> on_end);
  ~Session();

  void start();
  // Drops the client when its unread output exceeds max_queued_bytes.
  bool send(const json& message) override;
  std::uint64_t id() const override { return id_; }
  void on_close(std::function<void()> fn) override;

 private:
  void read_next();
  void handle_line(const std::string& line);
  void begin_call();
  void end_call();
  void write_next();
  void finish();
  void drain(const std::shared_ptr<boost::asio::steady_timer>& timer);
  void close();

  boost::asio::ip::tcp::socket socket_;
  boost::asio::strand<boost::asio::any_io_executor> strand_;
  boost::asio::streambuf input_;
  const ServerLimits& limits_;
  const Handler& handler_;
  std::function<void()> on_end_;
  std::mutex mutex_;  // guards the output queue and close callbacks (send() is called from any thread)
  std::deque<std::string> output_;
  std::size_t queued_bytes_ = 0;
  bool writing_ = false;
  bool close_when_flushed_ = false;
  std::size_t pending_calls_ = 0;  // requests (a batch counts once) whose answer is not yet queued
  bool read_paused_ = false;       // reading waits for a call to end
  std::vector<std::function<void()>> close_callbacks_;
  std::atomic<bool> closed_{false};
  std::uint64_t id_;
};

class Server {
 public:
  // Binds to `address`:`port` (port 0 picks a free one) and starts accepting; throws
  // std::runtime_error naming address:port when it cannot (the port taken, say).
  Server(boost::asio::io_context& io, const std::string& address, unsigned short port, Handler handler,
         ServerLimits limits = {});
  unsigned short port() const;
  std::size_t connections() const { return connections_; }
  void stop();

 private:
  void accept_next();

  boost::asio::io_context& io_;
  boost::asio::ip::tcp::acceptor acceptor_;
  Handler handler_;
  ServerLimits limits_;
  std::atomic<std::size_t> connections_{0};
};

}  // namespace fnet::rpc
